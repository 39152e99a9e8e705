"""Filters > Skin-Friction Topology in pvpython (test_plugin.py has the
display and the runs): a sphere whose flow spirals out of its poles onto its
equator, as a series of two times, the second reversed. The filter gives the
issue's cells at each time (transient data plays as with any filter), the
foci keeping their ids from one time to the next; its separation line shows
over the IBFVS representation along the equator in the filter's own colours,
and the representation's Overlay draws the same line itself.
"""
import json
import math
from pathlib import Path

import numpy as np

from test_plugin import image, on_display, pytestmark, sphere, why, write_vtp, xvfb  # noqa: F401
from test_plugin import PLUGIN

SCRIPT = Path(__file__).parent / "pv" / "topology.py"


def spiral_series(directory):
    """The sphere of radius 0.5 (ParaView's Sphere's), its flow turning about
    +Z and pulled onto z = 0 (time 0), then pushed off it (time 1)."""
    pts, tris, _ = sphere()
    pts = 0.5 * pts
    p = pts / np.linalg.norm(pts, axis=1)[:, None]
    z = p[:, 2:3]
    entries = []
    for k, pull in enumerate([1.0, -1.0]):
        v = np.cross([0.0, 0.0, 1.0], p) - pull * z * (np.array([0.0, 0.0, 1.0]) - z * p)
        write_vtp(directory / ("spiral_%d.vtp" % k), pts, tris, {"spiral": v})
        entries.append('<DataSet timestep="%d" file="spiral_%d.vtp"/>' % (k, k))
    pvd = directory / "spiral.pvd"
    pvd.write_text('<?xml version="1.0"?><VTKFile type="Collection" version="0.1"><Collection>%s'
                   "</Collection></VTKFile>" % "".join(entries))
    return pvd


def test_the_filter_finds_the_features_at_every_time_and_shows_them(tmp_path):
    cfg = {"plugin": PLUGIN, "data": str(spiral_series(tmp_path)),
           "vectors": ["POINTS", "spiral"], "out": str(tmp_path / "shot.png"),
           "overlay_out": str(tmp_path / "overlay.png"), "camera": [3.0, 0.0, 0.8]}
    done = on_display(["pvpython", str(SCRIPT), json.dumps(cfg)])
    assert done.returncode == 0, why(done)
    line = [s for s in done.stdout.splitlines() if s.startswith("ibfvs-test: ")]
    assert line, why(done)
    found = json.loads(line[0][len("ibfvs-test: "):])
    assert [f["time"] for f in found] == [0.0, 1.0]
    # Time 0: two repelling foci and the equator a closed separation line;
    # time 1, reversed: attracting foci and an attachment line.
    assert found[0]["kinds"] == [5, 5, 10], found[0]["summary"]
    assert found[1]["kinds"] == [4, 4, 11], found[1]["summary"]
    for f in found:
        assert f["line_z"] < 0.01  # on the equator (edges about 0.016 at radius 0.5)
        assert "index sum 2 (Euler characteristic 2)" in f["summary"]
    # The foci persist (their index the same, their kind reversed): their ids
    # go on; the line's kind changes, so it is a new feature.
    assert found[1]["ids"][:2] == found[0]["ids"][:2], found
    assert found[1]["ids"][2] not in found[0]["ids"], found
    for shot in ("shot.png", "overlay.png"):
        expect_the_equator(image(tmp_path / shot), shot)


def expect_the_equator(img, shot):
    """The red line across the middle of the sphere, over the texture; none
    of it above or below."""
    h, w, _ = img.shape
    # The overlay's legend (bottom left, with a red swatch): left out.
    img = img.copy()
    img[int(0.8 * h):, : int(0.45 * w)] = img[0, 0]
    ball = np.abs(img - img[0, 0]).sum(axis=2) > 30  # not the background (the corner's)
    ys, xs = np.nonzero(ball)
    middle, radius = (ys.min() + ys.max()) / 2.0, (xs.max() - xs.min()) / 2.0
    assert radius > 40
    red = (img[..., 0] > 180) & (img[..., 1] < 70) & (img[..., 2] < 70)
    rows = np.flatnonzero(red.any(axis=1))
    assert len(rows), "no separation line in " + shot
    # The equator seen from 15 degrees above: the front half of an ellipse
    # a little below the middle (sin 15 = 0.26 of the radius at most).
    assert rows.min() > middle - 0.05 * radius and rows.max() < middle + 0.35 * radius, (shot, rows)
    columns = np.flatnonzero(red.any(axis=0))
    assert columns.max() - columns.min() > 1.8 * radius, shot  # across the sphere
    # The texture still shows beside it (the IBFVS representation drawn).
    g = img.mean(axis=2)
    assert np.abs(np.diff(g[: h // 3], axis=1)).mean() > 1.0
