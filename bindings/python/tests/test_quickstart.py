"""The README's Python quick start, run as written (the marked region is quoted verbatim there)."""

import contextlib
import io
import unittest


class QuickStart(unittest.TestCase):
    def test_quickstart(self):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            # [quickstart-python]
            import zshift

            frustum = (-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0)  # the base's glFrustum(l, r, b, t, n, f)
            base = zshift.frustum(*frustum)  # replaces glFrustum
            decal = zshift.recommend_matrix(  # replaces LoadOffsetMatrix, with the offset a rasterizer needs
                frustum, viewport=(1280, 720), depth_format=zshift.GL_DEPTH_COMPONENT24,
                decal_depths=(40.0, 60.0),  # the decal's nearest and farthest eye distance
                slope=1.0,  # |dz/dx| + |dz/dy| of its plane in eye space
                subpixel_bits=8)  # glGetIntegerv(GL_SUBPIXEL_BITS)
            # moderngl: program["projection"].write(struct.pack("16f", *decal))

            try:
                zshift.load_offset_matrix(*frustum, 300.0, -250.0)  # delta, pz: pz + delta > 0 is behind the eye
            except zshift.ZshiftError as error:
                print(error.status.name, "-", error)  # DOMAIN - the shifted depth Pz + delta must stay ... (Pz + delta = 50)
            # [/quickstart-python]
        self.assertGreater(decal[10], base[10], "the decal moved toward the camera")
        self.assertEqual([decal[i] for i in range(16) if i != 10], [base[i] for i in range(16) if i != 10])
        self.assertEqual(printed.getvalue(),
                         "DOMAIN - the shifted depth Pz + delta must stay in front of the eye (< 0) (Pz + delta = 50)\n")

    def test_ground_quickstart(self):
        import zshift
        engine_projection = zshift.frustum(-0.1778, 0.1778, -0.1, 0.1, 0.1, 1000.0)
        # [quickstart-ground-python]
        # A 2x2 decal on the ground, 10 ahead of a level camera 1.7 above it; the ground (+-1000,
        # one quad) runs behind the camera. Corners in eye space (after the view matrix).
        decal = zshift.decal_matrix(
            engine_projection, zshift.Clip.NEG_ONE_TO_ONE,
            viewport=(1920, 1080), depth_format=zshift.Format.UNORM24_STENCIL8,
            corners=[(-1, -1.7, -9), (1, -1.7, -9), (1, -1.7, -11), (-1, -1.7, -11)],
            base_reach=1415.0,  # the ground's largest eye-space |x|, |y|, |z|: the rasterizer clips it
            depth_test="LEQUAL",  # the decal pass's glDepthFunc
            subpixel_bits=8)  # glGetIntegerv(GL_SUBPIXEL_BITS)
        # World-space vertices through a float view matrix: add world_reach= (the camera's
        # distance from the origin), or view_matrix= and world_box= for the exact terms.
        # [/quickstart-ground-python]
        self.assertGreater(decal[10], engine_projection[10], "the decal moved toward the camera")
        self.assertEqual([decal[i] for i in range(16) if i != 10],
                         [engine_projection[i] for i in range(16) if i != 10])

    def test_entity_quickstart(self):
        import zshift
        engine_projection = zshift.frustum(-0.1778, 0.1778, -0.1, 0.1, 0.1, 1000.0)
        # [quickstart-entity-python]
        # A decal entity 5000 from the world's origin: a unit quad through its own model matrix,
        # its model-view V*M multiplied in double and rounded once to float32. Tell zshift the
        # camera's view matrix and a box holding the ground's cells under the decal and its
        # corners (V*M multiplied in float32: world_reach alone, no view_matrix).
        camera_view = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -5000, -1.7, -5000, 1]  # column-major
        decal = zshift.decal_matrix(
            engine_projection, zshift.Clip.NEG_ONE_TO_ONE,
            viewport=(1920, 1080), depth_format=zshift.Format.UNORM24_STENCIL8,
            corners=[(-1, -1.7, -9), (1, -1.7, -9), (1, -1.7, -11), (-1, -1.7, -11)],  # eye space
            depth_test="LEQUAL", subpixel_bits=8,
            world_reach=5000.0, eye_first=True,  # proj * (modelView * p) in the shader
            view_matrix=camera_view, world_box=((4996, 0, 4988), (5004, 0, 4992)))
        # [/quickstart-entity-python]
        self.assertGreater(decal[10], engine_projection[10], "the decal moved toward the camera")
        self.assertEqual([decal[i] for i in range(16) if i != 10],
                         [engine_projection[i] for i in range(16) if i != 10])


if __name__ == "__main__":
    unittest.main()
