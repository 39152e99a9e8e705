#!/usr/bin/env bash
# Writes the corpus of files OpenFOAM itself writes: runs the small 3D case
# beside this script (cavity3d: a lid-driven box, 2,048 cells, simpleFoam,
# laminar, 30 iterations written at 10, 20 and 30, seconds in all) with the
# wall shear stress and the `surfaces` function object in VTK legacy and XML,
# then foamToVTK with and without -legacy and -one-boundary.
#   write_openfoam_files.sh OUT_DIR     (the case is OUT_DIR/cavity3d)
# OpenFOAM's binaries need only WM_PROJECT_DIR (Debian's etc/bashrc is broken).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:?usage: write_openfoam_files.sh OUT_DIR}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
case_dir=$out/cavity3d
rm -rf "$case_dir"
mkdir -p "$out"
cp -r "$here/cavity3d" "$case_dir"
cd "$case_dir"
run() {
  local name=$1
  shift
  "$@" > "log.$name" 2>&1 || {
    echo "write_openfoam_files: $name failed:" >&2
    tail -n 20 "log.$name" >&2
    exit 1
  }
}
run blockMesh blockMesh
run simpleFoam simpleFoam
run foamToVTK foamToVTK
run foamToVTK-one foamToVTK -name VTK-one -one-boundary
run foamToVTK-legacy foamToVTK -name VTK-legacy -legacy
run foamToVTK-legacy-one foamToVTK -name VTK-legacy-one -legacy -one-boundary
touch cavity3d.foam  # what ParaView opens a case by
