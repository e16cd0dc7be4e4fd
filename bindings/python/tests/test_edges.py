"""Edges over their own faces through the Python binding (zshift.edge_offset, zshift.edge_planes):
the references are computed here, not read from the library."""

import math
import unittest

import zshift


def perspective(n, f):
    # glFrustum(-n/2, n/2, -n/2, n/2, n, f), column-major.
    m = [0.0] * 16
    m[0] = m[5] = 2.0
    m[10] = -(f + n) / (f - n)
    m[11] = -1.0
    m[14] = -2.0 * f * n / (f - n)
    return m


class Edges(unittest.TestCase):
    M = perspective(1.0, 1000.0)

    def offset(self, method, **kw):
        args = dict(face_gradient=1e-3, subpixel_bits=zshift.SUBPIXEL_UNSNAPPED)
        args.update(kw)
        return zshift.edge_offset(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM24,
                                  (10.0, 20.0), method, **args)

    def test_matrix_method_moves_element_10_by_at_least_its_offset(self):
        r = self.offset(zshift.EdgeMethod.MATRIX)
        self.assertEqual(r.line_reach, 1.0)
        self.assertAlmostEqual(r.line_term, 1e-3, delta=1e-15)
        self.assertLess(r.ndc_offset, 0.0)
        self.assertGreaterEqual(r.matrix[10] - self.M[10], -r.ndc_offset * (1 - 1e-9))
        self.assertEqual([x for i, x in enumerate(r.matrix) if i != 10],
                         [float(__import__("ctypes").c_float(x).value) for i, x in enumerate(self.M) if i != 10])
        # The gap: window separation 2*offset + q at d = 20, through w(d) = F(1 - n/d).
        f, n, d = 1000.0, 1.0, 20.0
        big_f = f / (f - n)
        w = big_f * (1 - n / d) - (2 * r.window_offset + 1 / (2**24 - 1))
        front = n / (1 - w / big_f)
        self.assertAlmostEqual(r.hidden_gap, d - front, delta=1e-6 * r.hidden_gap)

    def test_polygon_offset_factor_is_the_wide_outline_reach(self):
        # Polygon-mode width 3: (w + 1)/2, plus 1/8 for a wide outline drawn as a shifted quad.
        r = self.offset(zshift.EdgeMethod.POLYGON_OFFSET, line_width=3.0, polygon_mode=True)
        self.assertEqual(r.polygon_offset[0], 2.125)
        self.assertEqual(r.d3d_bias[0], math.ceil(r.d3d_bias[0]))
        self.assertEqual(r.vulkan_bias[1], 2.125)

    def test_a_width_between_integers_is_taken_as_drawn(self):
        # GL rounds an aliased line's width to the nearest integer: 2.5 may be drawn 3 wide, so its
        # worst-case reach is (3 + 1)/2; 2.4 is drawn at most 2.4 wide, (2.4 + 1)/2.
        self.assertEqual(self.offset(zshift.EdgeMethod.MATRIX, line_width=2.5).line_reach, 2.0)
        self.assertAlmostEqual(self.offset(zshift.EdgeMethod.MATRIX, line_width=2.4).line_reach, 1.7,
                               delta=1e-12)

    def test_refusal_and_planes(self):
        m = perspective(0.01, 100.0)
        kw = dict(face_gradient=1e-9, subpixel_bits=zshift.SUBPIXEL_UNSNAPPED)
        free = zshift.edge_offset(m, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM16, (50.0, 60.0),
                                  zshift.EdgeMethod.MATRIX, **kw)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.edge_offset(m, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM16, (50.0, 60.0),
                               zshift.EdgeMethod.MATRIX, hidden_separation=free.hidden_gap / 2, **kw)
        self.assertEqual(caught.exception.status, zshift.Status.UNRESOLVABLE)
        near, far = zshift.edge_planes(m, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM16,
                                       (50.0, 60.0), zshift.EdgeMethod.MATRIX,
                                       hidden_separation=free.hidden_gap / 2, **kw)
        self.assertTrue(40.0 < near <= 50.0 and far >= 60.0, (near, far))

    def test_the_engines_pipeline(self):
        # World space 10^4 units from the origin costs offset; the view matrix with the mesh's box
        # less than world_reach alone; a viewport origin and glDepthRange are accepted, a reversed
        # range is named.
        eye = self.offset(zshift.EdgeMethod.MATRIX)
        far_away = self.offset(zshift.EdgeMethod.MATRIX, world_reach=1e4)
        view = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1e4, 0, 0, 1]
        box = ((1e4 - 5, -5, -25), (1e4 + 5, 5, -5))
        known = self.offset(zshift.EdgeMethod.MATRIX, world_reach=1e4, view_matrix=view, world_box=box,
                            eye_first=True)
        self.assertLess(eye.window_offset, far_away.window_offset)
        self.assertLessEqual(known.window_offset, far_away.window_offset)
        self.assertGreaterEqual(known.window_offset, eye.window_offset)
        tile = self.offset(zshift.EdgeMethod.POLYGON_OFFSET, viewport_origin=(1500, 900),
                           framebuffer_depth_range=(0.5, 1.0))
        self.assertGreater(tile.polygon_offset[1], 0.0)
        with self.assertRaises(zshift.ZshiftError) as caught:
            self.offset(zshift.EdgeMethod.MATRIX, framebuffer_depth_range=(0.75, 0.25))
        self.assertIn("depth_range_far", str(caught.exception))

    def test_bad_field_is_named(self):
        with self.assertRaises(zshift.ZshiftError) as caught:
            self.offset(zshift.EdgeMethod.MATRIX, line_width=0.5)
        self.assertIn("line_width", str(caught.exception))


if __name__ == "__main__":
    unittest.main()


class SteepestFace(unittest.TestCase):
    M = perspective(1.0, 1000.0)

    @staticmethod
    def projected_gradient(m, tri, width, height):
        # Each vertex to window coordinates (divide by w), then the plane through the three.
        win = []
        for x, y, z in tri:
            c = [m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r] for r in range(4)]
            win.append(((c[0] / c[3] + 1) / 2 * width, (c[1] / c[3] + 1) / 2 * height, (c[2] / c[3] + 1) / 2))
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = win
        area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
        gx = ((bz - az) * (cy - ay) - (cz - az) * (by - ay)) / area
        gy = ((cz - az) * (bx - ax) - (bz - az) * (cx - ax)) / area
        return max(abs(gx), abs(gy))

    def test_the_steepest_drawn_face_within_the_limit(self):
        facing = [(-1, -1, -10), (1, -1, -10), (0, 1, -10)]
        tilted = [(-1, -1, -10), (1, -1, -14), (0, 1, -10)]
        behind = [(-1, -1, 5), (1, -1, 5), (0, 1, 6)]
        positions = facing + tilted + behind
        s = zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), positions, range(9))
        expected = self.projected_gradient(self.M, tilted, 512, 512)
        self.assertEqual((s.triangle, s.counted, s.beyond_limit, s.culled), (1, 2, 0, 1))
        self.assertAlmostEqual(s.gradient, expected, delta=1e-6 * expected)
        limited = zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), positions,
                                       [(0, 1, 2), (3, 4, 5), (6, 7, 8)], limit=expected / 2)
        self.assertEqual((limited.triangle, limited.gradient, limited.beyond_limit), (0, 0.0, 1))
        # Passed on: the worst case's 1-pixel line term is the gradient.
        r = zshift.edge_offset(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM24, (9.0, 15.0),
                               zshift.EdgeMethod.MATRIX, face_gradient=s.gradient,
                               subpixel_bits=zshift.SUBPIXEL_UNSNAPPED)
        self.assertEqual(r.line_term, s.gradient)
        self.assertTrue(s.gradient <= s.length <= math.sqrt(2) * s.gradient, (s.gradient, s.length))

    def test_one_call_pays_less_than_the_angle(self):
        facing = [(-1, -1, -10), (1, -1, -10), (0, 1, -10)]
        tilted = [(-1, -1, -10), (1, -1, -14), (0, 1, -10)]
        kw = dict(face_angle=math.radians(60), subpixel_bits=zshift.SUBPIXEL_UNSNAPPED)
        args = (self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), zshift.Format.UNORM24, (9.0, 15.0),
                zshift.EdgeMethod.MATRIX)
        by_angle = zshift.edge_offset(*args, **kw)
        by_mesh = zshift.edge_offset_for_mesh(*args, self.M, facing + tilted, range(6), **kw)
        face = zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), facing + tilted, range(6),
                                    limit=by_angle.face_gradient)
        self.assertLess(by_mesh.window_offset, by_angle.window_offset)
        self.assertEqual(by_mesh.face_gradient, face.gradient)
        with self.assertRaises(TypeError):
            zshift.edge_offset_for_mesh(*args, self.M, facing, range(3), no_such_argument=1)

    def test_numpy_arrays_as_engines_hold_them(self):
        import numpy

        positions = [(-1, -1, -10), (1, -1, -10), (0, 1, -10), (-1, -1, -10), (1, -1, -14), (0, 1, -10)]
        by_list = zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), positions, range(6))
        by_numpy = zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), numpy.array(positions),
                                        numpy.arange(6, dtype=numpy.int64).reshape(2, 3))
        self.assertEqual(by_list, by_numpy)
        with self.assertRaises(zshift.ZshiftError):
            zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (512, 512), numpy.array(positions),
                                 numpy.array([0, 1, -2]))

    def test_bad_inputs_are_named(self):
        tri = [(0, 0, -5), (1, 0, -5), (0, 1, -5)]
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (64, 64), tri, [0, 1, 3])
        self.assertIn("indices", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (64, 64), tri, [0, 1, 2], limit=-1.0)
        self.assertIn("limit", str(caught.exception))
        with self.assertRaises(TypeError):
            zshift.steepest_face(self.M, zshift.Clip.NEG_ONE_TO_ONE, (64, 64), [(0, 0)], [0, 0, 0])
