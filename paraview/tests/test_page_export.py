"""File > Export Scene's "ibfvs web page (*.html)" (ExportView in Python):
the page exported from a view, opened in headless chromium
(web/test/shoot.mjs), against the view's own pictures: alignment with the
true flow within 0.03 of the view's, the hue of ParaView's colours at every
pixel, the view's background; a series plays its steps; bad input is one
error line and no file. Run with test_plugin.py (its helpers and display).
"""
import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from test_plugin import (IBFVS, MPIEXEC, PLUGIN, ROOT, grown,  # noqa: F401
                         hue_difference, image, local_contrast, mask_of, on_display, pytestmark,
                         run, sphere, why, write_pieces, write_vtp, xvfb)
from test_plugin_series import alignment, swirl_series, true_direction, turning_series

NODE = shutil.which("node")
SHOOT = ROOT / "web" / "test" / "shoot.mjs"
browser = pytest.mark.skipif(
    not (NODE and shutil.which("chromium") and IBFVS and
         (ROOT / "web" / "node_modules" / "puppeteer-core").exists()),
    reason="needs node, chromium, web/node_modules and the ibfvs command (IBFVS_EXE)")

SIZE = (320, 240)
Z = np.array([0.0, 0.0, 1.0])


@pytest.fixture(scope="module")
def swirl(tmp_path_factory):
    """The sphere in a swirl about +Z (v), with a point scalar (height), a
    vector of magnitude 0.3 to 1.4 for a log scale (w) and a cell scalar in
    bands of longitude, either end of its range in turn (band); and in two
    pieces for two ranks (sphere.pvtp)."""
    d = tmp_path_factory.mktemp("swirl")
    pts, tris, arrays = sphere()
    centre = pts[tris].mean(axis=1)
    bands = 10 * (np.floor(12 * (np.arctan2(centre[:, 1], centre[:, 0]) / np.pi + 1)) % 2)
    bands += centre[:, 2]
    write_vtp(d / "swirl.vtp", pts, tris,
              {"v": np.cross(Z, pts), "w": arrays["v"], "height": arrays["height"]},
              {"band": bands})
    write_pieces(d, pts, tris, {"v": np.cross(Z, pts), "height": arrays["height"]})
    return d


def shoot(page, png, frames=60, time=0.0):
    """The page's canvas in chromium, paused at `frames` frames and `time`
    steps: its state (frames, time, steps)."""
    done = subprocess.run([NODE, str(SHOOT), str(page), str(png), str(frames), str(time)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(done.stdout.splitlines()[-1])


CASES = {
    "point-scalar": {"color": ["POINTS", "height"]},
    "log-scale": {"color": ["POINTS", "w"], "lut": {"UseLogScale": 1}},
    "cell-scalar": {"color": ["CELLS", "band"]},
    # pvbatch under MPI: each rank holds a piece; the page, the whole surface.
    "two-ranks": {"color": ["POINTS", "height"], "data": "sphere.pvtp", "ranks": 2},
}


def header_of(page):
    return json.loads(page.read_text().split('id="ibfvs-scene">', 1)[1].split("</script>")[0])


@browser
@pytest.mark.parametrize("case", list(CASES))
def test_the_page_shows_the_view(swirl, tmp_path, case):
    """The page exported from a view coloured through ParaView's colour map
    (a point scalar, a vector's magnitude on a log scale, a cell scalar; two
    ranks' pieces) shows what the view shows: the whole surface, the texture
    as aligned with the flow, the same hue at every pixel of the surface,
    the view's background around."""
    cfg = dict(CASES[case])
    ranks = cfg.pop("ranks", 1)
    if ranks > 1 and MPIEXEC is None:
        pytest.skip("needs mpiexec")
    page = tmp_path / "view.html"
    cfg.update({"data": str(swirl / cfg.get("data", "swirl.vtp")), "vectors": ["POINTS", "v"],
                "frames": 60, "shots": [60], "mask": True, "size": list(SIZE),
                "export": {"file": str(page)}})
    done, out = run(cfg, tmp_path, ranks=ranks)
    assert "ibfvs-test: exported" in done.stdout, done.stdout + done.stderr
    # The sphere's 36,096 triangles, all of them (not one rank's piece).
    assert header_of(page)["index_count"] == 3 * 36096
    shot = tmp_path / "page.png"
    state = shoot(page, shot, 60)
    assert state["steps"] == 1
    view, drawn, mask = image(out + "-60.png"), image(shot), mask_of(out)
    assert drawn.shape == view.shape
    direction = true_direction(tmp_path / "direction.png", Z, SIZE)
    a_view, a_page = alignment(out + "-60.png", direction), alignment(shot, direction)
    d, share = hue_difference(drawn, view, mask)
    print(case, "A and W: view", a_view, "page", a_page, "hue difference median %.2f, 99th "
          "percentile %.2f degrees over %.0f%% of the surface" % (
              np.median(d), np.percentile(d, 99), 100 * share))
    assert a_page["A"] > 0.9, a_page
    assert abs(a_page["A"] - a_view["A"]) <= 0.03, (a_view, a_page)
    assert share > 0.4, share
    assert np.median(d) < 2.0 and np.percentile(d, 99) < 12.0, (np.median(d),
                                                                np.percentile(d, 99))
    # The texture over the colour, and the view's background around the
    # surface where the view has it.
    assert local_contrast(drawn, mask) > 4
    outside = ~grown(mask, 2)
    assert (np.abs(drawn[outside] - view[outside]).max(axis=-1) <= 2).mean() > 0.99


def exported_series(pvd, frames_per_step, tmp_path):
    """The page of a series (.pvd) shown with IBFVS: its path and header."""
    page = tmp_path / (pvd.stem + ".html")
    done, _ = run({"data": str(pvd), "vectors": ["POINTS", "v"], "frames": 2,
                   "size": list(SIZE), "properties": {"FramesPerStep": frames_per_step},
                   "export": {"file": str(page)}}, tmp_path)
    assert "ibfvs-test: exported" in done.stdout, done.stdout + done.stderr
    return page, header_of(page)


@browser
def test_a_series_plays_its_steps_in_the_page(tmp_path):
    """The swirl turning 30 degrees a step, exported over its four times: the
    page holds the four steps and plays them; as it reaches a step its
    texture follows that step's flow, not the step before."""
    pvd, axes = swirl_series(tmp_path, steps=4, turn=30.0)
    page, header = exported_series(pvd, 24, tmp_path)
    assert header["steps"] == 4 and header["frames_per_step"] == 24
    assert "motion" not in header["arrays"]  # the points stay
    measured = []
    for k in (1, 3):
        shot = tmp_path / ("step%d.png" % k)
        state = shoot(page, shot, 0, k)
        assert k <= state["time"] < k + 0.2, state
        own = alignment(shot, true_direction(tmp_path / ("d%d.png" % k), axes[k], SIZE))
        before = alignment(shot, true_direction(tmp_path / ("b%d.png" % k), axes[k - 1], SIZE))
        measured.append((k, own, before))
    print("series: at step k, A against step k's flow and against step k-1's", measured)
    for k, own, before in measured:
        assert own["A"] > 0.85 and own["A"] > before["A"] + 0.02, (k, own, before)


@browser
def test_a_moving_surface_plays_in_the_page(tmp_path):
    """The sphere turning 20 degrees a step about +X in a swirl about +Z that
    stays (its points move, its triangles stay): the page holds the points
    of every step and plays them, its texture aligned with the flow."""
    page, header = exported_series(turning_series(tmp_path), 12, tmp_path)
    assert header["steps"] == 4 and "motion" in header["arrays"]
    direction = true_direction(tmp_path / "direction.png", Z, SIZE)
    for k in (1, 3):
        shot = tmp_path / ("step%d.png" % k)
        state = shoot(page, shot, 0, k)
        a = alignment(shot, direction)
        # Measured A 0.97 at the steps reached. (Between the last step and
        # the first the page, as ibfvs render, plays on into the first
        # step's points: 60 degrees back, A 0.86 half way.)
        print("a turning body at time", state["time"], "A and W", a)
        assert k <= state["time"] < k + 0.2 and a["A"] > 0.93, (state, a)


def test_file_export_scene_offers_the_page(tmp_path):
    """The GUI's File > Export Scene lists the formats ParaView's export
    helper gives for the view: the page is among them, with its name."""
    script = tmp_path / "formats.py"
    script.write_text(
        "from paraview.simple import *\n"
        "from paraview import servermanager\n"
        "LoadPlugin(%r, remote=False, ns=globals())\n"
        "view = GetActiveViewOrCreate('RenderView')\n"
        "print(servermanager.vtkSMViewExportHelper().GetSupportedFileTypes(view.SMProxy))\n"
        % PLUGIN)
    done = on_display(["pvpython", str(script)], cwd=tmp_path)
    assert done.returncode == 0, why(done)
    assert "ibfvs web page (*.html)" in done.stdout.split(";;"), done.stdout


def test_a_still_surface_beside_a_series_is_one_step(swirl, tmp_path):
    """A steady surface in a session where another source has six times (the
    time keeper's times are theirs): the page holds the surface once, not six
    copies."""
    pvd, _ = swirl_series(tmp_path, steps=6)
    page = tmp_path / "still.html"
    done, _ = run({"data": str(swirl / "swirl.vtp"), "vectors": ["POINTS", "v"], "frames": 2,
                   "size": list(SIZE), "also_open": str(pvd), "export": {"file": str(page)}},
                  tmp_path)
    assert "ibfvs-test: exported" in done.stdout, done.stdout + done.stderr
    assert header_of(page)["steps"] == 1


def test_bad_input_is_one_error_line_and_no_file(swirl, tmp_path):
    """No IBFVS representation visible, a scene over the page's limit, a name
    that is not NAME.html: ParaView's error, one line, and no file."""
    base = {"data": str(swirl / "swirl.vtp"), "vectors": ["POINTS", "v"], "frames": 2,
            "size": list(SIZE)}
    cases = [
        ("surface", {"representation": "Surface"}, "surface.html",
         "no IBFVS representation is visible in the view"),
        ("large", {}, "large.html", "more than a page takes"),
        ("name", {}, "name.txt", "Failed to create exporter"),
    ]
    for name, extra, file, expected in cases:
        export = {"file": str(tmp_path / file)}
        if name == "large":
            export["properties"] = {"MaximumTriangles": 1000}
        done, _ = run(dict(base, name=name, export=export, **extra), tmp_path)
        said = [l for l in (done.stdout + done.stderr).splitlines() if expected in l]
        assert len(said) == 1, (name, done.stdout + done.stderr)
        assert not (tmp_path / file).exists(), name
        print(name, said[0])
        if name != "name":
            assert "ERR|" in said[0] and str(tmp_path / file) in said[0], said[0]
