"""Every file the real tools write opens in ibfvs and shows texture.

The corpus is made during the test by the tools themselves: ParaView's and
VTK's writers under pvpython (write_vtk_files.py: every XML kind in every
encoding, legacy ASCII and binary in both layouts, .pvd, .series,
multiblock, partitioned, ParaView's parallel files) and OpenFOAM on a small
3D case (write_openfoam_files.sh: the case itself, the `surfaces` function
object's walls in VTK legacy and XML at three times, foamToVTK with and
without -legacy and -one-boundary, their .series files). For each file,
`ibfvs render` must exit 0 and give a picture with texture on the surface.
The rule it guards: ibfvs never refuses a file that VTK reads.

Debian's Python with numpy runs it; it never imports ParaView (one VTK per
process). Environment: IBFVS_EXE (the built ibfvs), set by CTest.
"""
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).parent
EXE = os.environ.get("IBFVS_EXE", "")
SIZE = 160


def image(path):
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", str(path), "-f", "rawvideo",
                          "-pix_fmt", "rgb24", "-"], capture_output=True, check=True).stdout
    return np.frombuffer(raw, np.uint8).reshape(SIZE, SIZE, 3).astype(int)


def textured(img):
    """What the picture shows: the share of the image the surface covers
    (pixels unlike the background, read at the corners) and the mean
    difference between neighbouring surface pixels (texture has it; a plain
    shaded surface hardly any)."""
    background = np.median(np.stack([img[0, 0], img[0, -1], img[-1, 0], img[-1, -1]]), axis=0)
    surface = np.abs(img - background).max(axis=-1) > 6
    inside = surface[:, 1:] & surface[:, :-1]
    grey = img.mean(axis=-1)
    contrast = np.abs(np.diff(grey, axis=1))[inside].mean() if inside.any() else 0.0
    return surface.mean(), contrast


def render(path, array, out):
    """`ibfvs render` of one file with its array as the field; the problem,
    or None."""
    png = out / (str(path).replace("/", "_") + ".png")
    done = subprocess.run([EXE, "render", "--mesh", str(path), "--field", "file:" + array,
                           "--frames", "24", "--size", "%dx%d" % (SIZE, SIZE), "--out", str(png)],
                          capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        return "exit %d: %s" % (done.returncode, done.stderr.strip()[-400:])
    covered, contrast = textured(image(png))
    if covered < 0.03:
        return "the surface covers %.1f%% of the picture" % (100 * covered)
    if contrast < 4.0:
        return "no texture on the surface (neighbour contrast %.1f)" % contrast
    return None


def check_all(files, array, tmp_path):
    """`files`: paths, or (path, array) pairs for those with another array."""
    pairs = [f if isinstance(f, tuple) else (f, array) for f in files]
    problems = {str(f): render(f, a, tmp_path) for f, a in pairs}
    bad = {f: p for f, p in problems.items() if p}
    assert not bad, "%d of %d files:\n%s" % (len(bad), len(files),
                                             "\n".join("%s: %s" % kv for kv in bad.items()))


needs_exe = pytest.mark.skipif(not (EXE and Path(EXE).exists()), reason="needs IBFVS_EXE")


@pytest.fixture(scope="module")
def vtk_corpus(tmp_path_factory):
    if not shutil.which("pvpython"):
        pytest.skip("needs ParaView's pvpython")
    out = tmp_path_factory.mktemp("vtk")
    done = subprocess.run(["pvpython", str(HERE / "write_vtk_files.py"), str(out)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]


@pytest.fixture(scope="module")
def openfoam_case(tmp_path_factory):
    if not shutil.which("simpleFoam"):
        pytest.skip("needs OpenFOAM (Debian's openfoam)")
    out = tmp_path_factory.mktemp("openfoam")
    done = subprocess.run([str(HERE / "write_openfoam_files.sh"), str(out)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return out / "cavity3d"


@needs_exe
def test_every_file_paraview_and_vtk_write_opens_with_texture(vtk_corpus, tmp_path):
    files = [Path(w["file"]) for w in vtk_corpus]
    kinds = {w["kind"] for w in vtk_corpus}
    # The corpus is what it claims: every kind of file, each there.
    for kind in ("polydata", "unstructured grid", "image data", "structured grid",
                 "rectilinear grid", "multiblock", "partitioned", "partitioned collection",
                 "paraview .pvtp", "paraview .pvtu", "paraview .pvd", ".series time series"):
        assert kind in kinds, kind
    assert len(files) > 60 and all(f.exists() for f in files)
    check_all(files, "v", tmp_path)


@needs_exe
def test_every_file_openfoam_writes_opens_with_texture(openfoam_case, tmp_path):
    case = openfoam_case
    post = sorted((case / "postProcessing").glob("walls_vt*/*/walls.vt*"))
    # The surfaces function object, three times, in both formats; the
    # XML one as OpenFOAM writes it (comment first, UInt64 headers).
    assert len(post) == 6, post
    vtp = next(p for p in post if p.suffix == ".vtp").read_text(errors="replace")
    assert "<!--" in vtp.split("<VTKFile")[0] and "header_type='UInt64'" in vtp
    series = sorted(case.glob("VTK*/*.series"))
    assert len(series) == 4, series  # .vtm.series (XML) and .vtk.series (legacy)
    # Every file foamToVTK wrote but the volume alone (internal.vtu: its
    # outer surface carries the cells' values, not the walls'); at time 0
    # there is no wall shear stress yet, so those show U.
    written = [p for p in case.glob("VTK*/**/*.vt*")
               if p.name != "internal.vtu" and p.suffix != ".series"]
    at_zero = [(p, "U") for p in written
               if any(part.endswith("_0") or part.endswith("_0.vtk") or part.endswith("_0.vtm")
                      for part in p.parts)]
    later = [p for p in written if (p, "U") not in at_zero]
    assert len(later) > 20 and len(at_zero) > 5
    files = post + series + later + at_zero + [case, case / "cavity3d.foam"]
    check_all(files, "wallShearStress", tmp_path)


@needs_exe
def test_a_series_of_openfoam_steps_plays_through_its_times(openfoam_case, tmp_path):
    """foamToVTK's .series: time 0 has no wall shear stress yet, so the
    series starts at the first time that has it, and says so."""
    png = tmp_path / "series.png"
    done = subprocess.run([EXE, "render", "--mesh", str(openfoam_case / "VTK" / "cavity3d.vtm.series"),
                           "--field", "file:wallShearStress", "--frames", "20", "--size", "64x64",
                           "--out", str(png)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "step 0 has no 'wallShearStress'; starting at step 1" in done.stderr
