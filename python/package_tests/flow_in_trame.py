"""A trame server whose page shows one PyVista plotter with the flow texture,
rendered on the server: docs/python.md's trame example (its ```python trame
block, run as it stands on this port) on the swirl about +Z on the unit
sphere, seen down Z with parallel scale 1.2 (as test_pyvista.py draws it),
on white. Run by test_trame.py:

    python flow_in_trame.py PORT WIDTH HEIGHT
"""

import re
import sys
from pathlib import Path

import numpy as np
import pyvista as pv

port, width, height = (int(v) for v in sys.argv[1:4])
sphere = pv.Sphere(radius=1.0, theta_resolution=96, phi_resolution=96)
sphere.point_data["swirl"] = np.cross([0.0, 0.0, 1.0], sphere.points)
sphere.point_data["height"] = sphere.points[:, 2]
plotter = pv.Plotter(off_screen=True, window_size=(width, height))
plotter.set_background("white")
plotter.ibfvs.add_flow(sphere, vectors="swirl", scalars="height", show_scalar_bar=False)
plotter.camera.position = (0.0, 0.0, 5.0)
plotter.camera.focal_point = (0.0, 0.0, 0.0)
plotter.camera.up = (0.0, 1.0, 0.0)
plotter.enable_parallel_projection()
plotter.camera.parallel_scale = 1.2

docs = Path(__file__).resolve().parents[2] / "docs" / "python.md"
block = re.search(r"```python trame\n(.*?)```", docs.read_text(), re.S).group(1)
assert "port=8080" in block, block
exec(compile(block.replace("port=8080", f"port={port}"), str(docs), "exec"), {"plotter": plotter})
