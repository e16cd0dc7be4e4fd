"""Parity between the three front ends: every C entry point that include/zshift.h declares has a
Python function (listed in ``zshift.__all__``) and a C++ wrapper in bindings/cpp/zshift.hpp, both
named after it without the ``zshift_`` prefix; and the Python package exports exactly its API."""

import re
import types
import unittest
from pathlib import Path

import zshift

ROOT = Path(__file__).resolve().parents[3]

# C name -> (Python name, C++ name) where a front end spells it differently. None are needed
# today: zshift_status_message is zshift.status_message and zshift::status_message (C++ also
# keeps its older spelling zshift::message); zshift_last_error is zshift.last_error and
# zshift::last_error.
# C entry points reached through another name: the stored cut is clip_to_frustum's world-space
# keywords in Python and an overload in C++.
RENAMED = {"zshift_clip_to_frustum_stored": ("clip_to_frustum", "clip_to_frustum")}


def c_functions():
    """The ``zshift_*`` functions include/zshift.h declares (declarations start at column 0)."""
    header = (ROOT / "include" / "zshift.h").read_text()
    return sorted(set(re.findall(r"^[A-Za-z][\w ]*?\**\s*\b(zshift_\w+)\(", header, re.M)))


def cpp_wrappers():
    """The names of the functions zshift.hpp defines at namespace level (column 0, not comments)."""
    hpp = (ROOT / "bindings" / "cpp" / "zshift.hpp").read_text()
    return set(re.findall(r"^(?!//)[A-Za-z][^\n(]*?\b(\w+)\(", hpp, re.M))


class Parity(unittest.TestCase):
    def test_the_header_parses(self):
        names = c_functions()
        self.assertGreaterEqual(len(names), 40, names)
        for name in ("zshift_frustum", "zshift_clip_to_frustum", "zshift_probe", "zshift_version"):
            self.assertIn(name, names)

    def test_every_c_entry_point_has_a_python_function_and_a_cpp_wrapper(self):
        cpp = cpp_wrappers()
        missing = []
        for name in c_functions():
            short = name[len("zshift_"):]
            py_name, cpp_name = RENAMED.get(name, (short, short))
            if not callable(getattr(zshift, py_name, None)) or py_name not in zshift.__all__:
                missing.append(f"{name}: no Python zshift.{py_name} in __all__")
            if cpp_name not in cpp:
                missing.append(f"{name}: no C++ zshift::{cpp_name}")
        self.assertEqual(missing, [], "\n".join(missing))

    def test_all_lists_exactly_the_public_api(self):
        public = {name for name in vars(zshift) if not name.startswith("_")}
        modules = sorted(name for name in public if isinstance(getattr(zshift, name), types.ModuleType))
        self.assertEqual(modules, [], "modules leak into the zshift namespace")
        self.assertEqual(sorted(set(zshift.__all__) - public), [], "__all__ names what does not exist")
        self.assertEqual(sorted(public - set(zshift.__all__)), [], "public names missing from __all__")
        self.assertEqual(len(zshift.__all__), len(set(zshift.__all__)), "__all__ repeats a name")


class Arguments(unittest.TestCase):
    """Keyword defaults as C documents them, enum names, and clip_to_frustum."""

    FRUSTUM = (-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0)
    M = zshift.frustum(*FRUSTUM)

    def test_subpixel_bits_has_no_default(self):
        with self.assertRaises(TypeError) as caught:
            zshift.recommend(self.FRUSTUM, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0))
        self.assertIn("GL_SUBPIXEL_BITS", str(caught.exception))
        with self.assertRaises(TypeError):
            zshift.decal_matrix(self.M, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0))
        # A profile supplies the snapping: then subpixel_bits may be left out.
        worst = zshift.profile_worst_case()
        self.assertEqual(
            zshift.recommend(self.FRUSTUM, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0), profile=worst),
            zshift.recommend(self.FRUSTUM, (1280, 720), zshift.Format.UNORM24, (40.0, 60.0), profile=worst,
                             subpixel_bits=worst.subpixel_bits))

    def test_corners_need_no_decal_depths(self):
        corners = [(-1.0, -3.0, -14.0), (1.0, -3.0, -14.0), (1.0, -1.0, -18.0), (-1.0, -1.0, -18.0)]
        decal = zshift.decal_matrix(self.M, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24,
                                    subpixel_bits=8, corners=corners)
        self.assertEqual([i for i in range(16) if decal[i] != self.M[i]], [10])
        with self.assertRaises(TypeError) as caught:
            zshift.decal_matrix(self.M, zshift.Clip.NEG_ONE_TO_ONE, (1280, 720), zshift.Format.UNORM24, subpixel_bits=8)
        self.assertIn("decal_depths", str(caught.exception))

    def test_enums_accept_members_and_names_and_list_the_members(self):
        by_member = zshift.projection(*self.FRUSTUM, zshift.Clip.ZERO_TO_ONE)
        self.assertEqual(list(zshift.projection(*self.FRUSTUM, "ZERO_TO_ONE")), list(by_member))
        self.assertEqual(list(zshift.projection(*self.FRUSTUM, "zero_to_one")), list(by_member))
        self.assertEqual(zshift.depth_step(1, 100, "zero_to_one", "unorm24", 50),
                         zshift.depth_step(1, 100, zshift.Clip.ZERO_TO_ONE, zshift.Format.UNORM24, 50))
        for bad in ("opengl", 1.5, None):
            with self.assertRaises(zshift.ZshiftError) as caught:
                zshift.projection(*self.FRUSTUM, bad)
            self.assertIn("Clip.NEG_ONE_TO_ONE, Clip.ZERO_TO_ONE, Clip.REVERSED_ZERO_TO_ONE", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.decal_matrix(self.M, "opengl", (1280, 720), zshift.Format.UNORM24, (40.0, 60.0), subpixel_bits=8)
        self.assertIn("clip = 'opengl'", str(caught.exception))
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.recommend(self.FRUSTUM, (1280, 720), "D24", (40.0, 60.0), subpixel_bits=8)
        self.assertIn("Format.UNORM24", str(caught.exception))

    def test_clip_to_frustum(self):
        # A ground 2 below the eye running from behind the camera to 500 ahead: cut in double,
        # every vertex inside the frustum (the near plane slightly in front).
        l, r, b, t, n, f = self.FRUSTUM
        ground = [(-100.0, -2.0, 100.0), (100.0, -2.0, 100.0), (100.0, -2.0, -500.0), (-100.0, -2.0, -500.0)]
        cut = zshift.clip_to_frustum(self.FRUSTUM, ground)
        self.assertGreaterEqual(len(cut), 3)
        for x, y, z in cut:
            self.assertEqual(y, -2.0)
            d = -z
            self.assertTrue(n < d <= f, d)
            self.assertTrue(l * d / n <= x <= r * d / n and b * d / n <= y <= t * d / n, (x, y, z))
        self.assertEqual(zshift.clip_to_frustum(self.FRUSTUM, [(0.0, 0.0, 5.0), (1.0, 0.0, 5.0), (0.0, 1.0, 5.0)]), [])
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.clip_to_frustum((1.0, 1.0, -1.0, 1.0, 1.0, 10.0), ground)
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)
        with self.assertRaises(TypeError):
            zshift.clip_to_frustum(self.FRUSTUM, [(0.0, 0.0)])

    def test_clip_to_frustum_stored_in_world_space(self):
        # The same ground stored in world space 10**4 from the origin (a view matrix that
        # translates by -10**4): the stored cut lies inside the plain one, by more near the
        # camera than far from it (the storage's error is absolute).
        l, r, b, t, n, f = self.FRUSTUM
        ground = [(-100.0, -2.0, 100.0), (100.0, -2.0, 100.0), (100.0, -2.0, -500.0), (-100.0, -2.0, -500.0)]
        view = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, -1e4, 0, -1e4, 1.0]
        box = ((1e4 - 100.0, -2.0, 1e4 - 500.0), (1e4 + 100.0, -2.0, 1e4 + 100.0))
        plain = zshift.clip_to_frustum(self.FRUSTUM, ground)
        stored = zshift.clip_to_frustum(self.FRUSTUM, ground, eye_first=True, view_matrix=view, world_box=box)
        self.assertNotEqual(stored, plain)
        nearest = lambda cut: min(-z for _, _, z in cut)
        self.assertGreater(nearest(stored), nearest(plain))
        for x, y, z in stored:
            d = -z
            self.assertTrue(n < d <= f and l * d / n < x < r * d / n, (x, y, z))
        by_reach = zshift.clip_to_frustum(self.FRUSTUM, ground, world_reach=1e4)
        self.assertGreater(nearest(by_reach), nearest(plain))
        with self.assertRaises(TypeError):
            zshift.clip_to_frustum(self.FRUSTUM, ground, view_matrix=view)
        with self.assertRaises(zshift.ZshiftError) as caught:
            zshift.clip_to_frustum(self.FRUSTUM, ground, world_reach=-1.0)
        self.assertEqual(caught.exception.status, zshift.Status.DOMAIN)


if __name__ == "__main__":
    unittest.main()
