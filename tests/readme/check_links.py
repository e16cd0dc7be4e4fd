"""Checks that every relative link in README.md and docs/*.md reaches something: a file or folder
of the repository, and, where the link names an anchor (`path#anchor` or `#anchor`), a heading of
the target markdown file whose GitHub anchor it is.

GitHub makes a heading's anchor by lowercasing it, dropping everything but letters, digits,
spaces, hyphens and underscores (after removing backticks), and turning spaces into hyphens; a
repeated heading gets `-1`, `-2`, ... A link into a heading that was renamed or lost (a section
dropped in an edit, docs/edges.md's "Drawn as engines draw" once) then fails here instead of
landing on the top of the page. Links to the web (`http`, `https`, `mailto`) are not followed.
Run from anywhere (scripts/test runs it).
"""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LINK = re.compile(r"\]\(([^()\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def anchors(path):
    """The GitHub anchors of every heading of a markdown file (outside fenced code)."""
    seen = {}
    out = set()
    fenced = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        m = None if fenced else HEADING.match(line)
        if not m:
            continue
        text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(2)).replace("`", "")
        slug = re.sub(r"[^\w\- ]", "", text.lower(), flags=re.UNICODE).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def links(path):
    """Every relative link target of a markdown file, outside fenced code."""
    fenced = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        for target in LINK.findall(line):
            if re.match(r"^(https?|mailto):", target):
                continue
            yield number, target


def main():
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    cache = {}
    failures = []
    count = 0
    for page in pages:
        for number, target in links(page):
            count += 1
            file, _, anchor = target.partition("#")
            dest = (page.parent / file).resolve() if file else page
            where = f"{page.relative_to(ROOT)}:{number}: {target}"
            if not dest.exists():
                failures.append(f"{where}: no such file")
                continue
            if anchor and dest.suffix == ".md":
                if dest not in cache:
                    cache[dest] = anchors(dest)
                if anchor not in cache[dest]:
                    failures.append(f"{where}: no heading with that anchor")
    if failures:
        print("\n".join(failures))
        print(f"{len(failures)} of {count} links in README.md and docs/ lead nowhere")
        return 1
    print(f"links: all {count} relative links in README.md and docs/ reach a file (and heading)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
