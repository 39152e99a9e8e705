"""The live notebook widget (ibfvs.widget, python/ibfvs/notebook.py) in a real
JupyterLab server, driven in Debian's headless chromium by
web/test/notebook.mjs; and its Python side without a browser."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import ibfvs
from local_server import free_port, wait_until_up

ROOT = Path(__file__).resolve().parents[2]
anywidget = pytest.importorskip("anywidget")

# The notebook's one cell: the widget, and Python's answers to the page.
CELL = """\
import json
from pathlib import Path
import ibfvs

w = ibfvs.widget(mesh="torus", field="rotate:0,0,1", size=(256, 256))
heard = []

def answer(change):
    heard.append([change["name"], change["new"]])
    Path("heard.json").write_text(json.dumps(heard))
    if change["name"] != "beta":
        return
    if abs(change["new"] - 0.2) < 1e-6:
        w.alpha = 0.37                 # Python to the running page
    elif abs(change["new"] - 0.5) < 1e-6:
        w.set(background=(1, 0, 0))   # a new scene: the page starts again

w.observe(answer, names=["beta", "playing"])
w
"""


def _notebook(path):
    path.write_text(json.dumps({
        "cells": [{"cell_type": "code", "execution_count": None, "id": "widget", "metadata": {},
                   "outputs": [], "source": CELL}],
        "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                    "name": "python3"}},
        "nbformat": 4, "nbformat_minor": 5}))



def test_the_widget_and_python_change_each_others_settings_in_jupyterlab(tmp_path):
    pytest.importorskip("jupyterlab")
    for tool in ("node", "/usr/bin/chromium"):
        if not shutil.which(tool):
            pytest.skip(f"{tool} is not installed")
    _notebook(tmp_path / "widget.ipynb")
    port, token = free_port(), "ibfvs-test"
    # Jupyter's own folders in the test's (not the user's: their kernels
    # and settings); the venv's kernel and extensions are found in the venv.
    env = dict(os.environ, JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"),
               JUPYTER_CONFIG_DIR=str(tmp_path / "config"),
               JUPYTER_DATA_DIR=str(tmp_path / "data"),
               JUPYTERLAB_SETTINGS_DIR=str(tmp_path / "settings"),
               JUPYTERLAB_WORKSPACES_DIR=str(tmp_path / "workspaces"))
    env.pop("VTK_DEFAULT_OPENGL_WINDOW", None)
    log = open(tmp_path / "server.log", "w")
    server = subprocess.Popen(
        [sys.executable, "-m", "jupyterlab", "--no-browser", "--ip=127.0.0.1", f"--port={port}",
         f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={tmp_path}",
         "--LabApp.expose_app_in_browser=True", "--allow-root"],
        cwd=tmp_path, env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        base = f"http://127.0.0.1:{port}"
        wait_until_up(f"{base}/api/status?token={token}", server, tmp_path / "server.log",
                      "JupyterLab")
        result = tmp_path / "result.json"
        run = subprocess.run(
            ["node", str(ROOT / "web" / "test" / "notebook.mjs"),
             f"{base}/lab/tree/widget.ipynb?token={token}", str(result)],
            capture_output=True, text=True, timeout=600)
        seen = json.loads(result.read_text()) if result.exists() else {}
        heard_file = tmp_path / "heard.json"
        heard = json.loads(heard_file.read_text()) if heard_file.exists() else []
        assert run.returncode == 0, (run.stdout + run.stderr)[-3000:] + "\nheard: " + str(heard) \
            + "\nserver: " + (tmp_path / "server.log").read_text()[-3000:]
    finally:
        server.terminate()
        server.wait(30)
    # The page animates, with the surface in it.
    assert seen["animates"] and 0.2 < seen["covered"] < 0.95, seen
    # The page's sliders reached Python, in order; Pause and Play too.
    assert heard[0] == ["beta", pytest.approx(0.2)], heard
    assert ["playing", False] in heard and ["playing", True] in heard, heard
    assert ["beta", pytest.approx(0.5)] in heard, heard
    # Python's alpha reached the running page, which went on without restarting.
    assert seen["alpha_in_page"] == pytest.approx(0.37, abs=0.006) and seen["frames_on"], seen
    assert seen["pause_held"], seen
    # Python's new scene (a red background) restarted the page with the
    # settings as they were.
    assert seen["corner_before"][0] < 200 and seen["corner_after"][0] > 200, seen
    assert seen["alpha_after_restart"] == pytest.approx(0.37, abs=0.006), seen
    assert seen["beta_after_restart"] == pytest.approx(0.5, abs=0.006), seen
    assert not seen["errors"], seen["errors"]


def test_the_widget_starts_from_the_scene_and_refuses_what_the_page_cannot_take():
    w = ibfvs.widget(mesh="torus", field="rotate:0,0,1", size=(64, 64), alpha=0.2, step=2.5)
    # The scene's own look is the page's first ("as rendered": no style's own).
    assert (w.alpha, w.step, w.look) == (pytest.approx(0.2), pytest.approx(2.5), "as rendered")
    assert w.speed is None and w.loop is None and w.playing
    assert json.loads(w.scene)["width"] == 64 and len(w.data) > 1000
    assert w._esm.startswith("var ") or "export" in w._esm
    assert "ibfvs-panel" in w._css
    w.alpha = 0.5
    assert w.animation is not None and w.settings["alpha"] == 0.5
    for name, value, words in [("alpha", 2.0, "outside"), ("beta", float("nan"), "not a number"),
                               ("look", "nonesuch", "not one of this page's styles"),
                               ("loop", True, "one time step")]:
        with pytest.raises(ValueError, match=words):
            setattr(w, name, value)
    with pytest.raises(TypeError, match="unknown option"):
        w.set(nonesuch=1)
    with pytest.raises(ValueError, match="profile"):
        w.set(profile="nonesuch")
    with pytest.raises(TypeError):
        ibfvs.widget(w.animation, alpha=0.3)
    # A key the page cannot change live: a new scene, the settings kept.
    old = w.scene
    w.set(background=(1, 0, 0))
    assert w.scene != old and w.alpha == pytest.approx(0.5) and w.step == pytest.approx(2.5)
    assert json.loads(w.scene)["looks"][0]["name"] == "as rendered"
    # Another of the page's styles goes on live; it is the scene's style at the next new scene.
    w.look = "crisp"
    w.set(seed=3)
    assert json.loads(w.scene)["looks"][0]["name"] == "crisp" and w.look == "crisp"
    w.set(style="flow", alpha=0.3)  # one of the page's styles: live
    assert (w.look, w.alpha) == ("flow", 0.3)
    # A style that is not one of them: a new scene, with that style's own settings.
    w = ibfvs.widget(mesh="torus", field="rotate:0,0,1", size=(64, 64))
    w.alpha = 0.3
    w.set(style="bronze")
    assert w.look == "bronze" and json.loads(w.scene)["looks"][0]["name"] == "bronze"
    assert w.alpha != pytest.approx(0.3)
