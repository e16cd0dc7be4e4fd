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

            n, f, pz = 0.1, 1000.0, -250.0  # near, far, the decal's eye-space z (negative)
            delta = 4 * zshift.min_delta_toward(n, f, 24, pz)  # four steps of a 24-bit depth buffer
            base = zshift.frustum(-n, n, -n, n, n, f)  # replaces glFrustum
            decal = zshift.load_offset_matrix(-n, n, -n, n, n, f, delta, pz)  # replaces LoadOffsetMatrix
            # moderngl: program["projection"].write(struct.pack("16f", *decal))

            try:
                zshift.load_offset_matrix(-n, n, -n, n, n, f, 300.0, pz)  # pz + delta > 0: behind the eye
            except zshift.ZshiftError as error:
                print(error.status.name, "-", error)  # DOMAIN - an input was outside the function's domain
            # [/quickstart-python]
        self.assertGreater(decal[10], base[10], "the decal moved toward the camera")
        self.assertEqual([decal[i] for i in range(16) if i != 10], [base[i] for i in range(16) if i != 10])
        self.assertEqual(printed.getvalue(), "DOMAIN - an input was outside the function's domain\n")


if __name__ == "__main__":
    unittest.main()
