"""ibfvs.pyvista.add_flow against VTK's own Surface LIC from the same vtk
wheel, in one process, on real data (docs/python.md, "Measured"): the same
surface, camera and size; plain add_mesh, add_flow at its defaults and
vtkSurfaceLICMapper at its defaults, each coloured by the same array. For
each it saves the picture and times a frame (the camera nudged by 0.001
degrees each render, so that nothing is cached); for the two textures it
measures alignment A and streak width W against a direction-coded picture
of the TRUE projected flow (red, green: 0.5 + 0.5 x, y of the unit image
direction; blue 255 where the vector is not zero and not within 17 degrees
of the line of sight) with `ibfvs quality --png P --direction D`, and
prints one Markdown table. Runs in the pip package's venv:

  build/package/venv/bin/python scripts/pyvista_compare.py DATA ARRAY OUT [options]

  DATA     an OpenFOAM case (.foam, its last time) or any file pv.read takes
  ARRAY    the vector array (point or cell data; cell data moved to the points)
  --patches PATTERN   OpenFOAM patches to take (fnmatch, default: every patch)
  --colour NAME       the array to colour by (default: ARRAY's magnitude)
  --view AZ,EL        camera azimuth about the up axis from +X and elevation (degrees)
  --up X,Y,Z          the up axis (default 0,0,1)
  --zoom F            the data's bounding sphere fills 1/F of the view height
  --size W,H          default 1024,768
  --frames N          add_flow's warm-up renders before its picture (default 120)
  --timed N           renders timed for each (default 20)
"""

import argparse
import fnmatch
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np
import pyvista as pv
from PIL import Image
from vtkmodules.vtkRenderingLICOpenGL2 import vtkSurfaceLICMapper

import ibfvs
import ibfvs.pyvista

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
parser = argparse.ArgumentParser()
parser.add_argument("data")
parser.add_argument("array")
parser.add_argument("out")
parser.add_argument("--patches", default="*")
parser.add_argument("--colour", default="")
parser.add_argument("--view", default="35,20")
parser.add_argument("--up", default="0,0,1")
parser.add_argument("--zoom", type=float, default=1.0)
parser.add_argument("--size", default="1024,768")
parser.add_argument("--frames", type=int, default=120)
parser.add_argument("--timed", type=int, default=20)
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
size = tuple(int(v) for v in args.size.split(","))
up = np.array([float(v) for v in args.up.split(",")])
up /= np.linalg.norm(up)


def read_surface():
    if args.data.endswith(".foam"):
        reader = pv.OpenFOAMReader(args.data)
        reader.set_active_time_value(reader.time_values[-1])
        reader.disable_all_patch_arrays()
        names = [n for n in reader.patch_array_names
                 if n.startswith("patch/") and fnmatch.fnmatch(n[6:], args.patches)]
        if not names:
            sys.exit(f"{args.data}: no patch matches {args.patches}")
        for name in names:
            reader.enable_patch_array(name)
        reader.cell_to_point_creation = True
        data = reader.read()
    else:
        data = pv.read(args.data)
    if isinstance(data, pv.MultiBlock):
        data = data.combine(merge_points=False)
    surface = (data.extract_surface(algorithm="dataset_surface")
               if not isinstance(data, pv.PolyData) else data)
    if args.array not in surface.point_data and args.array in surface.cell_data:
        surface = surface.cell_data_to_point_data()
    surface = surface.triangulate()
    if args.array not in surface.point_data:
        sys.exit(f"{args.data}: no point or cell array {args.array}")
    colour = args.colour or "magnitude"
    if not args.colour:
        surface.point_data[colour] = np.linalg.norm(surface.point_data[args.array], axis=1)
    return surface, colour


surface, colour = read_surface()
clim = tuple(np.percentile(surface.point_data[colour], [2, 98]))
centre = np.array(surface.center)
radius = 0.5 * np.linalg.norm(np.array(surface.bounds[1::2]) - np.array(surface.bounds[::2]))
az, el = (math.radians(float(v)) for v in args.view.split(","))
x_axis = np.cross(up, [0.0, 1.0, 0.0]) if abs(up[1]) < 0.9 else np.cross(up, [1.0, 0.0, 0.0])
x_axis /= np.linalg.norm(x_axis)
y_axis = np.cross(up, x_axis)
view_angle = 30.0
distance = radius * args.zoom / math.sin(math.radians(view_angle / 2))
eye = centre + distance * (math.cos(el) * (math.cos(az) * x_axis + math.sin(az) * y_axis) +
                           math.sin(el) * up)


def plotter():
    p = pv.Plotter(off_screen=True, window_size=size)
    p.set_background("white")
    p.camera.position = tuple(eye)
    p.camera.focal_point = tuple(centre)
    p.camera.up = tuple(up)
    p.camera.view_angle = view_angle
    return p


def timed(p, renders):
    """ms a render, the camera nudged each time (nothing cached)."""
    start = time.perf_counter()
    for k in range(renders):
        p.camera.azimuth += 0.001 if k % 2 == 0 else -0.001
        p.render()
    return 1000.0 * (time.perf_counter() - start) / renders


def save(p, name):
    picture = p.screenshot(return_img=True)[..., :3]
    path = os.path.join(args.out, name + ".png")
    Image.fromarray(picture).save(path)
    return path


def direction_picture():
    """The true flow's unit image direction per pixel, rendered by VTK as
    point colours, unlit, with the same camera."""
    p = plotter()
    p.show(auto_close=False)
    cam = p.camera
    m = cam.GetCompositeProjectionTransformMatrix(size[0] / size[1], -1, 1)
    mvp = np.array([[m.GetElement(r, c) for c in range(4)] for r in range(4)])
    pts = np.asarray(surface.points, dtype=float)
    vec = np.asarray(surface.point_data[args.array], dtype=float)
    length = np.linalg.norm(vec, axis=1)
    eps = 1e-3 * radius / np.maximum(length, 1e-30)
    def screen(x):
        h = np.c_[x, np.ones(len(x))] @ mvp.T
        return h[:, :2] / h[:, 3:4] * np.array([size[0], size[1]]) / 2
    d = screen(pts + eps[:, None] * vec) - screen(pts)
    n = np.linalg.norm(d, axis=1)
    view = pts - eye
    view /= np.linalg.norm(view, axis=1, keepdims=True)
    across = np.linalg.norm(np.cross(view, vec / np.maximum(length, 1e-30)[:, None]), axis=1)
    ok = (length > 0) & (n > 0) & (across >= math.sin(math.radians(17.0)))
    u = d / np.maximum(n, 1e-30)[:, None]
    rgb = np.zeros((len(pts), 3), np.uint8)
    rgb[:, 0] = np.where(ok, np.round(127.5 + 127.5 * u[:, 0]), 0)
    rgb[:, 1] = np.where(ok, np.round(127.5 + 127.5 * u[:, 1]), 0)
    rgb[:, 2] = np.where(ok, 255, 0)
    coded = surface.copy()
    coded.point_data["direction"] = rgb
    p.add_mesh(coded, scalars="direction", rgb=True, lighting=False,
               interpolate_before_map=False)
    p.render()
    p.set_background("black")
    p.render()
    path = save(p, "direction")
    p.close()
    return path


def quality(picture, direction):
    exe = shutil.which("ibfvs", path=os.path.dirname(sys.executable)) or "ibfvs"
    out = subprocess.run([exe, "quality", "--png", picture, "--direction", direction],
                         capture_output=True, text=True, check=True).stdout
    values = {}
    for line in out.splitlines():
        if "alignment A" in line:
            values["A"] = float(line.split()[2])
        if "streak width W" in line:
            values["W"] = float(line.split()[3])
    return values


rows = []
direction = direction_picture()

p = plotter()
p.add_mesh(surface, scalars=colour, cmap="viridis", clim=clim, show_scalar_bar=False)
p.show(auto_close=False)
ms = timed(p, args.timed)
save(p, "plain")
rows.append(("plain add_mesh", ms, {}))
p.close()

p = plotter()
actor = ibfvs.pyvista.add_flow(p, surface, vectors=args.array, scalars=colour, cmap="viridis",
                               clim=clim, show_scalar_bar=False)
p.show(auto_close=False)
for _ in range(args.frames):
    p.render()
picture = save(p, "ibfvs")
rows.append(("ibfvs.pyvista.add_flow", timed(p, args.timed), quality(picture, direction)))
if actor.ibfvs.problem:
    print("add_flow:", actor.ibfvs.problem)
p.close()

p = plotter()
actor = p.add_mesh(surface, scalars=colour, cmap="viridis", clim=clim, show_scalar_bar=False)
# Coloured as add_mesh set up its mapper (vtkSurfaceLICMapper's ShallowCopy of
# that mapper crashes in VTK 9.7.2: the settings one by one instead).
shown = actor.GetMapper()
lic = vtkSurfaceLICMapper()
lic.SetInputData(surface)
lic.SetLookupTable(shown.GetLookupTable())
lic.SetScalarRange(shown.GetScalarRange())
lic.SetScalarVisibility(True)
lic.SetScalarModeToUsePointFieldData()
lic.SelectColorArray(colour)
lic.SetInterpolateScalarsBeforeMapping(shown.GetInterpolateScalarsBeforeMapping())
lic.SetInputArrayToProcess(0, 0, 0, 0, args.array)  # point data
actor.SetMapper(lic)
p.show(auto_close=False)
ms = timed(p, args.timed)
picture = save(p, "lic")
rows.append(("VTK Surface LIC (vtkSurfaceLICMapper)", ms, quality(picture, direction)))
p.close()

print(f"{args.data}: {surface.n_points} points, {surface.n_cells} triangles, "
      f"{size[0]}x{size[1]}, ibfvs {ibfvs.__version__}, vtk {pv.vtk_version_info}")
print()
print("| | ms a frame | A | W (px) |")
print("|---|---|---|---|")
for name, ms, q in rows:
    a = f"{q['A']:.3f}" if "A" in q else ""
    w = f"{q['W']:.2f}" if "W" in q else ""
    print(f"| {name} | {ms:.1f} | {a} | {w} |")
