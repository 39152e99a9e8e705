"""What scripts/lic_compare.py and scripts/lic_series.py share, under
pvbatch: the data's surface with its vectors on the points ("flow"), a camera
about the data's centre, the direction-coded picture of the TRUE projected
flow, and `ibfvs quality` against it (docs/quality.md, "Real data").
"""
import argparse
import fnmatch
import math
import os
import subprocess

import paraview.simple as pv

# The true projected direction, per point, for a camera: the derivative of the
# perspective projection along the unit vector, normalised, in eye space
# (x right, y up); blue 255 where the vector is not zero and its component
# across the line of sight is at least 0.3 (17 degrees off it).
DIRECTION_SCRIPT = """
import numpy as np
from vtk.numpy_interface import dataset_adapter as dsa
eye = np.array(%r); right = np.array(%r); upv = np.array(%r); back = np.array(%r)
data = dsa.WrapDataObject(inputs[0].VTKObject)
p = np.asarray(data.Points) - eye
v = np.asarray(data.PointData["flow"])
speed = np.linalg.norm(v, axis=1)
u = v / np.maximum(speed, 1e-30)[:, None]
x, y, z = p @ right, p @ upv, p @ back
dx, dy, dz = u @ right, u @ upv, u @ back
# d/ds of (x / -z, y / -z), times z^2: (dx (-z) + x dz, dy (-z) + y dz)
sx, sy = dx * (-z) + x * dz, dy * (-z) + y * dz
n = np.hypot(sx, sy)
across = n / np.maximum(np.sqrt(x * x + y * y + z * z), 1e-30)
rgb = np.zeros((len(v), 3), dtype=np.uint8)
ok = (speed > 0) & (n > 0)
rgb[:, 0] = np.clip(np.round(127.5 + 127.5 * np.where(ok, sx / np.maximum(n, 1e-30), 0)), 0, 255)
rgb[:, 1] = np.clip(np.round(127.5 + 127.5 * np.where(ok, sy / np.maximum(n, 1e-30), 0)), 0, 255)
rgb[:, 2] = np.where(ok & (across >= 0.3), 255, 0)
output.ShallowCopy(inputs[0].VTKObject)
out = dsa.WrapDataObject(output)
out.PointData.append(rgb, "direction")
"""


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def series_arguments(*positional):
    """The command line the series scripts share: DATA ARRAY (and
    `positional`), --blocks, --view, --up, --size and --plugin; the rest is
    each script's own."""
    parser = argparse.ArgumentParser()
    for name in ("data", "array") + positional:
        parser.add_argument(name)
    parser.add_argument("--blocks", default="")
    parser.add_argument("--view", default="0,10")
    parser.add_argument("--up", default="0,0,1")
    parser.add_argument("--size", default="1024,768")
    parser.add_argument("--plugin",
                        default=os.path.join(ROOT, "build/lib/ibfvs/paraview/IBFVS/IBFVS.so"))
    return parser


def series_view(args):
    """The parsed view of series_arguments: (w, h), the up axis, (azimuth,
    elevation)."""
    return (tuple(int(v) for v in args.size.split(",")), [float(v) for v in args.up.split(",")],
            tuple(float(v) for v in args.view.split(",")))


def flow_of(data, array, reverse, blocks=None):
    """The data's surface with `array` on the points as "flow" (negated with
    `reverse`): OpenFOAM cases read their patches (`blocks`: names or
    patterns such as patch/motorBike*, else every patch), cell data goes to
    the points as Surface LIC needs it."""
    source = pv.OpenDataFile(data)
    if hasattr(source, "MeshRegions"):  # OpenFOAM: the walls, not the volume
        available = source.GetProperty("MeshRegions").Available
        source.MeshRegions = ([r for r in available if any(fnmatch.fnmatchcase(r, b) for b in blocks)]
                              if blocks else
                              [r for r in available if r.startswith("patch/") or r.startswith("wall")]
                              or ["internalMesh"])
    source.UpdatePipeline()
    surface = pv.ExtractSurface(Input=pv.MergeBlocks(Input=source))
    surface.UpdatePipeline()
    on_cells = surface.CellData.GetArray(array) is not None and \
        surface.PointData.GetArray(array) is None
    if on_cells:
        surface = pv.CellDatatoPointData(Input=surface)
    flow = pv.Calculator(Input=surface, ResultArrayName="flow",
                         Function=("-" if reverse else "") + array)
    flow.UpdatePipeline()
    return source, flow


def bounding_sphere(proxy):
    bounds = proxy.GetDataInformation().GetBounds()
    centre = [0.5 * (bounds[2 * i] + bounds[2 * i + 1]) for i in range(3)]
    radius = 0.5 * math.sqrt(math.fsum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)))
    return centre, radius


def place_camera(view, centre, radius, up, zoom, azimuth, elevation):
    """The view's camera about `centre` (azimuth about `up` from its
    horizontal reference axis, elevation above the horizon), the bounding
    sphere filling 1/zoom of the view's height; returns eye, right, up, back
    (the eye space axes)."""
    upn = [u / math.sqrt(math.fsum(c * c for c in up)) for u in up]
    # A horizontal reference axis: +X unless up is X.
    ref = [1.0, 0.0, 0.0] if abs(upn[0]) < 0.9 else [0.0, 1.0, 0.0]
    dot = math.fsum(a * b for a, b in zip(ref, upn))
    e1 = [a - dot * b for a, b in zip(ref, upn)]
    l1 = math.sqrt(math.fsum(a * a for a in e1))
    e1 = [a / l1 for a in e1]
    e2 = [upn[1] * e1[2] - upn[2] * e1[1], upn[2] * e1[0] - upn[0] * e1[2],
          upn[0] * e1[1] - upn[1] * e1[0]]
    a, e = math.radians(azimuth), math.radians(elevation)
    to_eye = [math.cos(e) * (math.cos(a) * e1[i] + math.sin(a) * e2[i]) + math.sin(e) * upn[i]
              for i in range(3)]
    # Looking straight along the up axis: the view's up is the reference axis.
    view_up = upn if abs(math.fsum(t * u for t, u in zip(to_eye, upn))) < 0.999 else e1
    distance = radius * zoom / math.tan(math.radians(15.0))
    eye = [centre[i] + distance * to_eye[i] for i in range(3)]
    view.CameraPosition = eye
    view.CameraFocalPoint = centre
    view.CameraViewUp = view_up
    view.CameraViewAngle = 30
    view.CameraParallelProjection = 0
    back = to_eye
    # Not normalised (as the published measurements were made): above the
    # horizon both axes shrink by the cosine of the elevation, which scales
    # the across-the-line-of-sight threshold alike for every picture.
    right = [view_up[1] * back[2] - view_up[2] * back[1], view_up[2] * back[0] - view_up[0] * back[2],
             view_up[0] * back[1] - view_up[1] * back[0]]
    true_up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
               back[0] * right[1] - back[1] * right[0]]
    return eye, right, true_up, back


def measure(ibfvs, picture, truth):
    """A, W and Z of a picture against the true direction (ibfvs quality)."""
    text = subprocess.run([ibfvs, "quality", "--png", picture, "--direction", truth],
                          check=True, capture_output=True, text=True).stdout
    values = {}
    for line in text.splitlines():
        if "alignment A" in line:
            values["A"] = float(line.split()[2])
        if "streak width W" in line:
            values["W"] = float(line.split()[3])
        if "grain along Z" in line:
            values["Z"] = float(line.split()[3])
    return values
