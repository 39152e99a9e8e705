# Filters > Skin-Friction Topology as a user drives it in pvpython: open a
# series, apply the filter, and at each of its times fetch what it made;
# show it over the IBFVS representation of the data in its own colours (its
# `colour` array, not mapped: no colour table to copy), and save a picture;
# then hide it and let the representation draw the features itself (its
# Overlay), and save a second. Run by test_plugin_topology.py with one JSON
# argument: plugin, data, vectors ([association, name]), reverse, out and
# overlay_out (the pictures' files), camera (the view's position).
# Prints one line "ibfvs-test: " and the JSON of each time's cells: kinds,
# ids, the line points' largest |z|, the summary.
import json
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's own idiom)

cfg = json.loads(sys.argv[1])
LoadPlugin(cfg["plugin"], remote=False, ns=globals())
data = OpenDataFile(cfg["data"])
topology = SkinFrictionTopology(Input=data)
topology.Vectors = cfg["vectors"]
topology.Reverse = int(cfg.get("reverse", False))
times = list(data.TimestepValues) if data.TimestepValues else [0.0]
found = []
for t in times:
    topology.UpdatePipeline(t)
    out = servermanager.Fetch(topology)
    kinds = out.GetCellData().GetArray("kind")
    feature_ids = out.GetCellData().GetArray("id")
    z = 0.0
    for c in range(out.GetNumberOfCells()):
        if kinds.GetValue(c) >= 10:
            ids = out.GetCell(c).GetPointIds()
            for k in range(ids.GetNumberOfIds()):
                z = max(z, abs(out.GetPoint(ids.GetId(k))[2]))
    cells = sorted((kinds.GetValue(c), feature_ids.GetValue(c)) for c in range(out.GetNumberOfCells()))
    found.append({"time": t, "kinds": [k for k, _ in cells], "ids": [i for _, i in cells],
                  "line_z": z, "summary": out.GetFieldData().GetAbstractArray("summary").GetValue(0)})

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [320, 320]
view.OrientationAxesVisibility = 0
view.Background = [0.2, 0.3, 0.4]
surface = Show(data, view)
surface.Representation = "IBFVS"
surface.SelectInputVectors = cfg["vectors"]
features = Show(topology, view)
ColorBy(features, ("CELLS", "colour"))
features.MapScalars = 0  # the filter's own RGB
features.LineWidth = 4
features.PointSize = 12
features.RenderPointsAsSpheres = 1
features.Ambient = 1.0
features.Diffuse = 0.0
view.CameraPosition = cfg["camera"]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
view.CameraParallelProjection = 1
view.CameraParallelScale = 0.6
view.ViewTime = times[0]
for frame in range(20):
    Render(view)
SaveScreenshot(cfg["out"], view)
# The representation alone, drawing the same features itself.
Hide(topology, view)
surface.Overlay = "Topology"
for frame in range(20):
    Render(view)
SaveScreenshot(cfg["overlay_out"], view)
print("ibfvs-test: " + json.dumps(found))
