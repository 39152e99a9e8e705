"""What a time step change costs the IBFVS representation beside ParaView's
Surface, in one pvbatch session (docs/paraview.md, "Time"): the work each
representation does when its data changes, apart from the reader's.

Both show one series through a TemporalCache that holds every step (the
reader ran before the clock starts, so what is timed is the representation's
own work: ParaView's geometry filter and delivery, and the mapper's upload,
which for IBFVS is taking the surface, preparing the change and handing it to
the texture). In each round each representation plays every step as Play
does: RENDERS renders at a step, the first one showing the new step. The
change costs the first render less the median of the rest (the same view's
steady frame); rounds alternate which representation goes first. Prints the
medians over every step change of every round.

  xvfb-run -a pvbatch scripts/step_change_cost.py DATA ARRAY [options]

  DATA    a series ParaView opens (.foam, .pvd, .series, ...)
  ARRAY   the vector array (point or cell data)
  --blocks A,B      OpenFOAM regions to read (default: every patch)
  --view AZ,EL      the camera about the data's centre (degrees), default 0,10
  --up X,Y,Z        the up axis (default 0,0,1)
  --size W,H        default 1024,768
  --renders N       renders at each step (default 8; IBFVS gives a step change
                    one texture frame once the view rendered the last step at
                    least 2 x FramesPerStep times)
  --rounds N        default 4
  --save-animation  one render per step instead (Save Animation: the change
                    then gets FramesPerStep texture frames); the cost is the
                    whole render
  --frames-per-step N  the IBFVS representation's FramesPerStep (default: its
                    own, 3); 1 leaves a change one texture frame, whatever
                    it moved: the change's own work alone
  --plugin PATH     IBFVS.so (default: build/lib/ibfvs/paraview/IBFVS/IBFVS.so)
"""
import os
import statistics
import time

import paraview.simple as pv

import pvmeasure

parser = pvmeasure.series_arguments()
parser.add_argument("--renders", type=int, default=8)
parser.add_argument("--rounds", type=int, default=4)
parser.add_argument("--save-animation", action="store_true")
parser.add_argument("--frames-per-step", type=int, default=0)
args = parser.parse_args()
(w, h), up, (azimuth, elevation) = pvmeasure.series_view(args)
pv.LoadPlugin(args.plugin, remote=False, ns={})

source, flow = pvmeasure.flow_of(args.data, args.array, False,
                                 args.blocks.split(",") if args.blocks else None)
times = list(source.TimestepValues) if source.TimestepValues else [0.0]
if len(times) < 2:
    raise SystemExit("step_change_cost: %s has one time step; nothing changes" % args.data)
cache = pv.TemporalCache(Input=flow, CacheSize=len(times) + 1)
for t in times:
    cache.UpdatePipeline(t)
centre, radius = pvmeasure.bounding_sphere(flow)
pv._DisableFirstRenderCameraReset()

views = {}
for name in ("Surface", "IBFVS"):
    view = pv.CreateRenderView()
    view.ViewSize = [w, h]
    view.OrientationAxesVisibility = 0
    pvmeasure.place_camera(view, centre, radius, up, 1.0, azimuth, elevation)
    display = pv.Show(cache, view)
    display.ColorArrayName = ["POINTS", ""]
    display.Representation = name
    if name == "IBFVS":
        display.SelectInputVectors = ["POINTS", "flow"]
        if args.frames_per_step:
            display.FramesPerStep = args.frames_per_step
    views[name] = view

renders = 1 if args.save_animation else max(args.renders, 3)
changes = {name: [] for name in views}
steady = {name: [] for name in views}


def play(name):
    view = views[name]
    for t in times:
        view.ViewTime = t
        ms = []
        for _ in range(renders):
            start = time.perf_counter()
            pv.Render(view)
            ms.append(1e3 * (time.perf_counter() - start))
        changes[name].append(ms[0])
        if renders > 1:
            steady[name].append(statistics.median(ms[1:]))


for name in views:  # a first round untimed: programs compiled, buffers made
    play(name)
    changes[name].clear()
    steady[name].clear()
for k in range(args.rounds):
    for name in (list(views) if k % 2 == 0 else list(views)[::-1]):
        play(name)

print("\n%s (%s), %d time steps, %dx%d, %s, %d rounds, FramesPerStep %s, pvbatch, ParaView %s\n" % (
    os.path.basename(args.data), args.array, len(times), w, h,
    "one render a step (Save Animation)" if args.save_animation else "%d renders a step" % renders,
    args.rounds, args.frames_per_step or "default", pv.GetParaViewVersion()))
if args.save_animation:
    print("| representation | a step's render, ms |")
    print("|---|---|")
    for name in views:
        print("| %s | %.1f |" % (name, statistics.median(changes[name])))
else:
    print("| representation | change render, ms | steady render, ms | the change costs, ms |")
    print("|---|---|---|---|")
    cost = {}
    for name in views:
        extra = [c - s for c, s in zip(changes[name], steady[name])]
        cost[name] = statistics.median(extra)
        print("| %s | %.2f | %.2f | %.2f |" % (name, statistics.median(changes[name]),
                                              statistics.median(steady[name]), cost[name]))
    print("\nIBFVS's change against Surface's: %.2f times" % (cost["IBFVS"] / cost["Surface"]))
