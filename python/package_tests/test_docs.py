"""docs/python.md's PyVista examples (```python pyvista blocks) run, in
order, in the pip package's venv, writing into a temporary folder."""

import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_every_pyvista_example_in_the_docs_runs(tmp_path, monkeypatch):
    pytest.importorskip("imageio")
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python pyvista\n(.*?)```", text, re.S)
    assert len(blocks) >= 2
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert namespace["actor"].ibfvs.frame >= 30 and namespace["actor"].ibfvs.problem is None
    for name in ("swirl.png", "swirl.mp4", "turning.mp4"):
        assert (tmp_path / name).stat().st_size > 1000, name
    from PIL import Image

    picture = np.asarray(Image.open(tmp_path / "swirl.png"))
    assert picture[..., :3].std() > 20  # the texture, not a blank plotter


def test_the_gallery_notebook_runs(tmp_path, monkeypatch):
    """docs/gallery/pyvista.ipynb's code cells, in order (outside Jupyter:
    the static backend's show() renders off screen)."""
    import json

    notebook = json.loads((ROOT / "docs" / "gallery" / "pyvista.ipynb").read_text())
    code = ["".join(c["source"]) for c in notebook["cells"] if c["cell_type"] == "code"]
    assert code
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for cell in code:
        exec(compile(cell, "docs/gallery/pyvista.ipynb", "exec"), namespace)
    assert namespace["actor"].ibfvs.frame >= 60 and namespace["actor"].ibfvs.problem is None
    assert namespace["w"].alpha == 0.05 and len(namespace["w"].data) > 100_000  # the widget's cells


def test_the_notebook_widget_example_in_the_docs_runs(tmp_path, monkeypatch, capsys):
    """docs/python.md's ```python notebook block, outside a notebook (the
    widget's Python side: its settings and set)."""
    pytest.importorskip("anywidget")
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python notebook\n(.*?)```", text, re.S)
    assert len(blocks) == 1
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(blocks[0], "docs/python.md", "exec"), namespace)
    w = namespace["w"]
    assert w.alpha == 0.2 and w.look == "crisp" and "'look': 'crisp'" in capsys.readouterr().out
