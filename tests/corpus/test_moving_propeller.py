"""A rotating machine as OpenFOAM writes it plays with every step moving.

The propeller tutorial's mesh (scripts/cfd_transient.sh propellerMotion:
snappyHexMesh, then OpenFOAM's moveDynamicMesh turning its inner region
2.9 degrees a step, 5 steps, with the cell centres C written at each: a
real vector array at every time) is played by `ibfvs render` as a user
plays it:

- its blades (triangles, quadrilaterals and polygons of five to seven
  points), 4 frames a step, with a field of the scene's (rotate:): every
  frame turns the blades by a quarter of a step, none stands still and none
  jumps (a series once played only with a field from its file);
- its turning interface AMI1 (a cylinder of cut cells), one frame a step:
  at every step change the texture turns with it, not left in the image.
  Before the polygons' splits were kept from step to step
  (core/mesh/polygon.h), nearly straight corners there split otherwise at
  every step, and each step played as a surface of its own: it stood still
  and its texture stayed in the image.

The measures are scripts/turn_measure.py's. Debian's Python with numpy runs
it; ffmpeg decodes the pictures.
Environment: IBFVS_EXE (the built ibfvs), set by CTest.
"""
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import turn_measure  # noqa: E402  (scripts/turn_measure.py: the measure docs/cfd.md gives)

EXE = os.environ.get("IBFVS_EXE", "")
STEP_DEGREES = np.degrees(158.0 * 0.00032)  # the tutorial's omega, a written step
STEPS = 5


def case_key(name):
    """What the case is made from: the scripts and OpenFOAM's version (its
    tutorials come with it)."""
    h = hashlib.sha256(name.encode())
    for script in ("cfd_transient.sh", "cfd_common.sh"):
        h.update((ROOT / "scripts" / script).read_bytes())
    version = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "openfoam"],
                             capture_output=True, text=True)
    h.update(version.stdout.encode())
    return h.hexdigest()[:16]


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    """The case as scripts/cfd_transient.sh makes it (about two minutes of
    snappyHexMesh), kept under IBFVS_TEST_CACHE (default ~/.cache/ibfvs) by
    what it is made from, so that a second run copies it: the meshing is
    OpenFOAM's work, the reading and playing are what is tested."""
    cache = Path(os.environ.get("IBFVS_TEST_CACHE", Path.home() / ".cache" / "ibfvs"))
    kept = cache / ("propellerMotion-" + case_key("propellerMotion"))
    folder = tmp_path_factory.mktemp("propeller") / "propellerMotion"
    if kept.is_dir():
        shutil.copytree(kept, folder)
        return folder / "propellerMotion.foam"
    done = subprocess.run([str(ROOT / "scripts" / "cfd_transient.sh"), "propellerMotion"],
                          env=dict(os.environ, IBFVS_CFD_DIR=str(folder)),
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    try:  # whole or absent: copied aside, then renamed
        cache.mkdir(parents=True, exist_ok=True)
        part = Path(tempfile.mkdtemp(dir=cache))
        try:
            shutil.copytree(folder, part / "case")
            (part / "case").rename(kept)
        finally:
            shutil.rmtree(part, ignore_errors=True)
    except OSError as e:
        print("the case is not kept:", e)
    return folder / "propellerMotion.foam"


def frames(case, out, blocks, field, per_step, count):
    """`ibfvs render` of the case seen along its axis, against magenta: the
    frames' paths."""
    out.mkdir()
    done = subprocess.run(
        [EXE, "render", "--mesh", str(case), "--blocks", blocks, "--field", field,
         "--camera", "0,89,0", "--frames-per-step", str(per_step), "--frames", str(count),
         "--size", "320x320", "--background", "1,0,1", "--out", str(out / "f%04d.png")],
        capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return [str(out / ("f%04d.png" % k)) for k in range(count)]


def test_every_frame_turns_the_blades(case, tmp_path):
    per_step = 4
    expected = STEP_DEGREES / per_step
    rows = turn_measure.measure(
        frames(case, tmp_path / "blades", "propeller*", "rotate:0,1,0", per_step,
               (STEPS - 1) * per_step + 1),
        expected)
    turns = [turn for turn, _, _ in rows]
    print("blades, degrees a frame (a step is %.2f, %d frames a step):" % (STEP_DEGREES, per_step),
          " ".join("%.2f" % t for t in turns))
    sign = np.sign(np.median(turns))
    for k, t in enumerate(turns):
        assert 0.6 * expected < sign * t < 1.4 * expected, (
            "frame %d -> %d turns %.2f degrees, not about %.2f: %s" % (
                k, k + 1, t, sign * expected, turns))


def test_the_texture_turns_with_the_interface_at_every_step(case, tmp_path):
    rows = turn_measure.measure(frames(case, tmp_path / "interface", "AMI1", "file:C", 1, STEPS),
                                STEP_DEGREES)
    print("the interface, each step change: turned with it / left in place:",
          "; ".join("%d: %.3f / %.3f" % (k + 1, w, l) for k, (_, w, l) in enumerate(rows)))
    for k, (_, with_it, left) in enumerate(rows):
        if k == 0:
            continue  # the first change: the texture is still forming
        assert with_it > left + 0.1 and with_it > 0.5, (
            "step %d: the texture turned with the interface correlates %.3f, left in the image "
            "%.3f" % (k + 1, with_it, left))
