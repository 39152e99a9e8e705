"""The skin-friction topology's cost beside one Surface LIC frame of the same
surface, in one pvbatch session (issue 64; docs/performance.md):

  xvfb-run -a -s '-screen 0 1280x1024x24 -noreset' pvbatch scripts/bench_topology.py \\
      DATA ARRAY [--blocks ...] [--reverse] [--size W,H] [--repeats N] [--plugin IBFVS.so]

DATA's surface and ARRAY as scripts/lic_compare.py reads them (pvmeasure.py:
OpenFOAM patches, cell data to the points). Times, each the median of
--repeats runs: Filters > Skin-Friction Topology executing on the surface
(the data read once before; the filter made to execute again by a change
of Minimum Length by a millionth of a scale, which keeps every line), and Surface LIC's frame at
--size, rendered after the camera turned by 2 degrees (what each new view
costs it; its first frame, with its set-up, apart). Prints one line each
and the filter's summary.
"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview.simple as pv  # noqa: E402
from paraview import servermanager  # noqa: E402

from pvmeasure import ROOT, bounding_sphere, flow_of, place_camera  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("data")
parser.add_argument("array")
parser.add_argument("--blocks", default="")
parser.add_argument("--reverse", action="store_true")
parser.add_argument("--size", default="800,600")
parser.add_argument("--repeats", type=int, default=5)
parser.add_argument("--plugin", default=os.path.join(ROOT, "build/lib/ibfvs/paraview/IBFVS/IBFVS.so"))
args = parser.parse_args()
pv.LoadPlugin(args.plugin, remote=False, ns=globals())
blocks = [b for b in args.blocks.split(",") if b]
source, flow = flow_of(args.data, args.array, args.reverse, blocks)
source.UpdatePipeline(max(source.TimestepValues or [0.0]))
flow.UpdatePipeline(max(source.TimestepValues or [0.0]))
cells = flow.GetDataInformation().GetNumberOfCells()

topology = SkinFrictionTopology(Input=flow)  # noqa: F405 (the plugin's, in this namespace)
topology.Vectors = ["POINTS", "flow"]
topology.UpdatePipeline()
least = float(topology.MinimumLength)  # its default
found = []
for k in range(args.repeats):
    topology.MinimumLength = least + 1e-6 * (k + 1)  # executes again, the same lines
    start = time.perf_counter()
    topology.UpdatePipeline()
    found.append(time.perf_counter() - start)
summary = servermanager.Fetch(topology).GetFieldData().GetAbstractArray("summary").GetValue(0)

w, h = (int(v) for v in args.size.split(","))
view = pv.CreateView("RenderView")
view.ViewSize = [w, h]
view.OrientationAxesVisibility = 0
display = pv.Show(flow, view)
display.Representation = "Surface LIC"
display.SelectInputVectors = ["POINTS", "flow"]
centre, radius = bounding_sphere(flow)
start = time.perf_counter()
place_camera(view, centre, radius, [0, 0, 1], 1.0, 0.0, 10.0)
pv.Render(view)
first = time.perf_counter() - start
frames = []
for k in range(args.repeats):
    place_camera(view, centre, radius, [0, 0, 1], 1.0, 2.0 * (k + 1), 10.0)
    start = time.perf_counter()
    pv.Render(view)
    frames.append(time.perf_counter() - start)

ms = lambda seconds: 1000.0 * seconds  # noqa: E731
print("surface: %s, %d cells" % (os.path.basename(args.data), cells))
print("Skin-Friction Topology: %.1f ms (median of %d; %.1f-%.1f)" % (
    ms(statistics.median(found)), len(found), ms(min(found)), ms(max(found))))
print("Surface LIC frame at %dx%d, the camera turned: %.0f ms (median of %d; %.0f-%.0f); "
      "its first frame %.0f ms" % (w, h, ms(statistics.median(frames)), len(frames),
                                   ms(min(frames)), ms(max(frames)), ms(first)))
print("ratio: the topology costs %.3f of a Surface LIC frame" % (
    statistics.median(found) / statistics.median(frames)))
print("summary: " + summary)
