"""Tests of the zshift ctypes package against exact rational references (fractions.Fraction,
evaluating the seed formulas independently of zshift), and of its error and lookup behaviour.

Run from the repository root: python3 -m unittest discover -s bindings/python -t bindings/python
"""

import math
import os
import re
import struct
import subprocess
import sys
import unittest
from fractions import Fraction
from fractions import Fraction as Q
from pathlib import Path
from unittest import mock

import zshift

ROOT = Path(__file__).resolve().parents[3]


def f32(x):
    """The float32 nearest x (round to nearest even), as a Python float."""
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def f32_neighbours(x):
    """The float32 values either side of the float32 x."""
    bits = struct.unpack("I", struct.pack("f", x))[0]
    up, down = (bits + 1, bits - 1) if x > 0 else (bits - 1, bits + 1)
    if x == 0:
        return -1.4e-45, 1.4e-45
    return tuple(struct.unpack("f", struct.pack("I", b))[0] for b in (down, up))


def steps(bits):
    return Q(2**bits - 1)


def exact_frustum(l, r, b, t, n, f):
    """glFrustum's matrix (seed 000, eq. 4.1.1), column-major, in exact rationals."""
    l, r, b, t, n, f = map(Q, (l, r, b, t, n, f))
    m = [Q(0)] * 16
    m[0], m[5] = 2 * n / (r - l), 2 * n / (t - b)
    m[8], m[9] = (r + l) / (r - l), (t + b) / (t - b)
    m[10], m[11], m[14] = -(f + n) / (f - n), Q(-1), -2 * f * n / (f - n)
    return m


def exact_epsilon(n, f, delta, pz):
    """Eq. 4.1.7."""
    n, f, delta, pz = map(Q, (n, f, delta, pz))
    return -2 * f * n / (f + n) * delta / (pz * (pz + delta))


def exact_k(n, f, bits):
    """Eq. 4.1.11 with seed 002's correction."""
    n, f = Q(n), Q(f)
    return (f - n) / (f * n * steps(bits))


def exact_window_depth(n, f, d):
    """Walker's f(d) (seed 001) as printed."""
    n, f, d = map(Q, (n, f, d))
    return (f + n) / (2 * (f - n)) - f * n / (d * (f - n)) + Q(1, 2)


class TupleMatrices(unittest.TestCase):
    """Matrices without numpy: tuples of 16 Python floats."""

    CASES = [(-1, 1, -1, 1, 1, 100), (-0.1, 0.3, -0.2, 0.1, 0.1, 1e4), (-2, 2, -1.5, 1.5, 0.01, 1e6)]

    def setUp(self):
        patcher = mock.patch.object(zshift, "_numpy", None)
        patcher.start()
        self.addCleanup(patcher.stop)

    def test_frustum_is_nearest_float32_of_exact_matrix(self):
        for case in self.CASES:
            m = zshift.frustum(*case)
            self.assertIsInstance(m, tuple)
            self.assertEqual(len(m), 16)
            for i, (got, want) in enumerate(zip(m, exact_frustum(*case))):
                nearest = f32(want)
                self.assertIn(got, (nearest, *f32_neighbours(nearest)), f"{case} element {i}")

    def test_infinite_far_plane(self):
        m = zshift.frustum(-1, 1, -1, 1, 0.5, math.inf)
        self.assertEqual((m[10], m[11], m[14]), (-1.0, -1.0, -1.0))

    def test_offset_matrix_moves_element_10_by_at_least_the_exact_offset(self):
        for l, r, b, t, n, f, delta, pz in [
            (-1, 1, -1, 1, 1, 100, 0.01, -50),
            (-0.1, 0.1, -0.1, 0.1, 0.1, 1e4, 2.0, -5e3),
            (-1, 1, -1, 1, 1, 1e6, -10.0, -1e3),
        ]:
            plain = zshift.frustum(l, r, b, t, n, f)
            shifted = zshift.load_offset_matrix(l, r, b, t, n, f, delta, pz)
            for i in range(16):
                if i != 10:
                    self.assertEqual(shifted[i], plain[i], f"element {i}")
            exact_offset = exact_frustum(l, r, b, t, n, f)[10] * exact_epsilon(n, f, delta, pz)
            moved = Q(shifted[10]) - Q(plain[10])
            ulp = max(abs(Q(x) - Q(shifted[10])) for x in f32_neighbours(shifted[10]))
            self.assertGreater(moved * exact_offset, 0, "offset in the wrong direction")
            self.assertGreaterEqual(abs(moved), abs(exact_offset))
            self.assertLessEqual(abs(moved), abs(exact_offset) + ulp)


@unittest.skipIf(zshift._numpy is None, "numpy is not installed (scripts/setup installs it)")
class NumpyMatrices(unittest.TestCase):
    """Matrices with numpy: float32 arrays of shape (16,), the same values as the tuples."""

    def test_arrays_equal_the_tuples(self):
        array = zshift.load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.5, -50)
        with mock.patch.object(zshift, "_numpy", None):
            plain_tuple = zshift.load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.5, -50)
        self.assertEqual(array.dtype, zshift._numpy.float32)
        self.assertEqual(array.shape, (16,))
        self.assertEqual(tuple(float(x) for x in array), plain_tuple)


class Scalars(unittest.TestCase):
    """Each scalar is the f64 nearest the exact value (the library rounds correctly), or within
    the stated bound."""

    def assert_nearest(self, got, exact, what):
        self.assertIsInstance(got, float)
        self.assertEqual(got, float(exact), f"{what}: {got!r} vs exact {float(exact)!r}")

    def test_epsilon(self):
        self.assert_nearest(zshift.epsilon(0.1, 1000, 0.5, -20), exact_epsilon(0.1, 1000, 0.5, -20), "epsilon")
        self.assertLess(zshift.epsilon(0.1, 1000, 0.5, -20), 0)
        pz, delta = Q(-20), Q(0.5)
        self.assert_nearest(zshift.epsilon(1, math.inf, 0.5, -20), -2 * delta / (pz * (pz + delta)), "f = inf")

    def test_min_epsilon(self):
        for bits in (1, 16, 24, 32):
            exact = 2 / steps(bits) * (Q(1000) - Q(0.1)) / (Q(1000) + Q(0.1))
            self.assert_nearest(zshift.min_epsilon(0.1, 1000, bits), exact, f"bits {bits}")

    def test_min_delta_toward_and_depth_resolution(self):
        k, pz = exact_k(0.1, 1000, 16), Q(-300)
        exact = k * pz * pz / (1 - k * pz)
        self.assert_nearest(zshift.min_delta_toward(0.1, 1000, 16, -300), exact, "min_delta_toward")
        # Seeds 000 (with 002) and 001 agree: Walker's depth step at d = -pz is the same number.
        self.assert_nearest(zshift.depth_resolution(0.1, 1000, 16, 300), exact, "depth_resolution")

    def test_max_delta_away(self):
        k, pz = exact_k(0.1, 1000, 16), Q(-2)
        self.assert_nearest(zshift.max_delta_away(0.1, 1000, 16, -2), -k * pz * pz / (1 + k * pz), "max_delta_away")

    def test_window_depth(self):
        self.assert_nearest(zshift.window_depth(0.1, 1000, 37), exact_window_depth(0.1, 1000, 37), "f(37)")
        self.assertEqual(zshift.window_depth(1, 100, 1), 0.0)
        self.assertEqual(zshift.window_depth(1, 100, 100), 1.0)


class Errors(unittest.TestCase):
    """Failures raise ZshiftError carrying the status and the library's message."""

    def assert_raises_status(self, status, fn, *args):
        with self.assertRaises(zshift.ZshiftError) as caught:
            fn(*args)
        self.assertEqual(caught.exception.status, status)
        # The message is the library's detail (which input, its value, why), not the status's
        # sentence, and it is what zshift.last_error() says.
        self.assertNotEqual(str(caught.exception), zshift.status_message(status))
        self.assertGreater(len(caught.exception.message), 10)
        self.assertIsInstance(caught.exception, ValueError)

    def test_detail_names_the_input_and_its_value(self):
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.frustum(-1, 1, -1, 1, -1, 100)
        self.assertEqual(str(caught.exception), "the near plane distance n must be greater than 0 (n = -1)")
        self.assertEqual(zshift.last_error(), str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.depth_step(1, 100, zshift.Clip.ZERO_TO_ONE, 0x1902, 50)
        self.assertIn("(format = 0x1902)", str(caught.exception))
        zshift.frustum(-1, 1, -1, 1, 1, 100)
        self.assertEqual(zshift.last_error(), "")

    def test_a_near_plane_refusal_names_the_python_remedies(self):
        # World-space vertices 10^9 from the origin through one view-projection (eye_first
        # False): the offset would pass the near plane; the refusal says to compute the eye
        # position first, with the keyword Python takes, and not where the shader already does.
        ask = dict(viewport=(1920, 1080), depth_format=zshift.Format.UNORM24,
                   corners=[(-1, -1.7, -9), (1, -1.7, -9), (1, -1.7, -11), (-1, -1.7, -11)],
                   world_reach=1e9, subpixel_bits=8)
        projection = zshift.frustum(-0.1778, 0.1778, -0.1, 0.1, 0.1, 1000.0)
        for eye_first in (False, True):
            with self.assertRaises(zshift.ZshiftError) as caught:
                zshift.decal_matrix(projection, zshift.Clip.NEG_ONE_TO_ONE, eye_first=eye_first, **ask)
            self.assertEqual(caught.exception.status, zshift.Status.UNRESOLVABLE)
            self.assertIn("past the near plane", str(caught.exception))
            self.assertEqual("eye_first=True" in str(caught.exception), not eye_first, str(caught.exception))

    def test_arguments_of_another_kind_are_refused(self):
        # A Format where a Clip goes (the C header makes this a compile error).
        with self.assertRaises(TypeError):
            zshift.depth_step(1, 100, zshift.Format.UNORM24, zshift.Clip.ZERO_TO_ONE, 50)
        with self.assertRaises(TypeError):
            zshift.projection(-1, 1, -1, 1, 1, 100, zshift.Format.FLOAT32)

    def test_domain(self):
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.frustum, 1, 1, -1, 1, 1, 100)
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.frustum, -1, 1, -1, 1, 5, 5)
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.load_offset_matrix, -1, 1, -1, 1, 1, 100, 50, -50)
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.window_depth, 1, 100, 0.5)
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.min_epsilon, 1, 100, 33)

    def test_not_finite(self):
        self.assert_raises_status(zshift.Status.NOT_FINITE, zshift.frustum, math.nan, 1, -1, 1, 1, 100)
        self.assert_raises_status(zshift.Status.NOT_FINITE, zshift.epsilon, 1, 100, math.nan, -20)
        self.assert_raises_status(zshift.Status.NOT_FINITE, zshift.frustum, -1, 1, -1, 1, 1, -math.inf)

    def test_unresolvable_and_overflow(self):
        self.assert_raises_status(zshift.Status.UNRESOLVABLE, zshift.max_delta_away, 1, 1e6, 1, -1e5)
        self.assert_raises_status(zshift.Status.OVERFLOW, zshift.frustum, 0, 1e-40, -1, 1, 1, 100)

    def test_bits_outside_uint32_are_refused_not_wrapped(self):
        # ctypes alone would turn 2**32 + 24 into 24 and answer for a 24-bit buffer.
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.min_epsilon, 1, 100, 2**32 + 24)
        self.assert_raises_status(zshift.Status.DOMAIN, zshift.min_delta_toward, 1, 100, -1, -50)

    def test_wrong_argument_types_raise_type_errors(self):
        with self.assertRaises(Exception) as caught:
            zshift.frustum("left", 1, -1, 1, 1, 100)
        self.assertNotIsInstance(caught.exception, zshift.ZshiftError)

    def test_status_messages(self):
        messages = [zshift.status_message(s) for s in zshift.Status]
        self.assertEqual(len(set(messages)), len(messages), "each status has its own message")
        self.assertEqual(zshift.status_message(99), "unknown zshift status")
        self.assertEqual(zshift.ZshiftError(99).status, 99)


class Recommend(unittest.TestCase):
    """zshift.recommend: its parts agree with each other and with the seed formulas (exact
    rationals); recommend_matrix moves element 10 by at least the recommended offset."""

    FRUSTUM = (-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0)
    ARGS = dict(viewport=(1280, 720), depth_format=zshift.GL_DEPTH_COMPONENT24, decal_depths=(40.0, 60.0),
                slope=1.0, subpixel_bits=8)

    def test_parts_agree(self):
        r = zshift.recommend(self.FRUSTUM, **self.ARGS)
        n, f = Q(0.1), Q(1000.0)
        self.assertEqual(r.quantum, float(1 / steps(24)))
        terms = Q(r.quantum) + 2 * (Q(r.transform) + Q(r.vertex) + Q(r.interpolation) + Q(r.snap))
        self.assertAlmostEqual(float((Q(r.window_offset) - terms) / terms), 0.0, delta=1e-15)
        self.assertEqual(r.ndc_offset, 2 * r.window_offset)
        m10 = (f + n) / (f - n)
        self.assertAlmostEqual(float((Q(r.epsilon) + Q(r.ndc_offset) / m10) / Q(r.epsilon)), 0.0, delta=1e-14)
        eps_of_delta = exact_epsilon(0.1, 1000.0, r.delta_at_far, -60.0)  # eq. 4.1.7 at pz = -farthest
        self.assertAlmostEqual(float((eps_of_delta - Q(r.epsilon)) / Q(r.epsilon)), 0.0, delta=1e-12)
        self.assertEqual(r.polygon_offset_factor, 2.0**-7)  # 2^(1 - GL_SUBPIXEL_BITS)
        self.assertGreater(r.snap, 0)
        self.assertGreater(r.bleed_gap, 0)

    def test_unsnapped_and_exact_depth_drop_their_terms(self):
        unsnapped = zshift.recommend(self.FRUSTUM, **dict(self.ARGS, subpixel_bits=zshift.SUBPIXEL_UNSNAPPED))
        self.assertEqual((unsnapped.snap, unsnapped.polygon_offset_factor), (0.0, 0.0))
        exact = zshift.recommend(self.FRUSTUM, **dict(self.ARGS, slope=0.0, exact_depth=True))
        self.assertEqual((exact.vertex, exact.interpolation, exact.snap), (0.0, 0.0, 0.0))
        self.assertLess(exact.window_offset, unsnapped.window_offset)

    def test_matrix_moves_element_10_by_the_recommended_offset(self):
        with mock.patch.object(zshift, "_numpy", None):
            plain = zshift.frustum(*self.FRUSTUM)
            decal = zshift.recommend_matrix(self.FRUSTUM, **self.ARGS)
        r = zshift.recommend(self.FRUSTUM, **self.ARGS)
        self.assertEqual([decal[i] for i in range(16) if i != 10], [plain[i] for i in range(16) if i != 10])
        exact_offset = exact_frustum(*self.FRUSTUM)[10] * Q(r.epsilon)  # m10 * epsilon > 0: toward the camera
        moved = Q(decal[10]) - Q(plain[10])
        ulp = max(abs(Q(x) - Q(decal[10])) for x in f32_neighbours(decal[10]))
        self.assertGreaterEqual(moved, exact_offset)
        self.assertLessEqual(moved, exact_offset + ulp)

    def test_errors(self):
        domain, not_finite = zshift.Status.DOMAIN, zshift.Status.NOT_FINITE
        for changes, status in [
            (dict(decal_depths=(70.0, 60.0)), domain),
            (dict(decal_depths=(0.05, 60.0)), domain),
            (dict(slope=-1.0), domain),
            (dict(slope=math.nan), not_finite),
            (dict(depth_format=0x1234), domain),
            (dict(viewport=(0, 720)), domain),
            (dict(viewport=(2**32 + 1280, 720)), domain),  # refused, not wrapped to 1280
            (dict(subpixel_bits=-2), domain),
            (dict(subpixel_bits=33), domain),
        ]:
            for fn in (zshift.recommend, zshift.recommend_matrix):
                with self.assertRaises(zshift.ZshiftError, msg=str(changes)) as caught:
                    fn(self.FRUSTUM, **dict(self.ARGS, **changes))
                self.assertEqual(caught.exception.status, status, str(changes))

    def test_clip_conventions(self):
        """[0,1]: element 10 of projection(ZERO_TO_ONE) lowered by the window offset (exact
        rationals); reversed Z, infinite far, D32F: element 10 stays 0 and element 14 grows by at
        least 1 + epsilon; an unknown clip is refused."""
        clip = zshift.Clip
        self.assertEqual(zshift.recommend_clip(self.FRUSTUM, clip=clip.NEG_ONE_TO_ONE, **self.ARGS),
                         zshift.recommend(self.FRUSTUM, **self.ARGS))
        with mock.patch.object(zshift, "_numpy", None):
            z = zshift.recommend_clip(self.FRUSTUM, clip=clip.ZERO_TO_ONE, **self.ARGS)
            plain = zshift.projection(*self.FRUSTUM, clip.ZERO_TO_ONE)
            decal = zshift.recommend_clip_matrix(self.FRUSTUM, clip=clip.ZERO_TO_ONE, **self.ARGS)
            terms = Q(z.quantum) + 2 * (Q(z.transform) + Q(z.vertex) + Q(z.interpolation) + Q(z.snap))
            self.assertAlmostEqual(float((Q(z.window_offset) - terms) / terms), 0.0, delta=1e-15)
            self.assertGreaterEqual(Q(decal[10]) - Q(plain[10]), Q(z.window_offset))
            infinite = self.FRUSTUM[:5] + (math.inf,)
            args = dict(self.ARGS, depth_format=zshift.GL_DEPTH_COMPONENT32F)
            r = zshift.recommend_clip(infinite, clip=clip.REVERSED_ZERO_TO_ONE, **args)
            plain = zshift.projection(*infinite, clip.REVERSED_ZERO_TO_ONE)
            decal = zshift.recommend_clip_matrix(infinite, clip=clip.REVERSED_ZERO_TO_ONE, **args)
        self.assertEqual((plain[10], decal[10]), (0.0, 0.0))
        self.assertGreater(r.epsilon, 0)
        self.assertGreaterEqual(Q(decal[14]) / Q(plain[14]) - 1, Q(r.epsilon))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.recommend_clip(self.FRUSTUM, clip=7, **self.ARGS)
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)

    def test_structures_match_the_header(self):
        header = (ROOT / "include" / "zshift.h").read_text()
        for struct_name, cls in (("ZshiftScene", zshift._library.ZshiftScene),
                                 ("ZshiftRecommendation", zshift._library.ZshiftRecommendation),
                                 ("ZshiftShadowMap", zshift._ShadowMap)):
            body = re.search(r"typedef struct \{([^{}]*)\} " + struct_name + ";", header).group(1)
            fields = re.findall(r"^\s*(double|uint32_t|int32_t|ZshiftDepthTest|ZshiftClip|ZshiftPipeline|const ZshiftProfile|const float) \*?(\w+)(\[\d+\])?;",
                                body, re.M)
            # An array field (double world_box[6]) is a ctypes array of its element type.
            fields = [(c_type + array, name) for c_type, name, array in fields]
            # ZshiftDepthTest is a struct of one uint32_t: the same layout; a pointer is a c_void_p.
            ctypes_names = {"double": "c_double", "uint32_t": "c_uint", "int32_t": "c_int",
                            "ZshiftDepthTest": "c_uint", "ZshiftClip": "c_int", "const ZshiftProfile": "c_void_p",
                            "const float": "c_void_p", "double[6]": "c_double_Array_6",
                            "ZshiftPipeline": "ZshiftPipeline"}
            self.assertEqual([name for _, name in fields], [name for name, _ in cls._fields_], struct_name)
            for (c_type, name), (_, field_type) in zip(fields, cls._fields_):
                self.assertEqual(field_type.__name__, ctypes_names[c_type], f"{struct_name}.{name}")


class Conventions(unittest.TestCase):
    """The clip-convention, median, bias and planning functions against the seed formulas (exact
    rationals) or the functions they generalise."""

    def setUp(self):
        patcher = mock.patch.object(zshift, "_numpy", None)
        patcher.start()
        self.addCleanup(patcher.stop)

    def test_enums_match_the_header(self):
        header = (ROOT / "include" / "zshift.h").read_text()
        for prefix, enum_cls in (("CLIP", zshift.Clip), ("FORMAT", zshift.Format), ("BIAS", zshift.BiasApi),
                                 ("OFFSET", zshift.OffsetKind), ("DEPTH_TEST", zshift.DepthTest)):
            defined = dict(re.findall(r"static const Zshift\w+ ZSHIFT_" + prefix + r"_(\w+) = \{ (0x[0-9A-F]+|\d+) \};",
                                      header))
            self.assertEqual({k: int(v, 0) for k, v in defined.items()}, {m.name: m.value for m in enum_cls}, prefix)
        tweak = re.search(r"#define ZSHIFT_MIN_INFINITE_TWEAK (\S+)", header).group(1)
        self.assertEqual(zshift.MIN_INFINITE_TWEAK, float(tweak))

    def test_projection_depth_rows(self):
        n, f = Q(0.5), Q(200)
        rows = {zshift.Clip.NEG_ONE_TO_ONE: (-(f + n) / (f - n), -2 * f * n / (f - n)),
                zshift.Clip.ZERO_TO_ONE: (-f / (f - n), -f * n / (f - n)),
                zshift.Clip.REVERSED_ZERO_TO_ONE: (n / (f - n), f * n / (f - n))}
        for clip, (m10, m14) in rows.items():
            m = zshift.projection(-1, 1, -1, 1, 0.5, 200.0, clip)
            for got, want in ((m[10], m10), (m[14], m14)):
                self.assertIn(got, (f32(want), *f32_neighbours(f32(want))), clip.name)
        self.assertEqual(zshift.projection(-1, 1, -1, 1, 0.5, 200.0, zshift.Clip.NEG_ONE_TO_ONE),
                         zshift.frustum(-1, 1, -1, 1, 0.5, 200.0))

    def test_perspective_and_offsets(self):
        m = zshift.perspective(90.0, 2.0, 0.5, 200.0)  # cot(45 degrees) = 1
        self.assertEqual((m[0], m[5]), (0.5, 1.0))
        shifted = zshift.offset_perspective(90.0, 2.0, 0.5, 200.0, zshift.Clip.NEG_ONE_TO_ONE, 0.5, -50.0)
        self.assertEqual([shifted[i] for i in range(16) if i != 10], [m[i] for i in range(16) if i != 10])
        self.assertGreater(shifted[10], m[10])
        reversed_ = zshift.Clip.REVERSED_ZERO_TO_ONE
        plain = zshift.projection(-1, 1, -1, 1, 0.5, 200.0, reversed_)
        moved = zshift.offset_projection(-1, 1, -1, 1, 0.5, 200.0, reversed_, 0.5, -50.0)
        self.assertEqual([moved[i] for i in range(16) if i != 14], [plain[i] for i in range(16) if i != 14])
        tweaked = zshift.tweaked_infinite(-1, 1, -1, 1, 0.5, zshift.MIN_INFINITE_TWEAK)
        self.assertEqual(tweaked[10], f32(Q(zshift.MIN_INFINITE_TWEAK) - 1))
        self.assertEqual(tweaked[14], f32((Q(zshift.MIN_INFINITE_TWEAK) - 2) * Q(0.5)))
        self.assertNotEqual(zshift.offset_tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0, 10.0, -1000.0)[10],
                            zshift.tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0)[10])

    def test_depths_and_steps(self):
        neg, reversed_, unorm24 = zshift.Clip.NEG_ONE_TO_ONE, zshift.Clip.REVERSED_ZERO_TO_ONE, zshift.Format.UNORM24
        self.assertEqual(zshift.window_depth_clip(0.5, 200.0, neg, 37.0), zshift.window_depth(0.5, 200.0, 37.0))
        n, f, d = Q(0.5), Q(200), Q(37)
        self.assertAlmostEqual(zshift.window_depth_clip(0.5, 200.0, reversed_, 37.0),
                               float(n * (f - d) / ((f - n) * d)), delta=1e-16)
        self.assertAlmostEqual(zshift.depth_step(0.5, 200.0, neg, unorm24, 37.0) /
                               zshift.depth_resolution(0.5, 200.0, 24, 37.0), 1.0, delta=1e-15)
        self.assertEqual(zshift.min_ndc_offset(0.5, 200.0, neg, unorm24, 37.0), float(2 / steps(24)))
        self.assertAlmostEqual(zshift.min_epsilon_clip(0.5, 200.0, neg, unorm24, 37.0) /
                               zshift.min_epsilon(0.5, 200.0, 24), 1.0, delta=1e-15)
        r, median = 1 / steps(24), Q(10)
        self.assertAlmostEqual(zshift.median_depth_step(10.0, unorm24, 37.0) /
                               float(r * (d + median) ** 2 / (median + r * (d + median))), 1.0, delta=1e-14)
        self.assertAlmostEqual(zshift.median_ndc_offset(10.0, 0.5, -37.0) /
                               float(-2 * median * Q(0.5) / ((d + median) * (d + median - Q(0.5)))), 1.0, delta=1e-14)
        self.assertAlmostEqual(zshift.min_relative_epsilon(0.5, 200.0, neg, unorm24, 37.0) /
                               float(r * d / (f * n / (f - n))), 1.0, delta=1e-14)

    def test_bias_planning_and_errors(self):
        neg, unorm24 = zshift.Clip.NEG_ONE_TO_ONE, zshift.Format.UNORM24
        bias = zshift.bias_of_shift(0.5, 200.0, neg, unorm24, zshift.BiasApi.OPENGL, 0.25, -37.0)
        self.assertLess(bias, 0)
        self.assertAlmostEqual(zshift.shift_of_bias(0.5, 200.0, neg, unorm24, zshift.BiasApi.OPENGL, bias, -37.0),
                               0.25, delta=1e-9)
        near, far = zshift.tight_planes(2.0, 500.0)
        self.assertTrue(0 < near <= 2.0 and far >= 500.0)
        ro = zshift.range_offset(0.5, 200.0, neg, unorm24, zshift.OffsetKind.NDC, 10.0, 100.0, 2.0)
        self.assertLess(ro.offset, 0)
        self.assertLess(ro.shift_at_lo, ro.shift_at_hi)
        for fn, args, status in [
            (zshift.projection, (-1, 1, -1, 1, 1, 100, 7), zshift.Status.DOMAIN),
            (zshift.projection, (-1, 1, -1, 1, 1, 100, 2**32), zshift.Status.DOMAIN),  # not wrapped to 0
            (zshift.perspective, (180.0, 1.0, 1.0, 100.0), zshift.Status.DOMAIN),
            (zshift.min_epsilon_clip, (0.5, math.inf, zshift.Clip.REVERSED_ZERO_TO_ONE, zshift.Format.FLOAT32, 37.0),
             zshift.Status.UNRESOLVABLE),
            (zshift.tight_planes, (500.0, 2.0), zshift.Status.DOMAIN),
            (zshift.range_offset, (0.5, 200.0, neg, unorm24, zshift.OffsetKind.NDC, 10.0, 100.0, math.nan),
             zshift.Status.NOT_FINITE),
            (zshift.median_ndc_offset, (10.0, math.nan, -37.0), zshift.Status.NOT_FINITE),
        ]:
            with self.assertRaises(zshift.ZshiftError, msg=fn.__name__) as caught:
                fn(*args)
            self.assertEqual(caught.exception.status, status, fn.__name__)


class Library(unittest.TestCase):
    """The library lookup and the versions."""

    def test_version_matches_cargo_toml(self):
        cargo = (ROOT / "Cargo.toml").read_text()
        self.assertEqual(zshift.version(), re.search(r'^version\s*=\s*"([^"]+)"', cargo, re.M).group(1))

    def test_abi_version_matches_header(self):
        header = (ROOT / "include" / "zshift.h").read_text()
        self.assertEqual(zshift.ABI_VERSION, int(re.search(r"#define ZSHIFT_ABI_VERSION (\d+)", header).group(1)))

    def run_python(self, code, library):
        env = dict(os.environ, ZSHIFT_LIBRARY=str(library), PYTHONPATH=str(ROOT / "bindings" / "python"))
        return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)

    def test_environment_variable_is_used_first(self):
        done = self.run_python("import zshift; print(zshift.library_path())", zshift.library_path())
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.strip(), zshift.library_path())

    def test_wrong_environment_variable_fails_loudly(self):
        missing = ROOT / "target" / "no-such-dir" / "libzshift.so"
        done = self.run_python("import zshift; zshift.version()", missing)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("LibraryNotFound", done.stderr)
        self.assertIn(str(missing), done.stderr)


if __name__ == "__main__":
    unittest.main()


class FrontDoor(unittest.TestCase):
    """The engine's own matrix in, the decal's matrix out: only the offset element changes, by at
    least the offset asked (exact, with fractions) and at most one float32 ulp more."""

    @staticmethod
    def f32(x):
        return struct.unpack("f", struct.pack("f", x))[0]

    def perspective(self, fovy, aspect, n, f, zero_to_one=False, reversed_z=False):
        # GLM's perspectiveRH_NO / perspectiveRH_ZO, column-major, rounded to float32.
        h = 1.0 / math.tan(fovy / 2.0)
        if reversed_z:
            n, f = f, n
        m = [0.0] * 16
        m[0], m[5], m[11] = h / aspect, h, -1.0
        if zero_to_one:
            m[10], m[14] = f / (n - f), -(f * n) / (f - n)
        else:
            m[10], m[14] = -(f + n) / (f - n), -(2.0 * f * n) / (f - n)
        return [self.f32(x) for x in m]

    def ortho(self, l, r, b, t, n, f):
        m = [0.0] * 16
        m[0], m[5], m[10], m[15] = 2.0 / (r - l), 2.0 / (t - b), -2.0 / (f - n), 1.0
        m[12], m[13], m[14] = -(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n)
        return [self.f32(x) for x in m]

    def ulp(self, x):
        a = abs(x)
        bits = struct.unpack("I", struct.pack("f", a))[0]
        return Fraction(struct.unpack("f", struct.pack("I", bits + 1))[0]) - Fraction(a)

    def check(self, m, out, element, seen, want, what):
        for i in range(16):
            if i != element:
                self.assertEqual(struct.pack("f", m[i]), struct.pack("f", out[i]), f"{what}: element {i}")
        self.assertTrue((seen > 0) == (want > 0) and abs(seen) >= abs(want), f"{what}: {seen} < {want}")
        self.assertLessEqual(abs(seen) - abs(want), self.ulp(out[element]), what)

    def test_offset_matrix_changes_one_element_by_the_offset(self):
        cases = [
            ("GL [-1, 1]", self.perspective(1.0, 1.5, 0.1, 1000.0), zshift.Clip.NEG_ONE_TO_ONE, False),
            ("[0, 1]", self.perspective(1.0, 1.5, 0.1, 1000.0, zero_to_one=True), zshift.Clip.ZERO_TO_ONE, False),
            ("reversed", self.perspective(1.0, 1.5, 0.1, 1000.0, True, True), zshift.Clip.REVERSED_ZERO_TO_ONE, False),
            ("glOrtho", self.ortho(-20.0, 20.0, -10.0, 10.0, 1.0, 500.0), zshift.Clip.NEG_ONE_TO_ONE, True),
        ]
        for name, m, clip, is_ortho in cases:
            for delta, d in ((0.01, 50.0), (2.5, 400.0)):
                what = f"{name} delta {delta} at {d}"
                out = [float(x) for x in zshift.offset_matrix(m, clip, delta, d)]
                m10, m14, fd, fdelta = Fraction(m[10]), Fraction(m[14]), Fraction(d), Fraction(delta)
                if is_ortho:
                    self.check(m, out, 14, Fraction(out[14]) - m14, m10 * fdelta, what)
                elif clip == zshift.Clip.REVERSED_ZERO_TO_ONE:
                    self.check(m, out, 14, Fraction(out[14]) - m14, m14 * fdelta / (fd - fdelta), what)
                else:
                    seen = (Fraction(out[10]) - m10) * Fraction(m[11])
                    self.check(m, out, 10, seen, m14 * fdelta / (fd * (fd - fdelta)), what)

    def test_decal_matrix_and_its_record(self):
        m = self.perspective(1.0, 16 / 9, 0.1, 1000.0)
        decal = zshift.decal_matrix(m, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0),
                                    slope=1.0, subpixel_bits=8)
        self.assertEqual([i for i in range(16) if decal[i] != m[i]], [10])
        rec = zshift.recommend_for_matrix(m, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24,
                                          (40.0, 60.0), slope=1.0, subpixel_bits=8)
        self.assertGreater(rec.window_offset, 0.0)
        o = zshift.ortho(-20.0, 20.0, -10.0, 10.0, 1.0, 500.0)
        decal = zshift.decal_matrix(o, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0),
                                    subpixel_bits=8)
        self.assertEqual([i for i in range(16) if decal[i] != o[i]], [14])

    def test_a_decal_over_planes_takes_the_largest_offset(self):
        # A mesh decal over terrain: two triangles under it, one flat, one rising 0.7 per unit.
        m = self.perspective(1.0, 16 / 9, 0.1, 1000.0)
        args = (m, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24)

        def triangle(ahead, rise):
            at = lambda x, z: (x, -1.7 + rise * x, -z)
            return [at(-1.0, ahead), at(1.0, ahead), at(0.0, ahead + 1.5)]

        planes = [dict(corners=triangle(10.0, 0.0)), dict(corners=triangle(12.0, 0.7), base_reach=0.0)]
        each = [zshift.decal_matrix(*args, None, subpixel_bits=8, corners=p["corners"]) for p in planes]
        both = zshift.decal_matrix_planes(*args, planes, subpixel_bits=8)
        # NDC depth is -m10 + m14/d: the larger offset toward the camera is the larger element 10.
        self.assertEqual(list(both), list(max(each, key=lambda d: d[10])))
        self.assertNotEqual(each[0][10], each[1][10])
        rec = zshift.recommend_for_planes(*args, planes, subpixel_bits=8)
        own = [zshift.recommend_for_matrix(*args, None, subpixel_bits=8, corners=p["corners"]) for p in planes]
        self.assertGreaterEqual(rec.bleed_gap, max(r.bleed_gap for r in own))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix_planes(*args, [planes[0], dict(corners=triangle(10.0, 0.0), base_reach=-1.0)],
                                       subpixel_bits=8)
        self.assertTrue(str(caught.exception).startswith("plane 1: "), str(caught.exception))
        self.assertIn("base_reach = -1", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError):
            zshift.decal_matrix_planes(*args, [], subpixel_bits=8)
        # A terrain triangle under the decal but behind the camera, given raw: left out.
        behind = dict(corners=[(-1.0, -1.7, 2.0), (1.0, -1.7, 2.0), (0.0, -1.7, 0.5)])
        self.assertEqual(list(zshift.decal_matrix_planes(*args, [planes[0], behind, planes[1]], subpixel_bits=8)),
                         list(both))
        with self.assertRaises(TypeError) as caught:
            zshift.decal_matrix_planes(*args, [dict(corner=triangle(10.0, 0.0))], subpixel_bits=8)
        self.assertIn("'corner'", str(caught.exception))

    def test_a_plane_nearer_than_the_largest_offset_allows_is_named(self):
        # A piece just beyond the near plane, and a far one on a clipped base of growing reach:
        # once the far plane's offset would move the near one past the near plane, the refusal
        # names the plane that set it, and each plane alone is still answered (the remedy).
        m = self.perspective(1.0, 16 / 9, 0.1, 1000.0)
        args = (m, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24)
        near = dict(corners=[(-0.01, -0.02, -0.125), (0.01, -0.02, -0.125), (0.0, -0.02, -0.13)])
        far = [(-1.0, -1.7, -50.0), (1.0, -1.7, -50.0), (0.0, -1.7, -51.5)]
        named = 0
        for reach in (1e4, 1e5, 1e6, 1e7):
            planes = [near, dict(corners=far, base_reach=reach)]
            try:
                alone = [zshift.decal_matrix(*args, None, subpixel_bits=8, corners=p["corners"],
                                             base_reach=p.get("base_reach", 0.0)) for p in planes]
            except zshift.ZshiftError:
                continue
            self.assertEqual(len(alone), 2)
            try:
                zshift.decal_matrix_planes(*args, planes, subpixel_bits=8)
            except zshift.ZshiftError as e:
                self.assertEqual(e.status, zshift.Status.UNRESOLVABLE, str(e))
                self.assertTrue(str(e).startswith("plane 0: "), str(e))
                self.assertIn("largest_plane = 1", str(e))
                self.assertIn("its own plane's matrix", str(e))
                named += 1
        self.assertGreater(named, 0)

    def test_corners_describe_the_decal(self):
        # A steep square (z = -20 - 2y) below the view axis: its corners give the depths (14, 18) and the
        # slope (2) this test computes itself, and its place on the screen, which can only tighten the offset.
        m = self.perspective(1.0, 16 / 9, 0.1, 1000.0)
        corners = [(-1.0, -3.0, -14.0), (1.0, -3.0, -14.0), (1.0, -1.0, -18.0), (-1.0, -1.0, -18.0)]
        args = (m, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24)
        without = zshift.recommend_for_matrix(*args, (14.0, 18.0), slope=2.0, subpixel_bits=8)
        with_corners = zshift.recommend_for_matrix(*args, None, subpixel_bits=8, corners=corners)
        # The decal's own plane (its form on eye coordinates) bounds the vertex term no higher
        # than every plane of that slope does.
        self.assertGreater(with_corners.vertex, 0.0)
        self.assertLessEqual(with_corners.vertex, without.vertex)
        self.assertLess(with_corners.snap, without.snap)
        self.assertLessEqual(with_corners.window_offset, without.window_offset)
        decal = zshift.decal_matrix(*args, None, subpixel_bits=8, corners=corners)
        self.assertEqual([i for i in range(16) if decal[i] != m[i]], [10])
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix(*args, (14.0, 18.0), subpixel_bits=8, corners=corners)
        self.assertIn("corners", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix(*args, subpixel_bits=8, corners=corners[:2])
        self.assertIn("decal_corner_count", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix(*args, subpixel_bits=8, corners=[(x, y, -z) for x, y, z in corners])
        self.assertIn("wholly behind the near plane", str(caught.exception))

    def test_a_decal_reaching_behind_the_camera_is_answered(self):
        # A 2x8 decal on the ground under a level camera 1.7 above it, from 2 behind to 6 ahead:
        # described by the part on screen, the rasterizer's clipping of the rest counted.
        engine = zshift.perspective(60.0, 16 / 9, 0.1, 1000.0)
        under = [(-1, -1.7, 2), (1, -1.7, 2), (1, -1.7, -6), (-1, -1.7, -6)]
        decal = zshift.decal_matrix(engine, zshift.Clip.NEG_ONE_TO_ONE, viewport=(1920, 1080),
                                    depth_format=zshift.Format.UNORM24, corners=under, subpixel_bits=8)
        self.assertEqual([i for i in range(16) if decal[i] != engine[i]], [10])
        self.assertGreater(decal[10], engine[10])  # toward the camera

    def test_mismatch_and_bad_matrices_are_refused_with_a_reason(self):
        reversed_m = self.perspective(1.0, 1.5, 0.1, 1000.0, True, True)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.offset_matrix(reversed_m, zshift.Clip.NEG_ONE_TO_ONE, 0.01, 50.0)
        self.assertIn("reversed-Z", str(caught.exception))
        with self.assertRaises(TypeError):
            zshift.offset_matrix(reversed_m[:12], zshift.Clip.REVERSED_ZERO_TO_ONE, 0.01, 50.0)
        with self.assertRaises(TypeError):
            zshift.offset_matrix(reversed_m, zshift.Format.UNORM24, 0.01, 50.0)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix(reversed_m, zshift.Clip.REVERSED_ZERO_TO_ONE, (0, 720), zshift.Format.FLOAT32,
                                (40.0, 60.0), subpixel_bits=8)
        self.assertIn("viewport", str(caught.exception))


class ShadowBiasTest(unittest.TestCase):
    """zshift.shadow_bias: a directional light's map, references computed here."""

    ARGS = dict(light=zshift.Light.ORTHOGRAPHIC, projection=(-8.0, 8.0, -8.0, 8.0, 2.0, 30.0),
                clip=zshift.Clip.NEG_ONE_TO_ONE, resolution=(1024, 1024),
                depth_format=zshift.Format.UNORM24, limit_angle_deg=60.0, receiver_depths=(2.0, 30.0),
                lookup=zshift.Lookup.PCF, pcf_size=3, elevation_deg=30.0)

    def test_footprint_factor_and_units(self):
        import math
        bias = zshift.shadow_bias(**self.ARGS)
        footprint = 1.5 * math.tan(math.radians(60.0)) * (16.0 / 1024.0) * math.sqrt(2.0) / 28.0
        self.assertAlmostEqual(bias.footprint / footprint, 1.0, places=10)
        self.assertGreaterEqual(bias.gl_factor, 3.0 + 1.0 / 256.0)
        self.assertGreaterEqual(bias.d3d_depth_bias / 16777215.0, bias.constant)
        self.assertGreaterEqual(bias.gl_clamp, bias.constant + bias.snap + bias.footprint)
        self.assertLess(bias.along_normal, bias.along_light)
        self.assertAlmostEqual(bias.peter_panning / bias.leak_thickness, math.cos(math.radians(30.0)), places=9)

    def test_refusals_and_bad_fields(self):
        # A clamp that would span the whole depth range: none is set, the factor still covers the
        # footprint, and no receiver-side offset reaches.
        args = dict(self.ARGS, resolution=(64, 64), pcf_size=5, limit_angle_deg=89.9)
        grazing = zshift.shadow_bias(**args)
        self.assertEqual((grazing.gl_clamp, grazing.d3d_clamp, grazing.vk_clamp), (0.0, 0.0, 0.0))
        self.assertGreaterEqual(grazing.gl_factor, 5.0)
        self.assertTrue(math.isinf(grazing.along_light))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.shadow_bias(**dict(self.ARGS, receiver_depths=(1.0, 30.0)))
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)
        self.assertIn("receiver_near", str(caught.exception))
        with self.assertRaises(TypeError):
            zshift.shadow_bias(**dict(self.ARGS, lookup=zshift.Clip.ZERO_TO_ONE))

    def test_an_atlas_tile(self):
        # A tile far from the atlas's origin: the caster's plane runs further, the quantum is
        # the same. glDepthRange(0.5, 1): a D24 quantum is 2 / (2**24 - 1) in unit window
        # depth, and the clamp, applied to stored depth, is half the unit bias.
        whole = zshift.shadow_bias(**self.ARGS)
        tile = zshift.shadow_bias(**self.ARGS, viewport_origin=(3072, 2048))
        self.assertGreater(tile.caster, whole.caster)
        self.assertEqual(tile.quantum, whole.quantum)
        half = zshift.shadow_bias(**self.ARGS, depth_range=(0.5, 1.0))
        self.assertAlmostEqual(half.quantum * 16777215.0, 2.0, places=9)
        needed = half.constant + half.snap + half.footprint
        self.assertAlmostEqual(half.gl_clamp / (0.5 * needed), 1.0, places=6)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.shadow_bias(**self.ARGS, depth_range=(0.5, 0.5))
        self.assertIn("depth_range_far", str(caught.exception))

    def test_a_profile_changes_the_units(self):
        worst = zshift.profile_worst_case()
        llvmpipe = worst._replace(resolvable=(2.0, 2.0, 2.0, 1.0), subpixel_bits=zshift.SUBPIXEL_UNSNAPPED)
        a = zshift.shadow_bias(**self.ARGS, profile=worst)
        b = zshift.shadow_bias(**self.ARGS, profile=llvmpipe)
        self.assertEqual(a, zshift.shadow_bias(**self.ARGS))
        self.assertLess(b.gl_units, a.gl_units)
        self.assertEqual(b.snap, 0.0)
        self.assertEqual(b.slope_factor, 3.0)

    def test_listed_receivers(self):
        args = {k: v for k, v in self.ARGS.items() if k not in ("limit_angle_deg", "receiver_depths")}
        tilted = [(-4.0, -4.0, -12.0), (4.0, -4.0, -8.0), (4.0, 4.0, -8.0), (-4.0, 4.0, -12.0)]
        bias = zshift.shadow_bias_receivers(**args, receivers=[tilted])
        own = 1.5 * 0.5 * (16.0 / 1024.0) / 28.0
        self.assertGreaterEqual(bias.footprint, own)
        self.assertLess(bias.footprint, own * 1.0001)
        self.assertGreaterEqual(bias.gl_clamp, bias.constant + bias.footprint)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.shadow_bias_receivers(**args, receivers=[tilted[::-1]])
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)
        self.assertIn("faces the light", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.shadow_bias_receivers(**args, receivers=[])
        self.assertIn("receiver_count", str(caught.exception))

    def test_the_lights_view(self):
        # A light 25 units up the world z axis looking down -z (its view a translation), the
        # scene inside the box [-8, 8] x [-8, 8] x [-5, 23]: tighter than world_reach alone.
        view = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -25, 1]
        box = ((-8.0, -8.0, -5.0), (8.0, 8.0, 23.0))
        scalar = zshift.shadow_bias(**self.ARGS, world_reach=25.0)
        viewed = zshift.shadow_bias(**self.ARGS, world_reach=25.0, view_matrix=view, world_box=box,
                                    eye_first=True)
        self.assertLess(viewed.lookup, scalar.lookup)
        self.assertLess(viewed.constant, scalar.constant)
        self.assertEqual(zshift.shadow_bias(**self.ARGS, world_reach=25.0, view_matrix=None, world_box=None), scalar)
        args = {k: v for k, v in self.ARGS.items() if k not in ("limit_angle_deg", "receiver_depths")}
        tilted = [(-4.0, -4.0, -12.0), (4.0, -4.0, -8.0), (4.0, 4.0, -8.0), (-4.0, 4.0, -12.0)]
        listed = zshift.shadow_bias_receivers(**args, receivers=[tilted], world_reach=25.0, view_matrix=view,
                                              world_box=box, eye_first=True)
        self.assertLess(listed.lookup,
                        zshift.shadow_bias_receivers(**args, receivers=[tilted], world_reach=25.0).lookup)
        with self.assertRaises(TypeError):
            zshift.shadow_bias(**self.ARGS, view_matrix=view)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.shadow_bias(**self.ARGS, view_matrix=view, world_box=((0, 0, 0), (0, 0, 0)))
        self.assertIn("world_box", str(caught.exception))
