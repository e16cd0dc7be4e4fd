"""Checks that every quick start in README.md is code the tests build and run.

Test sources mark regions with `[quickstart-NAME]` ... `[/quickstart-NAME]` comment lines; each
region, dedented, must appear verbatim in README.md, and the README must quote every region.
Run from anywhere: python3 tests/readme/check_quickstarts.py
"""

import re
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# The sources that carry quick-start regions (the tests that build them are noted beside).
SOURCES = [
    "examples/c/legacy_gl.c",  # make -C examples/c check
    "examples/c/modern_gl.c",  # make -C examples/c check
    "examples/c/scene.c",  # make -C examples/c check
    "tests/cpp/wrapper_test.cpp",  # make -C tests/cpp check
    "bindings/python/tests/test_quickstart.py",  # python3 -m unittest discover ...
    "tests/packaging/run.sh",  # bash tests/packaging/run.sh
    "tests/packaging/CMakeLists.txt",  # bash tests/packaging/run.sh
    "tests/packaging/pip.sh",  # bash tests/packaging/pip.sh
    "examples/engines/common/decal_scene.h",  # make -C examples/engines check
    "examples/engines/osg/decal_osg.cpp",  # make -C examples/engines check
    "examples/engines/irrlicht/decal_irrlicht.cpp",  # make -C examples/engines check
    "examples/engines/ogre/decal_ogre.cpp",  # make -C examples/engines check
]

START = re.compile(r"\[quickstart-([a-z0-9-]+)\]")


def regions(path):
    """{name: dedented text} of the marked regions in one file."""
    found, current, lines = {}, None, []
    for line in (ROOT / path).read_text().splitlines():
        if current is not None and f"[/quickstart-{current}]" in line:
            found[current] = textwrap.dedent("\n".join(lines)).strip("\n")
            current, lines = None, []
        elif current is not None:
            lines.append(line)
        elif (match := START.search(line)) is not None:
            current = match.group(1)
    if current is not None:
        raise SystemExit(f"FAIL: {path}: [quickstart-{current}] is never closed")
    return found


def main():
    readme = (ROOT / "README.md").read_text()
    failures, count = [], 0
    for path in SOURCES:
        found = regions(path)
        if not found:
            failures.append(f"{path}: no [quickstart-...] region")
        for name, text in found.items():
            count += 1
            if text not in readme:
                failures.append(f"{path}: region {name} is not quoted verbatim in README.md:\n{text}")
    for failure in failures:
        print("FAIL:", failure, file=sys.stderr)
    if failures:
        return 1
    print(f"README quick starts: all {count} regions are quoted verbatim from the tested sources")
    return 0


if __name__ == "__main__":
    sys.exit(main())
