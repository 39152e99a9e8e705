"""docs/python.md's examples run, in order, from the repository's root (so
that data/ and scenes/ are where they say), writing into a temporary folder."""

import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_every_python_example_in_the_docs_runs(tmp_path, monkeypatch):
    if not (ROOT / "data" / "earth" / "monthly_navy_winds.cdf").exists():
        pytest.skip("fetched data missing (scripts/fetch_data.sh)")
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 4
    for name in ("data", "scenes"):
        os.symlink(ROOT / name, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert namespace["image"].shape == (256, 256, 3)
    assert namespace["earth"].std() > 10  # the winds' texture, not a blank sphere
    assert (tmp_path / "torus.mp4").stat().st_size > 1000


def test_the_readme_python_examples_run(tmp_path, monkeypatch):
    if not (ROOT / "data" / "meshes" / "cow.off").exists():
        pytest.skip("fetched data missing (scripts/fetch_data.sh)")
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    for name in ("data", "scenes"):
        os.symlink(ROOT / name, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})
    # The shell line: Python from the build tree.
    line = next(l for l in text.splitlines() if l.startswith("PYTHONPATH=build/python"))
    code = line.split(' -c "', 1)[1].rsplit('"', 1)[0]
    exec(compile(code, "README.md", "exec"), {})
