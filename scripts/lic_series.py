"""ibfvs's representation over a transient or moving-mesh result, beside
ParaView's Surface LIC and Surface, in one pvbatch session (docs/cfd.md,
"Time"): the series played as ParaView users play and export it.

For every time step it saves the direction-coded picture of the TRUE
projected flow of that step (as scripts/lic_compare.py), Surface LIC of that
step, and IBFVS twice: as File > Save Animation writes it (one frame per
step: SaveAnimation itself, Snap To TimeSteps) and as Play shows it (RENDERS
renders at each step, the last one measured). It measures A and W of each
against the truth (`ibfvs quality --png P --direction D`), the correlation
of the Play pictures across each step change against two frames within a
step, and the milliseconds of a step change (the render that first shows a
new step: the reader's work included) for Surface and for IBFVS, each
playing the series alone. Play's pictures are read from the window as its
renders left them (SaveScreenshot would render again: one more texture
frame each), so two renders within a step are one frame apart and
--renders 2 plays as the GUI's Play does (two renders a step). Prints
Markdown tables; pictures go to OUT.

  xvfb-run -a pvbatch scripts/lic_series.py DATA ARRAY OUT [options]

  DATA    a series ParaView opens (.foam, .pvd, .series, ...)
  ARRAY   the vector array (point or cell data)
  --reverse            negate it (OpenFOAM's wallShearStress)
  --blocks A,B         OpenFOAM regions to read (default: every patch)
  --view AZ,EL         the camera about the data's centre (degrees), default 0,10
  --up X,Y,Z           the up axis (default 0,0,1)
  --zoom F             the bounding sphere fills 1/F of the view height (default 1)
  --size W,H           default 1024,768
  --renders N          Play: renders at each time step (default 24)
  --region X,Y,Z,R[,R0]  also measure within the sphere of radius R about (X, Y,
                       Z) only, as seen (a moving part), and beyond R0 from it
                       (a still shaft in the middle of a turning propeller)
  --turn DEG           the moving part turns about the line of sight
                       through the region's centre, by about DEG degrees a step
                       (counter-clockwise as seen: positive): Play's texture
                       (the picture less a 4-px Gaussian blur) of the last
                       render before each step change, turned as the part
                       turned (the turn within 2 degrees of DEG that best maps
                       one silhouette onto the other), correlated with the
                       first render after the change, within the region;
                       beside it left in place, and two renders within a step
  --set NAME=VALUE     a property of the IBFVS representation (repeatable)
  --plugin PATH        IBFVS.so (default: build/lib/ibfvs/paraview/IBFVS/IBFVS.so)
  --ibfvs PATH         the ibfvs binary (default: build/ibfvs)
  --no-lic             leave Surface LIC out (the plugin's own figures only)
  --no-play            leave Play out
  --export-variant N=V[,N=V]  Save Animation again with these properties too
                       (repeatable): FramesPerStep=3, ...
  --sequence K         also Save Animation in Sequence mode, K frames over the
                       series (more frames than steps): A and W of each frame
                       against the truth at its time, and the correlation of
                       consecutive frames, within a step and across a change
  --interpolate        the data through ParaView's TemporalInterpolator (every
                       sequence frame then shows data of its own time)
  --page               also File > Export Scene's web page of the IBFVS view
                       (OUT/ibfvs.html, every time step): the seconds it takes,
                       its size, and A and W of its picture in headless chromium
                       (web/test/shoot.mjs) as it reaches each step
"""
import builtins
import math
import os
import time

import paraview.simple as pv

import pvmeasure

parser = pvmeasure.series_arguments("out")
parser.add_argument("--reverse", action="store_true")
parser.add_argument("--zoom", type=float, default=1.0)
parser.add_argument("--renders", type=int, default=24)
parser.add_argument("--region", default="")
parser.add_argument("--turn", type=float, default=None)
parser.add_argument("--set", action="append", default=[])
parser.add_argument("--ibfvs", default=os.path.join(pvmeasure.ROOT, "build/ibfvs"))
parser.add_argument("--no-lic", action="store_true")
parser.add_argument("--export-variant", action="append", default=[])
parser.add_argument("--no-play", action="store_true")
parser.add_argument("--sequence", type=int, default=0)
parser.add_argument("--interpolate", action="store_true")
parser.add_argument("--page", action="store_true")
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
(w, h), up, (azimuth, elevation) = pvmeasure.series_view(args)
pv.LoadPlugin(args.plugin, remote=False, ns={})

source, flow = pvmeasure.flow_of(args.data, args.array, args.reverse,
                                 args.blocks.split(",") if args.blocks else None)
centre, radius = pvmeasure.bounding_sphere(flow)
times = list(source.TimestepValues) if source.TimestepValues else [0.0]
if args.interpolate:
    flow = pv.TemporalInterpolator(Input=flow)
pv._DisableFirstRenderCameraReset()


def new_view():
    view = pv.CreateRenderView()
    view.ViewSize = [w, h]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.32, 0.34, 0.43]
    camera = pvmeasure.place_camera(view, centre, radius, up, args.zoom, azimuth, elevation)
    return view, camera


def shown(view, representation):
    display = pv.Show(flow, view)
    display.ColorArrayName = ["POINTS", ""]
    display.Representation = representation
    if representation != "Surface":
        display.SelectInputVectors = ["POINTS", "flow"]
    if representation == "IBFVS":
        for setting in args.set:
            key, value = setting.split("=")
            number = float(value)
            setattr(display, key, int(number) if number.is_integer() else number)
    return display


def shot(view, name):
    path = os.path.join(args.out, name + ".png")
    pv.SaveScreenshot(path, view, ImageResolution=[w, h])
    return path


def grab(view, name):
    """The picture the last render left in the window, without rendering
    again (SaveScreenshot renders: each shot would be one more render of
    the step, and a texture frame): Play's renders are its own."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    path = os.path.join(args.out, name + ".png")
    capture = vtkWindowToImageFilter()
    capture.SetInput(view.GetRenderWindow())
    capture.SetShouldRerender(False)
    capture.ReadFrontBufferOff()
    capture.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    return path


def at_time(view, t):
    view.ViewTime = t


# ---- the step changes, timed: Surface alone, then IBFVS alone (each render
# that first shows a step pays for reading it)
def step_changes(representation):
    view, _ = new_view()
    shown(view, representation)
    at_time(view, times[0])
    pv.Render(view)
    ms = []
    for t in times[1:]:
        at_time(view, t)
        start = time.perf_counter()
        pv.Render(view)
        ms.append(1e3 * (time.perf_counter() - start))
    pv.Delete(view)
    return ms


surface_ms = step_changes("Surface")
ibfvs_ms = step_changes("IBFVS")

# ---- File > Save Animation: one frame per time step (and its variants)
scene = pv.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
exports = {}
for k, variant in enumerate([""] + args.export_variant):
    export_view, _ = new_view()
    display = shown(export_view, "IBFVS")
    for setting in filter(None, variant.split(",")):
        key, value = setting.split("=")
        number = float(value)
        setattr(display, key, int(number) if number.is_integer() else number)
    stem = "export" if not variant else "export-v%d" % k
    pv.SetActiveView(export_view)
    pv.SaveAnimation(os.path.join(args.out, stem + ".png"), export_view, ImageResolution=[w, h])
    label = "IBFVS, Save Animation" + (", " + variant if variant else "")
    exports[label] = sorted(os.path.join(args.out, f) for f in os.listdir(args.out)
                            if f.startswith(stem + ".") and f.endswith(".png"))
    pv.Delete(export_view)
exported = exports["IBFVS, Save Animation"]

# ---- File > Export Scene: the page of the IBFVS view, every time step
page, page_seconds = None, 0.0
if args.page:
    page_view, _ = new_view()
    shown(page_view, "IBFVS")
    pv.Render(page_view)
    page = os.path.join(args.out, "ibfvs.html")
    start = time.perf_counter()
    pv.ExportView(page, view=page_view)
    page_seconds = time.perf_counter() - start
    pv.Delete(page_view)


def page_shot(k):
    """The page's canvas as it reaches step k (web/test/shoot.mjs)."""
    import subprocess
    path = os.path.join(args.out, "page-%02d.png" % k)
    subprocess.run(["node", os.path.join(pvmeasure.ROOT, "web", "test", "shoot.mjs"), page,
                    path, "0", str(k)], check=True, capture_output=True)
    return path


# ---- Save Animation in Sequence mode: more frames than steps
sequence = []
if args.sequence:
    scene.PlayMode = "Sequence"
    scene.NumberOfFrames = args.sequence
    sequence_view, _ = new_view()
    shown(sequence_view, "IBFVS")
    pv.SetActiveView(sequence_view)
    pv.SaveAnimation(os.path.join(args.out, "sequence.png"), sequence_view,
                     ImageResolution=[w, h])
    pv.Delete(sequence_view)
    scene.PlayMode = "Snap To TimeSteps"
    start, end = times[0], times[-1]
    sequence = [(start + (end - start) * i / (args.sequence - 1),
                 os.path.join(args.out, "sequence.%04d.png" % i)) for i in range(args.sequence)]

# ---- the truth, Surface LIC and Play, step by step
truth_view, axes = new_view()
# The region as seen: its centre projected, its radius at that depth (before
# the programmable filter runs: in a builtin session its script shares this
# module's globals).
region = None
if args.region:
    eye_, right_, up_, back_ = axes
    values = [float(v) for v in args.region.split(",")]
    rx, ry, rz, rr = values[:4]
    r0 = values[4] if len(values) > 4 else 0.0
    p = [rx - eye_[0], ry - eye_[1], rz - eye_[2]]
    depth = -math.fsum(a * b for a, b in zip(p, back_))
    # The axes above the horizon are shortened alike (pvmeasure.place_camera).
    norm = math.sqrt(math.fsum(c * c for c in right_))
    n = [math.fsum(a * b for a, b in zip(p, right_)) / norm,
         math.fsum(a * b for a, b in zip(p, up_)) / norm]
    scale = (h / 2) / math.tan(math.radians(15.0)) / depth
    region = (w / 2 + scale * n[0], h / 2 + scale * n[1], scale * rr, scale * r0)
direction = pv.ProgrammableFilter(Input=flow)
direction.Script = pvmeasure.DIRECTION_SCRIPT % axes
direction_display = pv.Show(direction, truth_view)
pv.ColorBy(direction_display, ("POINTS", "direction"))
direction_display.MapScalars = 0
direction_display.Ambient, direction_display.Diffuse, direction_display.Specular = 1.0, 0.0, 0.0
truth_view.Background = [0.0, 0.0, 0.0]
if not args.no_lic:
    lic_view, _ = new_view()
    shown(lic_view, "Surface LIC")
if not args.no_play:
    play_view, _ = new_view()
    shown(play_view, "IBFVS")



def region_truth(path):
    """The truth with blue cleared outside the region: measured there only."""
    import numpy as np
    from PIL import Image
    out = path[:-4] + "-region.png"
    rgb = np.array(Image.open(path).convert("RGB"))
    rows, columns = np.mgrid[0:rgb.shape[0], 0:rgb.shape[1]]
    x, y = columns + 0.5, rgb.shape[0] - rows - 0.5  # y up, as the region's centre
    distance = np.hypot(x - region[0], y - region[1])
    outside = (distance > region[2]) | (distance < region[3])
    rgb[outside, 2] = 0
    Image.fromarray(rgb).save(out)
    return out


sequence_rows, sequence_truths = [], []
for i, (t, path) in enumerate(sequence):
    at_time(truth_view, t)
    pv.Render(truth_view)
    truth = shot(truth_view, "sequence-truth-%04d" % i)
    sequence_truths.append(truth)
    m = pvmeasure.measure(args.ibfvs, path, truth)
    r = pvmeasure.measure(args.ibfvs, path, region_truth(truth)) if region else {}
    sequence_rows.append((i, t, m, r))

rows, correlations, lic_ms = [], [], []
previous_last = None
for k, t in enumerate(times):
    for view in ([truth_view] + ([] if args.no_play else [play_view]) +
                 ([] if args.no_lic else [lic_view])):
        at_time(view, t)
    pv.Render(truth_view)
    truth = shot(truth_view, "truth-%02d" % k)
    pictures = {}
    if not args.no_lic:
        start = time.perf_counter()
        pv.Render(lic_view)
        lic_ms.append(1e3 * (time.perf_counter() - start))
        pictures["Surface LIC"] = shot(lic_view, "lic-%02d" % k)
    for label, frames in exports.items():
        if k < len(frames):
            pictures[label] = frames[k]
    if page:
        pictures["page (chromium, as it reaches the step)"] = page_shot(k)
    if not args.no_play:
        for r in range(args.renders):
            pv.Render(play_view)
            if r == 0:
                first = grab(play_view, "play-%02d-first" % k)
            if r == args.renders - 2:
                second_last = grab(play_view, "play-%02d-r%d" % (k, r))
        last = grab(play_view, "play-%02d" % k)
        pictures["IBFVS, Play (%d renders a step)" % args.renders] = last
        correlations.append((k, second_last, last, previous_last, first))
        previous_last = last
    for label, path in pictures.items():
        m = pvmeasure.measure(args.ibfvs, path, truth)
        r = pvmeasure.measure(args.ibfvs, path, region_truth(truth)) if region else {}
        rows.append((k, t, label, m, r))

# ---- the correlations, on the pixels the surface covers in both
try:
    import numpy as np
    from PIL import Image

    def grey(path):
        return np.asarray(Image.open(path).convert("L"), dtype=float)

    def corr(a, b):
        ga, gb = grey(a), grey(b)
        background = ga[0, 0]
        mask = (np.abs(ga - background) > 2) & (np.abs(gb - background) > 2)
        return float(np.corrcoef(ga[mask], gb[mask])[0, 1])

    within = [corr(s, l) for _, s, l, _, _ in correlations]

    # The measure of a moving part (--turn): the texture turned with it.
    turned_rows = []
    if args.turn is not None and region:
        from PIL import ImageFilter

        def texture(path):
            image = Image.open(path).convert("L")
            return (np.asarray(image, dtype=float) -
                    np.asarray(image.filter(ImageFilter.GaussianBlur(4)), dtype=float))

        def silhouette(path):
            g = grey(path)
            return np.abs(g - g[0, 0]) > 2

        rows_, columns_ = np.mgrid[0:h, 0:w]
        distance = np.hypot(columns_ + 0.5 - region[0], (h - rows_ - 0.5) - region[1])
        inside = (distance < region[2]) & (distance >= region[3])
        centre = (region[0], h - region[1])  # PIL's: y down

        def turned(array, degrees):
            """Turned counter-clockwise as seen about the region's centre."""
            image = Image.fromarray(array.astype(np.float32), mode="F")
            return np.asarray(image.rotate(degrees, resample=Image.BILINEAR, center=centre))

        def eroded(mask, pixels=2):
            out = mask.copy()
            for dy in range(-pixels, pixels + 1):
                for dx in range(-pixels, pixels + 1):
                    out &= np.roll(np.roll(mask, dy, 0), dx, 1)
            return out

        def correlation(a, b, mask):
            return float(np.corrcoef(a[mask], b[mask])[0, 1])

        for k, second_last, last, previous_last, first in correlations:
            if not previous_last:
                continue
            before, after = silhouette(previous_last) & inside, silhouette(first) & inside
            def overlap(d):
                r = turned(before.astype(float), d) > 0.5
                return (r & after).sum() / builtins.max((r | after).sum(), 1)

            # (builtins': the programmable filter's script, which shares these
            # globals, imports numpy_interface's max.)
            degrees = builtins.max(np.arange(args.turn - 2.0, args.turn + 2.01, 0.1), key=overlap)
            both = eroded(after & (turned(before.astype(float), degrees) > 0.99))
            t_before, t_after = texture(previous_last), texture(first)
            turned_rows.append((k, degrees, correlation(turned(t_before, degrees), t_after, both),
                                correlation(t_before, t_after, eroded(before & after)),
                                correlation(texture(second_last), texture(last),
                                            eroded(silhouette(last) & inside))))
    across = [corr(p, f) for _, _, _, p, f in correlations if p]
    export_across = [corr(exported[k - 1], exported[k]) for k in range(1, len(exported))]
    # Whether a sequence frame shows other data than the one before: its
    # truth differs (the reader takes the step nearest a time, or its own
    # rule; the interpolator its own data at every time).
    sequence_within, sequence_across = [], []
    for i in range(2, len(sequence)):  # from the second change on (the first forms the texture)
        c = corr(sequence[i - 1][1], sequence[i][1])
        changed = not np.array_equal(grey(sequence_truths[i - 1]), grey(sequence_truths[i]))
        (sequence_across if changed else sequence_within).append(c)
except ImportError:
    within = across = export_across = sequence_within = sequence_across = []
    turned_rows = []

print("\n%s (%s%s), %d time steps, %dx%d, view %s, pvbatch, ParaView %s, %s\n" % (
    os.path.basename(args.data), args.array, ", reversed" if args.reverse else "", len(times), w, h,
    args.view, pv.GetParaViewVersion(), ", ".join(args.set) or "defaults"))
print("| step | time | picture | A | W (px) |" + (" A, region | W, region |" if region else ""))
print("|---|---|---|---|---|" + ("---|---|" if region else ""))
for k, t, label, m, r in rows:
    line = "| %d | %g | %s | %.3f | %.2f |" % (k, t, label, m.get("A", math.nan), m.get("W", math.nan))
    if region:
        line += " %.3f | %.2f |" % (r.get("A", math.nan), r.get("W", math.nan))
    print(line)


def summary(values):
    values = [v for v in values if not math.isnan(v)]
    if not values:
        return "-"
    return "%.3f (%.3f-%.3f)" % (sum(values) / len(values), min(values), max(values))


print("\nMeans over the steps after the first (min-max):\n")
print("| picture | A | W (px) |" + (" A, region | W, region |" if region else ""))
print("|---|---|---|" + ("---|---|" if region else ""))
for label in dict.fromkeys(label for _, _, label, _, _ in rows):
    sel = [(m, r) for k, _, l, m, r in rows if l == label and k > 0]
    line = "| %s | %s | %s |" % (label, summary([m.get("A", math.nan) for m, _ in sel]),
                                 summary([m.get("W", math.nan) for m, _ in sel]))
    if region:
        line += " %s | %s |" % (summary([r.get("A", math.nan) for _, r in sel]),
                                summary([r.get("W", math.nan) for _, r in sel]))
    print(line)
print("\nCorrelation of the pictures: Play, two renders within a step %s; across a step "
      "change %s; Save Animation, frame to frame %s" % (summary(within), summary(across),
                                                       summary(export_across)))
if turned_rows:
    print("\nThe moving part's texture across each step change (Play; the picture less a 4-px "
          "blur, within the region):\n")
    print("| change to step | turn (degrees) | turned with the part | left in place | "
          "within the step before |")
    print("|---|---|---|---|---|")
    for k, degrees, t, l, wi in turned_rows:
        print("| %d | %.1f | %.3f | %.3f | %.3f |" % (k, degrees, t, l, wi))
    print("\nAfter the first change (min-max): turned %s, left in place %s, within a step %s" % (
        summary([t for _, _, t, _, _ in turned_rows[1:]]),
        summary([l for _, _, _, l, _ in turned_rows[1:]]),
        summary([wi for _, _, _, _, wi in turned_rows[1:]])))
if sequence:
    print("\nSave Animation in Sequence mode, %d frames%s, after the first two (min-max): A %s, "
          "W %s%s; correlation of consecutive frames within a step %s, across a step change %s" % (
              len(sequence), " (TemporalInterpolator)" if args.interpolate else "",
              summary([m.get("A", math.nan) for i, _, m, _ in sequence_rows if i >= 2]),
              summary([m.get("W", math.nan) for i, _, m, _ in sequence_rows if i >= 2]),
              "; region A %s, W %s" % (
                  summary([r.get("A", math.nan) for i, _, _, r in sequence_rows if i >= 2]),
                  summary([r.get("W", math.nan) for i, _, _, r in sequence_rows if i >= 2]))
              if region else "",
              summary(sequence_within), summary(sequence_across)))
if page:
    print("\nThe page: %s, %.1f MB, exported in %.1f s (%d time steps)" % (
        page, os.path.getsize(page) / 1e6, page_seconds, len(times)))
print("\nA step change, ms (the render that first shows a step, the reader's work included): "
      "Surface %s; IBFVS %s%s" % (summary(surface_ms), summary(ibfvs_ms),
                                  "; Surface LIC, each step %s" % summary(lic_ms) if lic_ms else ""))
