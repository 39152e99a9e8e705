#!/usr/bin/env bash
# Wall shear stress on a motorbike and rider, computed with Debian's OpenFOAM
# (the simpleFoam motorBike tutorial of openfoam-examples), for ibfvs's
# oil-flow pictures (docs/cfd.md). Not part of the set-up: it takes 7 to 15
# minutes on two cores. Output in git-ignored data/cfd/motorBike:
#   motorBike.foam            the case, for ibfvs and ParaView (time 100..500)
#   VTK/                      foamToVTK of the last time: the bike's patches
#   motorBike.vtp             the same surface, one file: wallShearStress, p, yPlus, U
#                             (cell data)
#
# Usage: scripts/cfd_motorbike.sh [ITERATIONS]   (default 500, the tutorial's)
# IBFVS_CFD_DIR=FOLDER puts the case elsewhere.
#
# Differences from the tutorial's Allrun: 2 MPI ranks instead of 6; no
# potentialFoam (it diverges in Debian's 1912 build; simpleFoam starts from
# the uniform 20 m/s instead); no streamline, cutting-plane or EnSight
# function objects; wallShearStress and yPlus computed at every written time.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
iterations="${1:-500}"
case_dir="${IBFVS_CFD_DIR:-$root/data/cfd/motorBike}"  # IBFVS_CFD_DIR: elsewhere
examples=/usr/share/doc/openfoam-examples/examples
tutorial="$examples/incompressible/simpleFoam/motorBike"
me=cfd_motorbike
# log and run
# shellcheck source=scripts/cfd_common.sh
source "$root/scripts/cfd_common.sh"

if ! command -v simpleFoam > /dev/null || [[ ! -d $tutorial ]]; then
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  log "installing Debian's openfoam and openfoam-examples"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    openfoam openfoam-examples > /dev/null
fi
# OpenFOAM's environment (its utilities need it; the script complains about
# helper scripts Debian does not ship, harmlessly).
# shellcheck disable=SC1091
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1 || true
set -u
mpi=(mpiexec -n 2)
[[ $(id -u) -eq 0 ]] && mpi=(mpiexec --allow-run-as-root -n 2)
mpi+=(--oversubscribe)

start=$(date +%s)
rm -rf "$case_dir"
mkdir -p "$case_dir"
cp -r "$tutorial"/. "$case_dir"/
cd "$case_dir"
gunzip -f system/snappyHexMeshDict.gz 2> /dev/null || true
mkdir -p constant/triSurface
cp "$examples/resources/geometry/motorBike.obj.gz" constant/triSurface/
# Two ranks; no heavy function objects; the iteration count.
cat > system/decomposeParDict << 'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains 2;
method hierarchical;
coeffs { n (2 1 1); }
EOF
sed -i -e '/#include "streamLines"/d' -e '/#include "wallBoundedStreamLines"/d' \
  -e '/#include "cuttingPlane"/d' -e '/#include "ensightWrite"/d' \
  -e "s/^endTime .*/endTime         $iterations;/" system/controlDict
interval=$((iterations / 5))
((interval < 1)) && interval=1
sed -i "s/^writeInterval .*/writeInterval   $interval;/" system/controlDict

run surfaceFeatureExtract surfaceFeatureExtract
run blockMesh blockMesh
run decomposePar decomposePar
run snappyHexMesh "${mpi[@]}" snappyHexMesh -parallel -overwrite
for p in processor*; do
  rm -rf "$p/0"
  cp -r 0.orig "$p/0"
done
run simpleFoam "${mpi[@]}" simpleFoam -parallel
run reconstructParMesh reconstructParMesh -constant
run reconstructPar reconstructPar
rm -rf processor*
run wallShearStress simpleFoam -postProcess -func wallShearStress -noZero
run yPlus simpleFoam -postProcess -func yPlus -noZero
touch motorBike.foam
run foamToVTK foamToVTK -latestTime -no-internal -one-boundary -patches '("motorBike.*")'
cp VTK/*/boundary.vtp motorBike.vtp  # VTK/<case folder name>_<time>/
end=$(date +%s)
cells=$(grep -oE 'cells: *[0-9]+' log.snappyHexMesh | tail -n1 || true)
log "done in $((end - start)) s (${cells:-cells: see log.snappyHexMesh}); the case: $case_dir/motorBike.foam"
