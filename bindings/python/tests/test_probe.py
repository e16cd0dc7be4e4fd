"""zshift.probe on a real OpenGL context: a headless EGL context made here through ctypes (Mesa's
surfaceless platform, no window), EGL's eglGetProcAddress as the loader. Fails, never skips,
when no context can be made."""

import ctypes
import math
import unittest

import zshift

EGL_PLATFORM_SURFACELESS_MESA = 0x31DD
EGL_NONE, EGL_OPENGL_API = 0x3038, 0x30A2
EGL_CONTEXT_MAJOR_VERSION, EGL_CONTEXT_MINOR_VERSION = 0x3098, 0x30FB
EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT = 0x30FD, 0x1


def _egl():
    egl = ctypes.CDLL("libEGL.so.1")
    egl.eglGetProcAddress.restype = ctypes.c_void_p
    egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
    egl.eglGetPlatformDisplay.restype = ctypes.c_void_p
    egl.eglGetPlatformDisplay.argtypes = [ctypes.c_uint, ctypes.c_void_p, ctypes.POINTER(ctypes.c_ssize_t)]
    egl.eglInitialize.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
    egl.eglBindAPI.argtypes = [ctypes.c_uint]
    egl.eglCreateContext.restype = ctypes.c_void_p
    egl.eglCreateContext.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_int32)]
    egl.eglMakeCurrent.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
    egl.eglGetError.restype = ctypes.c_int32
    return egl


def make_context():
    """A 3.3 core context current on this thread; returns EGL (for eglGetProcAddress), the
    display and the context."""
    egl = _egl()
    display = egl.eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, None, (ctypes.c_ssize_t * 1)(EGL_NONE))
    if not display or not egl.eglInitialize(display, None, None) or not egl.eglBindAPI(EGL_OPENGL_API):
        raise AssertionError("no EGL surfaceless display (EGL error 0x%x)" % egl.eglGetError())
    attributes = (ctypes.c_int32 * 7)(EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE)
    context = egl.eglCreateContext(display, None, None, attributes)
    if not context or not egl.eglMakeCurrent(display, None, None, context):
        raise AssertionError("no OpenGL 3.3 core context (EGL error 0x%x)" % egl.eglGetError())
    return egl, display, context


class ProbeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.egl, cls.display, cls.context = make_context()

    def get_proc_address(self, name):
        return self.egl.eglGetProcAddress(name.encode("ascii"))

    def test_llvmpipe_profile(self):
        p = zshift.probe(self.get_proc_address)
        self.assertEqual(p.measured, 1)
        self.assertEqual(p.subpixel_bits, zshift.SUBPIXEL_UNSNAPPED)
        # lp_state_setup.c: units * 2 * mrd on UNORM formats, 2^(e - 23) on float depth.
        self.assertAlmostEqual(p.resolvable[1], 2.0, delta=0.01)
        self.assertAlmostEqual(p.resolvable[3], 1.0, delta=0.01)
        self.assertTrue(0.5 <= p.line_reach[0] < 0.55 and 0.5 <= p.line_reach[1] < 0.8, p.line_reach)
        # Mesa draws an outline with its line's depth: none of its neighbour's plane (f32 noise).
        self.assertTrue(0.0 <= p.outline_neighbour < 1e-3, p.outline_neighbour)
        # Under 4x MSAA a line's sample takes its depth about a pixel from itself on llvmpipe.
        self.assertTrue(all(1.0 <= r < 1.1 for r in p.line_reach_msaa), p.line_reach_msaa)
        # 3-pixel lines and outlines take their depth 1.5 pixels away: less than the wide quad's 2.125.
        self.assertTrue(all(1.49 <= r < 1.6 for r in p.line_reach_wide), p.line_reach_wide)
        # Against the whole gradient a multisampled 1-pixel line's sample lies within 0.87 of its line's point.
        self.assertTrue(all(0.7 <= r < 0.9 for r in p.line_reach_msaa_whole), p.line_reach_msaa_whole)
        # At width 3 within the model's (w + 1)/2 = 2, and at least the line's half width.
        self.assertTrue(all(1.4 <= r < 2.0 for r in p.line_reach_msaa_wide_whole), p.line_reach_msaa_wide_whole)
        self.assertAlmostEqual(p.offset_slope, 1.0, delta=1e-3)
        self.assertLess(p.plane_error[0], 1.0)
        # A facing decal with shared z needs a few element-10 steps on D24 (not measured on D16).
        self.assertTrue(math.isnan(p.facing_quanta[0]))
        self.assertTrue(1.0 <= p.facing_quanta[1] <= 4.0, p.facing_quanta)
        self.assertEqual(p.near_clip, zshift.NEAR_CLIP_CLIPPED_F32)
        self.assertGreater(p.probe_seconds, 0.0)

    def test_the_recommendation_takes_the_probed_profile(self):
        p = zshift.probe(self.get_proc_address)
        args = dict(frustum=(-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0), viewport=(256, 192),
                    depth_format=0x81A6, decal_depths=(40.0, 60.0), slope=1.0, subpixel_bits=8)
        plain = zshift.recommend(**args)
        probed = zshift.recommend(profile=p, **args)
        # The profile's snapping (unsnapped) wins over subpixel_bits = 8; units count r = 2 quanta.
        self.assertGreater(plain.snap, 0.0)
        self.assertEqual(probed.snap, 0.0)
        self.assertLess(probed.window_offset, plain.window_offset)
        self.assertAlmostEqual(probed.polygon_offset_units * 2 * probed.quantum / probed.window_offset, 1.0, places=12)
        m = zshift.frustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0)
        front = dict(viewport=(256, 192), depth_format=zshift.Format.UNORM24, decal_depths=(40.0, 60.0), slope=1.0,
                     subpixel_bits=8)
        inside = zshift.recommend_for_matrix(m, zshift.Clip.NEG_ONE_TO_ONE, profile=p, **front)
        clipped = zshift.recommend_for_matrix(m, zshift.Clip.NEG_ONE_TO_ONE, profile=p, base_reach=1000.0, **front)
        self.assertEqual((inside.snap, inside.clip), (0.0, 0.0))
        self.assertGreater(clipped.clip, 0.0)
        zeroed = zshift.Profile(*([0] * 2 + [(0.0,) * 4] * 2 + [0.0, 0.0, 0, 0.0, (0.0,) * 4, (0.0,) * 4, 0.0, 0.0, 0, 0.0, (0.0,) * 2, 0.0, (0.0,) * 2, (0.0,) * 2, 0.0, (0.0,) * 2, (0.0,) * 2]))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.recommend(profile=zeroed, **args)
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)
        with self.assertRaises(TypeError):
            zshift.recommend(profile=(1, 2), **args)

    def test_a_missing_entry_point_is_a_gl_error(self):
        def without_read_pixels(name):
            return None if name == "glReadPixels" else self.get_proc_address(name)

        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.probe(without_read_pixels)
        self.assertEqual(caught.exception.status, zshift.Status.GL)

    def test_no_current_context_is_a_gl_error(self):
        self.egl.eglMakeCurrent(self.display, None, None, None)
        try:
            with self.assertRaises(zshift.ZshiftError) as caught:
                zshift.probe(self.get_proc_address)
            self.assertEqual(caught.exception.status, zshift.Status.GL)
        finally:
            self.assertTrue(self.egl.eglMakeCurrent(self.display, None, None, self.context))

    def test_worst_case(self):
        p = zshift.profile_worst_case()
        self.assertEqual((p.measured, p.subpixel_bits, p.near_clip), (0, 8, zshift.NEAR_CLIP_CLIPPED_F32))
        self.assertEqual(p.resolvable, (1.0, 1.0, 1.0, 1.0))
        self.assertTrue(all(math.isnan(e) for e in p.plane_error))
        self.assertTrue(all(math.isnan(e) for e in p.facing_quanta))


if __name__ == "__main__":
    unittest.main()
