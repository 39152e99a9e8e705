#!/usr/bin/env bash
# Wall shear stress of a small simpleFoam tutorial of Debian's
# openfoam-examples, computed serially, for ibfvs's real-data comparisons
# beside the motorbike (docs/quality.md): windAroundBuildings (buildings and
# the ground: sharp edges, stagnation on the faces, a wake) and squareBend (a
# duct bending 90 degrees: walls seen from outside, secondary flow). Not part
# of the set-up; about 1-5 minutes each on two cores. Output in git-ignored
# data/cfd/CASE:
#   CASE.foam   the case, for ibfvs and ParaView (its written times)
#   CASE.vtp    the wall patches at the last time, one file: wallShearStress,
#               p, U (cell data), from foamToVTK
#
# Usage: scripts/cfd_case.sh CASE [ITERATIONS]   (default: the tutorial's)
# IBFVS_CFD_DIR=FOLDER puts the case elsewhere.
#
# Differences from the tutorial: wallShearStress computed at every written
# time; the snappyHexMesh cases mesh serially (as their Allrun.pre does).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
name="${1:?usage: scripts/cfd_case.sh windAroundBuildings|squareBend [ITERATIONS]}"
iterations="${2:-}"
examples=/usr/share/doc/openfoam-examples/examples
tutorial="$examples/incompressible/simpleFoam/$name"
case_dir="${IBFVS_CFD_DIR:-$root/data/cfd/$name}"
me=cfd_case
# shellcheck source=scripts/cfd_common.sh
source "$root/scripts/cfd_common.sh"

if [[ -d $examples ]] && [[ ! -d $tutorial ]]; then
  echo "cfd_case: no simpleFoam tutorial $name in $examples/incompressible/simpleFoam" >&2
  exit 1
fi
need_openfoam simpleFoam "$tutorial"

start=$(date +%s)
copy_tutorial "$tutorial" "$case_dir"
[[ -n $iterations ]] && sed -i "s/^endTime .*/endTime         $iterations;/" system/controlDict

[[ -f system/surfaceFeatureExtractDict ]] && run surfaceFeatureExtract surfaceFeatureExtract
run blockMesh blockMesh
[[ -f system/snappyHexMeshDict ]] && run snappyHexMesh snappyHexMesh -overwrite
[[ -d 0.orig && ! -d 0 ]] && cp -r 0.orig 0
run simpleFoam simpleFoam
run wallShearStress simpleFoam -postProcess -func wallShearStress -noZero
touch "$name.foam"
# The wall patches (type wall in the mesh's boundary file), one surface.
walls="$(wall_patches) "
[[ -n $walls ]] || { echo "cfd_case: $name has no wall patches" >&2; exit 1; }
run foamToVTK foamToVTK -latestTime -no-internal -one-boundary -patches "(${walls% })"
cp VTK/*/boundary.vtp "$name.vtp"  # VTK/<case folder name>_<time>/
end=$(date +%s)
log "done in $((end - start)) s; walls: $walls; the case: $case_dir/$name.foam"
