"""PyVista's trame backend (docs/python.md, "trame"): with server-side
rendering a real trame server animates the texture, seen in Debian's
headless chromium; client-side rendering (vtk.js) cannot draw it and says
so, once."""

import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import pyvista as pv
from PIL import Image

import ibfvs.pyvista
from local_server import free_port, wait_until_up
from test_pyvista import alignment, radius_map, swirl_sphere

ROOT = Path(__file__).resolve().parents[2]
pytest.importorskip("trame_pyvista")
SIZE = (320, 240)



def test_server_side_rendering_animates_the_texture_in_the_browser(tmp_path):
    for tool in ("node", "/usr/bin/chromium"):
        if not shutil.which(tool):
            pytest.skip(f"{tool} is not installed")
    port = free_port()
    log = open(tmp_path / "server.log", "w")
    server = subprocess.Popen([sys.executable, str(Path(__file__).with_name("flow_in_trame.py")),
                               str(port), str(SIZE[0]), str(SIZE[1])],
                              cwd=tmp_path, stdout=log, stderr=subprocess.STDOUT)
    try:
        url = f"http://localhost:{port}/"
        wait_until_up(url, server, tmp_path / "server.log", "trame")
        a, b = tmp_path / "a.png", tmp_path / "b.png"
        run = subprocess.run(["node", str(ROOT / "web" / "test" / "trame.mjs"), url,
                              f"{SIZE[0]}x{SIZE[1]}", str(a), str(b)],
                             capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, (run.stdout + run.stderr)[-3000:] + "\nserver: " + \
            (tmp_path / "server.log").read_text()[-3000:]
    finally:
        server.terminate()
        server.wait(30)
    first = np.asarray(Image.open(a).convert("RGB"))
    second = np.asarray(Image.open(b).convert("RGB"))
    assert first.shape[:2] == (SIZE[1], SIZE[0])
    r, _ = radius_map(SIZE)
    surface, outside = r < 0.9, r > 1.05
    # The server's pictures come as JPEG: the background near white, the
    # texture along the swirl and moving from one picture to the next.
    assert first[outside].min(axis=1).mean() > 245, "texture off the sphere"
    assert (first[surface] > 245).all(axis=1).mean() < 0.01, "background on the sphere"
    measured = alignment(first, tmp_path, "trame")
    assert measured["A"] > 0.85, measured
    change = np.abs(first.astype(int) - second.astype(int)).mean(axis=2)
    assert change[surface].mean() > 3.0, "the texture stood still between the pictures"


def test_client_side_rendering_warns_once_that_it_draws_the_plain_surface(tmp_path):
    """vtk.js gets the plain surface (PyVista's export_html serializes the
    scene as trame's client mode does): one warning that says so and what
    to use instead."""
    p = pv.Plotter(off_screen=True, window_size=(64, 64))
    p.ibfvs.add_flow(swirl_sphere(32), vectors="swirl")
    p.show(auto_close=False)
    ibfvs.pyvista._FlowMapper.told = False
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        p.export_html(tmp_path / "scene.html")
        p.export_html(tmp_path / "again.html")
    told = [w for w in seen if "client-side rendering" in str(w.message)]
    assert len(told) == 1, [str(w.message) for w in seen]
    assert "mode='server'" in str(told[0].message) and "ibfvs.widget" in str(told[0].message)
    assert (tmp_path / "scene.html").stat().st_size > 1000
