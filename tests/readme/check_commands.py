"""Checks that every shell command README.md and docs/*.md show names things that exist, and that
the suite runs what each one runs.

Each line of a ```sh / ```bash block (continuation lines joined, comments dropped, split at `&&`)
is resolved by what it invokes:

- `cargo test ... --test NAME`: tests/NAME.rs exists (scripts/test's `cargo test --workspace
  --all-targets` runs it); `--example NAME`: examples/NAME.rs or examples/NAME/main.rs; `-p PKG`:
  a workspace member; `--bench NAME`: benches/NAME.rs (built by `--all-targets`); `--bin NAME`:
  a binary of that package.
- `scripts/NAME [args]`: the script exists, is executable, and, where it takes flags, accepts the
  ones shown (its usage text names them).
- `make ... -C DIR TARGET`: DIR/Makefile defines TARGET.
- `.venv/bin/python PATH` or `PYTHONPATH=... .venv/bin/python PATH`: PATH exists; `-m unittest
  discover -s DIR`: DIR exists.
- `cc`/`c++`/`cmake`/`pkg-config`/`cd`/`./app`/`pip`/`python -c`: lines of the consumer recipe,
  which tests/packaging/run.sh and pip.sh run verbatim (check_quickstarts.py checks those blocks
  are exact quotes of them); they are accepted when their block is such a quote.
- `xvfb-run ... CMD`: CMD is resolved as above.

A line this script cannot resolve fails: a command that names a test, example, script or target
that no longer exists is a stale command. Run from anywhere (scripts/test runs it).
"""

import re
import shlex
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Programs of the consumer recipe, run verbatim by the packaging tests (quoted blocks only).
RECIPE = {"cd", "cc", "c++", "cmake", "pkg-config", "./app_c", "pip", "python"}


def blocks(path):
    """(line number, previous line, body) of every sh/bash fenced block."""
    text = path.read_text()
    for m in re.finditer(r"```(?:sh|bash)\n(.*?)```", text, re.S):
        line = text.count("\n", 0, m.start()) + 1
        before = text[: m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        yield line, before, m.group(1)


def commands(body):
    """The commands of a block: continuations joined, comments dropped, split at `&&`."""
    joined = re.sub(r"\\\n\s*", " ", body)
    for raw in joined.split("\n"):
        line = raw.split(" #", 1)[0].strip()
        if not line or line.startswith("#"):
            continue
        for part in line.split("&&"):
            part = part.strip()
            if part:
                yield part


def words(command):
    try:
        w = shlex.split(command)
    except ValueError:
        w = command.split()
    # Leading environment assignments (VAR=value) are not the program.
    while w and re.match(r"^[A-Z_][A-Z0-9_]*=", w[0]):
        w = w[1:]
    return w


def workspace_members():
    members = {"zshift"}
    for cargo in ROOT.glob("*/Cargo.toml"):
        m = re.search(r'^name\s*=\s*"([^"]+)"', cargo.read_text(), re.M)
        if m:
            members.add(m.group(1))
    for cargo in ROOT.glob("tests/*/Cargo.toml"):
        m = re.search(r'^name\s*=\s*"([^"]+)"', cargo.read_text(), re.M)
        if m:
            members.add(m.group(1))
    return members


def check_cargo(w):
    def value(flag):
        return w[w.index(flag) + 1] if flag in w and w.index(flag) + 1 < len(w) else None

    if (name := value("--test")) and not (ROOT / "tests" / f"{name}.rs").exists():
        return f"no tests/{name}.rs"
    if (name := value("--example")) and not (
        (ROOT / "examples" / f"{name}.rs").exists() or (ROOT / "examples" / name / "main.rs").exists()
    ):
        return f"no example {name}"
    if (name := value("--bench")) and not (ROOT / "benches" / f"{name}.rs").exists():
        return f"no benches/{name}.rs"
    if (name := value("-p")) and name not in workspace_members():
        return f"no workspace member {name}"
    if (name := value("--bin")) and not list(ROOT.glob(f"**/src/bin/{name}.rs")):
        return f"no binary {name}"
    return None


def check_script(w):
    script = ROOT / w[0]
    if not script.exists():
        return f"no {w[0]}"
    text = script.read_text()
    for flag in (a for a in w[1:] if a.startswith("--")):
        if flag not in text:
            return f"{w[0]} does not take {flag}"
    return None


def check_make(w):
    directory = w[w.index("-C") + 1] if "-C" in w else "."
    makefile = ROOT / directory / "Makefile"
    if not makefile.exists():
        return f"no {directory}/Makefile"
    targets = [a for a in w[1:] if not a.startswith("-") and a != directory]
    for t in targets:
        if not re.search(rf"^{re.escape(t)}\s*:", makefile.read_text(), re.M):
            return f"{directory}/Makefile has no target {t}"
    return None


def check_python(w):
    args = w[1:]
    if args[:3] == ["-m", "unittest", "discover"]:
        directory = args[args.index("-s") + 1] if "-s" in args else "."
        return None if (ROOT / directory).is_dir() else f"no {directory}"
    if args and args[0] == "-c":
        return None
    return None if args and (ROOT / args[0]).exists() else f"no {args[0] if args else '?'}"


def resolve(command, quoted):
    w = words(command)
    if not w:
        return None
    if w[0] == "xvfb-run":
        rest = [a for a in w[1:] if not a.startswith("-")]
        # xvfb-run's own option values (-s '-screen ...') come as separate words.
        while rest and rest[0] not in ("cargo",) and not rest[0].startswith(("scripts/", "./")):
            rest = rest[1:]
        w = rest
    program = w[0]
    if program == "cargo":
        return check_cargo(w)
    if program.startswith("scripts/"):
        return check_script(w)
    if program == "make":
        return check_make(w)
    if program.endswith("bin/python") or program in ("python3",):
        return check_python(w)
    if program in RECIPE or program.startswith("./"):
        return None if quoted else f"{program}: a recipe line outside a quoted block"
    return f"unknown program {program}"


def main():
    files = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
    failures, count = [], 0
    for path in files:
        for line, before, body in blocks(path):
            quoted = "<!-- quote:" in before
            for command in commands(body):
                count += 1
                problem = resolve(command, quoted)
                if problem:
                    failures.append(f"{path.relative_to(ROOT)}:{line}: {command!r}: {problem}")
    for f in failures:
        print("FAIL:", f)
    if failures:
        sys.exit(1)
    print(f"README and docs: all {count} shell commands name tests, examples, scripts and targets that exist")


if __name__ == "__main__":
    main()
