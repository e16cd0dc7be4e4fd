"""Checks that the code README.md and docs/*.md quote is exact, current code the tests build and run.

The convention: a fenced code block right after an HTML comment line

    <!-- quote: path/to/file -->

is a quote of that file (a path from the repository root). It must be an exact copy of a
contiguous run of the file's lines, less the run's common indentation (a region inside a
function may be quoted dedented); a stale or edited copy fails. Every C, C++, Python and CMake
block (```c, ```cpp, ```python, ```cmake) must be such a quote, or say why it is not with
`<!-- sketch: why -->` (a fragment no test compiles).

Test sources also mark regions with `[quickstart-NAME]` ... `[/quickstart-NAME]` comment lines
(SOURCES below); every region must be quoted, whole, somewhere in README.md or docs/.
Run from anywhere: .venv/bin/python tests/readme/check_quickstarts.py (scripts/test runs it).
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
    "bindings/python/tests/test_quickstart.py",  # .venv/bin/python -m unittest discover ...
    "tests/packaging/run.sh",  # bash tests/packaging/run.sh
    "tests/packaging/CMakeLists.txt",  # bash tests/packaging/run.sh
    "tests/packaging/pip.sh",  # bash tests/packaging/pip.sh
    "examples/engines/common/decal_scene.h",  # make -C examples/engines check
    "examples/engines/osg/decal_osg.cpp",  # make -C examples/engines check
    "examples/engines/osg/edges_osg.cpp",  # make -C examples/engines check
    "examples/engines/irrlicht/decal_irrlicht.cpp",  # make -C examples/engines check
    "examples/engines/ogre/decal_ogre.cpp",  # make -C examples/engines check
]

START = re.compile(r"\[quickstart-([a-z0-9-]+)\]")
QUOTE = re.compile(r"^<!--\s*quote:\s*(\S+)\s*-->\s*$")
SKETCH = re.compile(r"^<!--\s*sketch:.*-->\s*$")
FENCE = re.compile(r"^(\s*)```(\w*)\s*$")
MUST_QUOTE = {"c", "cpp", "c++", "python", "cmake"}


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


def blocks(doc):
    """(line number, language, marker line or None, block lines) of every fenced block in doc."""
    lines = (ROOT / doc).read_text().splitlines()
    found, i = [], 0
    while i < len(lines):
        match = FENCE.match(lines[i])
        if match is None:
            i += 1
            continue
        start, language = i, match.group(2)
        j = i + 1
        while j < len(lines) and not FENCE.match(lines[j]):
            j += 1
        if j == len(lines):
            raise SystemExit(f"FAIL: {doc}:{start + 1}: a code block is never closed")
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        marker = lines[k] if k >= 0 and (QUOTE.match(lines[k]) or SKETCH.match(lines[k])) else None
        found.append((start + 1, language, marker, lines[start + 1:j]))
        i = j + 1
    return found


def is_contiguous_copy(block, source):
    """Whether `block` equals a contiguous run of `source`'s lines less one common indentation."""
    while block and not block[0].strip():
        block = block[1:]
    while block and not block[-1].strip():
        block = block[:-1]
    if not block:
        return False
    first = block[0]
    for i, line in enumerate(source):
        if i + len(block) > len(source) or not line.endswith(first):
            continue
        indent = line[: len(line) - len(first)]
        if indent.strip():
            continue
        if all((not want.strip() and not got.strip()) or got == indent + want
               for want, got in zip(block, source[i:i + len(block)])):
            return True
    return False


def docs():
    return ["README.md"] + sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs").glob("*.md"))


def main():
    failures, quoted_texts, count = [], [], 0
    for doc in docs():
        for line_no, language, marker, block in blocks(doc):
            quote = QUOTE.match(marker) if marker else None
            if quote is None:
                if language.lower() in MUST_QUOTE and marker is None:
                    failures.append(f"{doc}:{line_no}: a ```{language} block with neither "
                                    "<!-- quote: path --> nor <!-- sketch: why --> before it")
                continue
            count += 1
            path = quote.group(1)
            source = ROOT / path
            if not source.is_file():
                failures.append(f"{doc}:{line_no}: quotes {path}, which does not exist")
                continue
            if not is_contiguous_copy(block, source.read_text().splitlines()):
                failures.append(f"{doc}:{line_no}: the block quoted from {path} is not an exact, current "
                                f"copy of a contiguous region of it:\n" + "\n".join(block))
            quoted_texts.append("\n".join(block))
    everything = "\n\n".join(quoted_texts)
    regions_count = 0
    for path in SOURCES:
        found = regions(path)
        if not found:
            failures.append(f"{path}: no [quickstart-...] region")
        for name, text in found.items():
            regions_count += 1
            if not is_contiguous_copy(text.splitlines(), everything.splitlines()):
                failures.append(f"{path}: region {name} is quoted nowhere in README.md or docs/:\n{text}")
    for failure in failures:
        print("FAIL:", failure, file=sys.stderr)
    if failures:
        return 1
    print(f"README and docs: all {count} quoted blocks are exact copies of their sources; "
          f"all {regions_count} quick-start regions are quoted")
    return 0


if __name__ == "__main__":
    sys.exit(main())
