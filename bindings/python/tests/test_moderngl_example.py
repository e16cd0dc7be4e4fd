"""Runs examples/decal_moderngl.py: zshift's matrix in a real GL 3.3 pipeline from Python (moderngl
over headless EGL), checking its own pixels. scripts/setup installs moderngl; without it this test
fails with the reason (a GL test never skips)."""

import importlib.util
import os
import subprocess
import sys
import unittest
from pathlib import Path

PYTHON_DIR = Path(__file__).resolve().parents[1]


class ModernglExample(unittest.TestCase):
    def test_decal_example_keeps_every_decal_pixel(self):
        self.assertIsNotNone(importlib.util.find_spec("moderngl"),
                             "moderngl is not installed: run scripts/setup (scripts/test does)")
        env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
        done = subprocess.run(
            [sys.executable, str(PYTHON_DIR / "examples" / "decal_moderngl.py")],
            env=env, capture_output=True, text=True, timeout=120,
        )
        self.assertEqual(done.returncode, 0, f"stdout: {done.stdout}\nstderr: {done.stderr}")
        self.assertIn("with zshift", done.stdout)


if __name__ == "__main__":
    unittest.main()
