"""ibfvs's representation against ParaView's Surface LIC on real data, in one
pvbatch session: same data, same cameras, same size, each at its defaults
(docs/quality.md, "Real data"). For every view it saves the plain Surface,
Surface LIC, IBFVS after the warm-up frames and 100 frames later, and a
direction-coded picture of the TRUE projected flow (red, green: 0.5 + 0.5 x,
y of the unit image-space direction; blue 255 where the direction is defined:
the vector is not zero and not within 17 degrees of the line of sight), then
measures alignment A, streak width W and grain along the lines Z of each
against it with
`ibfvs quality --png P --direction D`, times a frame of each (the camera
nudged by 0.001 degrees each frame, so that nothing is cached) and prints one
Markdown table. Crops magnified 4x, side by side, go to OUT/crops-VIEW.png.

  xvfb-run -a pvbatch scripts/lic_compare.py DATA ARRAY OUT [options]

  DATA    a surface file ParaView opens (.vtp, .vtm, .foam, ...)
  ARRAY   the vector array (point or cell data; cell data is moved to the points
          for every picture alike)
  --reverse             negate it (OpenFOAM's wallShearStress)
  --views NAME=AZ,EL    cameras about the data's centre (degrees; azimuth about
                        the up axis from +X, elevation above the horizon),
                        default front=0,10 side=90,10
  --up X,Y,Z            the up axis (default 0,0,1)
  --zoom F              the data's bounding sphere fills 1/F of the view height (default 1)
  --size W,H            default 1024,768
  --crop X,Y            the crop's centre from the top left (default the middle)
  --plugin PATH         IBFVS.so (default: build/lib/ibfvs/paraview/IBFVS/IBFVS.so)
  --ibfvs PATH          the ibfvs binary (default: build/ibfvs)
  --set NAME=VALUE      a property of the IBFVS representation (repeatable)
  --variant N=V[,N=V]   IBFVS with these properties too, measured after the
                        defaults in the same session (repeatable)
  --frames N            IBFVS warm-up frames before the first picture (default 120)
  --library             also `ibfvs render` at its defaults, same data, camera and
                        size, after the warm-up frames and 100 later (its own
                        shading; no frame time: it renders off screen)
"""
import argparse
import math
import os
import subprocess
import time

import paraview.simple as pv

import pvmeasure

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser()
parser.add_argument("data")
parser.add_argument("array")
parser.add_argument("out")
parser.add_argument("--reverse", action="store_true")
parser.add_argument("--views", nargs="*", default=["front=0,10", "side=90,10"])
parser.add_argument("--up", default="0,0,1")
parser.add_argument("--zoom", type=float, default=1.0)
parser.add_argument("--size", default="1024,768")
parser.add_argument("--crop", default="")
parser.add_argument("--plugin", default=os.path.join(root, "build/lib/ibfvs/paraview/IBFVS/IBFVS.so"))
parser.add_argument("--ibfvs", default=os.path.join(root, "build/ibfvs"))
parser.add_argument("--set", action="append", default=[])
parser.add_argument("--variant", action="append", default=[])
parser.add_argument("--frames", type=int, default=120)
parser.add_argument("--library", action="store_true")
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
w, h = (int(v) for v in args.size.split(","))
up = [float(v) for v in args.up.split(",")]
pv.LoadPlugin(args.plugin, remote=False, ns={})

# The data, its vectors on the points (as Surface LIC needs them), reversed if asked.
source, flow = pvmeasure.flow_of(args.data, args.array, args.reverse)
centre, radius = pvmeasure.bounding_sphere(flow)
DIRECTION_SCRIPT = pvmeasure.DIRECTION_SCRIPT

view = pv.CreateRenderView()
view.ViewSize = [w, h]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0.32, 0.34, 0.43]
pv._DisableFirstRenderCameraReset()
display = pv.Show(flow, view)
display.ColorArrayName = ["POINTS", ""]
direction = pv.ProgrammableFilter(Input=flow)
direction_display = None


def place_camera(azimuth, elevation):
    """The camera about the centre; returns eye, right, up, back (eye space axes)."""
    return pvmeasure.place_camera(view, centre, radius, up, args.zoom, azimuth, elevation)


def library_camera(back):
    """`ibfvs render --camera` for the eye direction `back`: its azimuth and
    elevation are about +Y turned onto the up axis (core/scene/camera.cpp,
    up_frame), its distance in bounding-box diagonals (2 radius)."""
    u = [c / math.sqrt(math.fsum(c * c for c in up)) for c in up]
    if u[1] > 0.999999:
        local = back
    elif u[1] < -0.999999:
        local = [back[0], -back[1], -back[2]]
    else:
        # Rodrigues: the inverse rotation (angle -acos(u.y)) about Y x u.
        axis = [u[2], 0.0, -u[0]]
        n = math.sqrt(math.fsum(c * c for c in axis))
        k = [c / n for c in axis]
        c, s = u[1], -math.sqrt(abs(1.0 - u[1] * u[1]))
        kv = math.fsum(a * b for a, b in zip(k, back))
        cross = [k[1] * back[2] - k[2] * back[1], k[2] * back[0] - k[0] * back[2],
                 k[0] * back[1] - k[1] * back[0]]
        local = [back[i] * c + cross[i] * s + k[i] * kv * (1.0 - c) for i in range(3)]
    azimuth = math.degrees(math.atan2(local[0], local[2]))
    # (pvbatch's namespace replaces max and min with numpy's.)
    elevation = math.degrees(math.asin(local[1] if abs(local[1]) <= 1.0 else math.copysign(1.0, local[1])))
    distance = args.zoom / math.tan(math.radians(15.0)) / 2.0
    return "%.6f,%.6f,%.6f" % (azimuth, elevation, distance)


def library_shot(name, back, frames):
    path = os.path.join(args.out, name + ".png")
    subprocess.run([args.ibfvs, "render", args.data, "--field", "file:" + args.array] +
                   (["--reverse"] if args.reverse else []) +
                   ["--up", args.up, "--camera", library_camera(back), "--fov", "30",
                    "--size", "%dx%d" % (w, h), "--frames", str(frames), "--out", path, "-q"],
                   check=True)
    return path


def timed(frames):
    """Milliseconds per Render over `frames` frames, the camera nudged each."""
    camera = view.GetActiveCamera()
    start = time.perf_counter()
    for k in range(frames):
        camera.Azimuth(0.001 if k % 2 == 0 else -0.001)
        pv.Render(view)
    return 1e3 * (time.perf_counter() - start) / frames


def shot(name):
    path = os.path.join(args.out, name + ".png")
    pv.SaveScreenshot(path, view, ImageResolution=[w, h])
    return path


def measure(picture, truth):
    return pvmeasure.measure(args.ibfvs, picture, truth)


rows = []
crops = {}
for spec in args.views:
    name, angles = spec.split("=")
    azimuth, elevation = (float(v) for v in angles.split(","))
    eye, right, true_up, back = place_camera(azimuth, elevation)
    # The truth first.
    direction.Script = DIRECTION_SCRIPT % (eye, right, true_up, back)
    if direction_display is None:
        direction_display = pv.Show(direction, view)
    pv.Hide(flow, view)
    pv.Show(direction, view)
    pv.ColorBy(direction_display, ("POINTS", "direction"))
    direction_display.MapScalars = 0
    direction_display.Ambient, direction_display.Diffuse, direction_display.Specular = 1.0, 0.0, 0.0
    background = list(view.Background)
    view.Background = [0.0, 0.0, 0.0]
    pv.Render(view)
    truth = shot(name + "-direction")
    view.Background = background
    pv.Hide(direction, view)
    pv.Show(flow, view)

    pictures = []
    display.Representation = "Surface"
    pv.Render(view)
    ms = timed(10)
    pictures.append(("Surface, no texture", shot(name + "-surface"), ms))
    display.Representation = "Surface LIC"
    display.SelectInputVectors = ["POINTS", "flow"]
    pv.Render(view)
    ms = timed(3)
    pictures.append(("Surface LIC, defaults", shot(name + "-lic"), ms))
    display.Representation = "IBFVS"
    display.SelectInputVectors = ["POINTS", "flow"]
    def apply(settings):
        for setting in settings:
            key, value = setting.split("=")
            number = float(value)
            setattr(display, key, int(number) if number.is_integer() else number)

    apply(args.set)
    for _ in range(args.frames):
        pv.Render(view)
    ms = timed(20)
    label = "IBFVS, " + (", ".join(args.set) if args.set else "defaults")
    pictures.append((label, shot(name + "-ibfvs"), ms))
    for _ in range(100):
        pv.Render(view)
    pictures.append((label + ", 100 frames later", shot(name + "-ibfvs-later"), ms))
    if args.library:
        pictures.append(("ibfvs render, defaults", library_shot(name + "-library", back,
                                                                 args.frames + 1), float("nan")))
        pictures.append(("ibfvs render, 100 frames later",
                         library_shot(name + "-library-later", back, args.frames + 101),
                         float("nan")))
    for k, variant in enumerate(args.variant):
        settings = variant.split(",")
        before = [s.split("=")[0] + "=" + str(getattr(display, s.split("=")[0])) for s in settings]
        apply(settings)
        for _ in range(args.frames):
            pv.Render(view)
        ms = timed(20)
        pictures.append(("IBFVS, " + ", ".join(args.set + settings),
                         shot("%s-variant%d" % (name, k + 1)), ms))
        apply(before)
    for label, path, ms in pictures:
        m = measure(path, truth)
        rows.append((name, label, m.get("A", float("nan")), m.get("W", float("nan")),
                     m.get("Z", float("nan")), ms))
    crops[name] = [p for _, p, _ in pictures[1:3]]

print("\n%s (%s%s), %dx%d, pvbatch, ParaView %s\n" % (
    os.path.basename(args.data), args.array, ", reversed" if args.reverse else "", w, h,
    pv.GetParaViewVersion()))
print("| view | picture | A | W (px) | Z | ms per frame |")
print("|---|---|---|---|---|---|")
for name, label, a, wd, z, ms in rows:
    print("| %s | %s | %.3f | %.2f | %.3f | %s |" % (name, label, a, wd, z,
                                                      "-" if math.isnan(ms) else "%.0f" % ms))

# Crops: the middle (or --crop) of LIC and IBFVS, 4x, side by side.
try:
    from PIL import Image
    cx, cy = (w // 2, h // 2) if not args.crop else (int(v) for v in args.crop.split(","))
    for name, paths in crops.items():
        tiles = [Image.open(p).convert("RGB").crop((cx - 64, cy - 48, cx + 64, cy + 48))
                 .resize((512, 384), Image.NEAREST) for p in paths]
        sheet = Image.new("RGB", (512 * len(tiles) + 8 * (len(tiles) - 1), 384), (255, 255, 255))
        for i, tile in enumerate(tiles):
            sheet.paste(tile, (i * 520, 0))
        sheet.save(os.path.join(args.out, "crops-%s.png" % name))
except ImportError:
    pass
