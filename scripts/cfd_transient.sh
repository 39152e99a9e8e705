#!/usr/bin/env bash
# A transient or moving-mesh pimpleFoam tutorial of Debian's
# openfoam-examples, shortened to minutes on two cores and run serially, for
# ibfvs's comparisons over time (docs/cfd.md, "Time"). Output in git-ignored
# data/cfd/CASE:
#   CASE.foam      the case with every written time (a moving mesh's points
#                  per time too), for ibfvs and ParaView
#   CASE.vtm.series ParaView's file series of the wall patches at every
#                  written time, from foamToVTK (TJunction; the mixer's front
#                  face is an empty patch, which foamToVTK leaves out)
#
# Usage: scripts/cfd_transient.sh TJunction|mixerVesselAMI2D|propeller|propellerMotion
#   TJunction         pimpleFoam/RAS/TJunction: a T-junction of square ducts,
#                     the inlet pressure rising 10 -> 40 over the first second;
#                     fixed walls, wallShearStress at every written time
#                     (endTime 1.5 s, 16 times; the tutorial's own), on a mesh
#                     twice as fine as the tutorial's (10 cells across a duct)
#   mixerVesselAMI2D  pimpleFoam/laminar/mixerVesselAMI2D: a rotor turning
#                     once a second inside a baffled tank, started from rest,
#                     its cells and points rotating (solid-body motion with an
#                     arbitrary mesh interface); the front face of the slab
#                     with U on it (endTime 1 s, written every 0.05 s: 21 times)
#   propeller         pimpleFoam/RAS/propeller: a three-bladed propeller turning
#                     at 158 rad/s inside an arbitrary mesh interface, its
#                     cells and points rotating; snappyHexMesh two levels
#                     coarser than the tutorial's, started from rest, written
#                     every 0.32 ms (2.9 degrees of turn) to 6.4 ms: 21 times
#                     (Courant number 0.8, not 2, on the coarser mesh);
#                     wallShearStress on its walls at every written time
#   propellerMotion   the propeller's mesh (its blades and its turning
#                     interface AMI1: faces of three to seven points, a
#                     third of the blades' polygons of five or more), turned
#                     by moveDynamicMesh alone (no flow: the test of a moving
#                     machine's steps, tests/corpus), 2.9 degrees a step for
#                     5 steps: 6 times, each with the cell centres C (a real
#                     vector array at every time)
# IBFVS_CFD_DIR=FOLDER puts the case elsewhere.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
name="${1:?usage: scripts/cfd_transient.sh TJunction|mixerVesselAMI2D|propeller|propellerMotion}"
resources=/usr/share/doc/openfoam-examples/examples/resources
examples=/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam
case "$name" in
  TJunction)
    tutorial=$examples/RAS/TJunction end="" write="" patches="" ;;
  mixerVesselAMI2D)
    tutorial=$examples/laminar/mixerVesselAMI2D end=1 write=0.05 patches="front" ;;
  propeller)
    tutorial=$examples/RAS/propeller end=0.0064 write=0.00032 patches="" ;;
  propellerMotion)
    tutorial=$examples/RAS/propeller end=0.0016 write=0.00032 patches="" ;;
  *)
    echo "cfd_transient: no case $name (TJunction, mixerVesselAMI2D, propeller or propellerMotion)" >&2
    exit 1 ;;
esac
case_dir="${IBFVS_CFD_DIR:-$root/data/cfd/$name}"
me=cfd_transient
# shellcheck source=scripts/cfd_common.sh
source "$root/scripts/cfd_common.sh"
need_openfoam pimpleFoam "$tutorial"

start=$(date +%s)
copy_tutorial "$tutorial" "$case_dir"
[[ -n $end ]] && sed -i "s/^endTime .*/endTime         $end;/" system/controlDict
[[ -n $write ]] && sed -i "s/^writeInterval .*/writeInterval   $write;/" system/controlDict

[[ -f system/blockMeshDict.m4 ]] && m4 system/blockMeshDict.m4 > system/blockMeshDict
[[ $name == TJunction ]] &&
  sed -i 's/(50 5 5)/(100 10 10)/; s/(5 5 5)/(10 10 10)/; s/(5 50 5)/(10 100 10)/g' system/blockMeshDict
run blockMesh blockMesh
if [[ $name == propeller* ]]; then
  # The tutorial's Allrun.pre, its refinement two levels coarser, and no
  # function objects (Q, sampled surfaces, forces, AMI weights: minutes).
  cp "$resources/geometry/propellerTip.obj.gz" constant/triSurface/
  sed -i 's/level       4;/level       2;/; s/level       (4 4);/level       (2 2);/;
          s/level       (4 5);/level       (2 3);/; s/levels      ((1E15 3));/levels      ((1E15 1));/' \
    system/snappyHexMeshDict
  # Courant 0.8, not 2: on the coarser mesh the tutorial's step diverges.
  sed -i '/#includeFunc/d; /#include "/d; s/^maxCo .*/maxCo           0.8;/' system/controlDict
  if [[ $name == propellerMotion ]]; then
    # One time step a write.
    sed -i "s/^deltaT .*/deltaT          $write;/; s/^writeControl .*/writeControl    timeStep;/;
            s/^writeInterval .*/writeInterval   1;/; s/^adjustTimeStep .*/adjustTimeStep  no;/" \
      system/controlDict
  fi
  run surfaceFeatureExtract surfaceFeatureExtract
  run snappyHexMesh snappyHexMesh -overwrite
  rm -rf 0
  run topoSet topoSet -dict system/createInletOutletSets.topoSetDict
  run createPatch createPatch -overwrite
fi
[[ -f system/topoSetDict ]] && run topoSet topoSet
[[ -d 0.orig && ! -d 0 ]] && cp -r 0.orig 0
if [[ $name == propellerMotion ]]; then
  run moveDynamicMesh moveDynamicMesh
  run writeCellCentres postProcess -func writeCellCentres -noZero
else
  run pimpleFoam pimpleFoam
fi
# The wall patches (type wall in the mesh's boundary file), unless the case
# names its own (a 2D case's front face).
touch "$name.foam"
if [[ -z $patches && $name != propellerMotion ]]; then
  patches=$(wall_patches)
  run wallShearStress pimpleFoam -postProcess -func wallShearStress -noZero
  run foamToVTK foamToVTK -no-internal -one-boundary -patches "(${patches})"
  # Beside the case, its names made relative to it.
  sed 's#"name" *: *"#&VTK/#' VTK/*.series > "$name.vtm.series"
fi
end_s=$(date +%s)
times=$(ls -d [0-9]* | wc -l)
log "done in $((end_s - start)) s; $times written times; patches: $patches; the case: $case_dir/$name.foam"
