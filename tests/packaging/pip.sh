#!/usr/bin/env bash
# `pip install .` as a new user does it: a copy of the source tree with no target/ (no earlier
# cargo build), a fresh venv, no ZSHIFT_LIBRARY, no PYTHONPATH. The build backend (setuptools-rust,
# from PyPI) compiles the Rust library and puts it inside the package; then `import zshift` must
# load that copy, and the moderngl decal example (headless EGL) must render with it and pass.
# PYTHON is the interpreter the venv is made from (default: the project venv's, made by scripts/setup).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
work=$root/target/pip-test
python=${PYTHON:-$root/.venv/bin/python}
rm -rf "$work"
mkdir -p "$work/src"
unset ZSHIFT_LIBRARY PYTHONPATH CARGO_TARGET_DIR
fail() { echo "FAIL: $*" >&2; exit 1; }
[ -x "$python" ] || fail "$python is missing: run scripts/setup (it makes the project venv), or set PYTHON"

# The files a clone has (tracked, plus new files git does not ignore): no target/, no .venv.
git ls-files -z --cached --others --exclude-standard | xargs -0 -I{} sh -c '[ -f "{}" ] && echo "{}"' \
  | tar -cf - -T - | tar -xf - -C "$work/src"
[ ! -e "$work/src/target" ] || fail "the source copy has a target/ directory"

"$python" -m venv "$work/venv"
(
  cd "$work/src"
  export PATH="$work/venv/bin:$PATH"
  # [quickstart-use-python]
  pip install . && python -c "import zshift; print(zshift.version(), zshift.library_path())"  # Python (in a venv; run in this repository)
  # [/quickstart-use-python]
) 2>&1 | tee "$work/install.log" | tail -n 3
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "pip install . failed (log: $work/install.log)"

cd "$work"  # away from the source tree: only the installed package can be imported
loaded=$("$work/venv/bin/python" -c "import zshift; print(zshift.library_path())")
case "$loaded" in
  "$work/venv/lib/"*/site-packages/zshift/_zshift*) echo "import zshift loads the packaged library: $loaded" ;;
  *) fail "import zshift loaded $loaded, not the library inside the installed package" ;;
esac

"$work/venv/bin/python" -m pip install --quiet moderngl
"$work/venv/bin/python" "$work/src/bindings/python/examples/decal_moderngl.py"
echo "pip: a fresh venv installs zshift from source and renders the moderngl decal with it"
