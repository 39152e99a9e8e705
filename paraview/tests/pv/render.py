# Drives the IBFVS representation the way a user does, under pvpython or
# pvbatch (also under mpiexec): load the plugin, open data, switch the
# representation, render frames, save screenshots. Run by test_plugin.py
# with one JSON argument:
#   plugin     path of IBFVS.so (empty: ParaView alone)
#   data       a file (.vtp, .pvtp: pieces spread over the ranks, ...)
#   pieces     also save a picture coloured by rank (the split)
#   vectors    [association, name] for SelectInputVectors, or null
#   color      [association, name] to colour by, or null
#   frames     renders before the last screenshot; shots: frames to save at
#   size       [w, h]; out: file name prefix; mask: also save the surface's mask
#   properties {name: value} set on the representation
#   camera, focal, view_angle: the view (default from (3.5, 2.1, 2.8) at the origin)
#   lut        {property: value} set on the colour array's transfer function
#   reference  also save the Surface representation coloured alike (-reference.png)
#   calculator [name, function, later function]: colour by an array computed
#              from the data, its function changed after the frames, then
#              frames again (-changed.png) and Surface's (-reference-changed.png)
#   animation  a series played after the frames: {"mode": "save"} File > Save
#              Animation, one frame per time step (OUT.0000.png, ...); or
#              {"mode": "play", "renders": R}: R renders at each time step, the
#              first and the last two saved (-stepK-rJ.png); or
#              {"mode": "sequence", "frames": K}: Save Animation in Sequence
#              mode, K frames over the series (OUT.0000.png, ...)
#   interpolate  the data through ParaView's TemporalInterpolator
#   also_open  another file opened (not shown): its times join the time keeper's
#   server     HOST:PORT of a pvserver to connect to (the plugin loaded on
#              both sides); remote_render: the server renders (threshold 0)
#   export     {"file": NAME, "properties": {...}}: after the frames,
#              ExportView(NAME) with those exporter properties (File > Export
#              Scene); a failure is printed as "ibfvs-test: export failed: ..."
import json
import sys

import paraview.simple
from paraview.simple import *  # noqa: F401,F403 (ParaView's own idiom)

cfg = json.loads(sys.argv[1])
if cfg.get("server"):
    # A client of a pvserver: the plugin on both sides (Tools > Manage
    # Plugins, server and client), the data read there.
    host, port = cfg["server"].rsplit(":", 1)
    Connect(host, int(port))
    if cfg.get("plugin"):
        LoadPlugin(cfg["plugin"], remote=True, ns=globals())
if cfg.get("plugin"):
    LoadPlugin(cfg["plugin"], remote=False, ns=globals())

source = OpenDataFile(cfg["data"])
if cfg.get("also_open"):  # another source, not shown: its times are the time keeper's too
    OpenDataFile(cfg["also_open"])
if cfg.get("pieces"):
    source = ProcessIdScalars(Input=source)
calculator = None
if cfg.get("interpolate"):
    source = TemporalInterpolator(Input=source)
if cfg.get("calculator"):
    name, function, _ = cfg["calculator"]
    source = calculator = Calculator(Input=source, ResultArrayName=name, Function=function)

paraview.simple._DisableFirstRenderCameraReset()  # the camera below is the view
view = GetActiveViewOrCreate("RenderView")
w, h = cfg.get("size", [320, 240])
view.ViewSize = [w, h]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0.2, 0.3, 0.4]
if "fxaa" in cfg:  # ParaView's default: on
    view.UseFXAA = cfg["fxaa"]
if cfg.get("remote_render"):  # the server renders, however small the data
    view.RemoteRenderThreshold = 0
display = Show(source, view)
view.CameraPosition = cfg.get("camera", [3.5, 2.1, 2.8])
view.CameraFocalPoint = cfg.get("focal", [0, 0, 0])
view.CameraViewUp = [0, 0, 1]
view.CameraViewAngle = cfg.get("view_angle", 30)
# The first render: a run that does not reach it soon is taken for hung and
# stopped at once by the test harness, which waits for this line.
Render(view)
print("ibfvs-test: first render", flush=True)

if cfg.get("pieces"):
    ColorBy(display, ("POINTS", "ProcessId"))
    Render(view)
    SaveScreenshot(cfg["out"] + "-pieces.png", view, ImageResolution=[w, h])
    ColorBy(display, None)

if cfg.get("mask"):
    # The surface in flat magenta: where the texture may be, and nowhere else
    # (uncoloured: Show colours a calculator's output by its result).
    if display.ColorArrayName[1]:
        ColorBy(display, None)
    display.AmbientColor = [1, 0, 1]
    display.DiffuseColor = [1, 0, 1]
    display.Ambient, display.Diffuse = 1.0, 0.0
    Render(view)
    SaveScreenshot(cfg["out"] + "-mask.png", view, ImageResolution=[w, h])
    display.AmbientColor = [1, 1, 1]
    display.DiffuseColor = [1, 1, 1]
    display.Ambient, display.Diffuse = 0.0, 1.0
    Render(view)
    SaveScreenshot(cfg["out"] + "-surface.png", view, ImageResolution=[w, h])



def colour():
    """Colours by cfg's array through its transfer function, with cfg's
    settings of that function, over the data's range."""
    ColorBy(display, tuple(cfg["color"]))
    lut = GetColorTransferFunction(cfg["color"][1])
    for name, value in cfg.get("lut", {}).items():
        setattr(lut, name, value)
    display.RescaleTransferFunctionToDataRange(False, True)


def reference(suffix):
    """The Surface representation's picture of the same colouring."""
    shown = display.Representation
    display.Representation = "Surface"
    Render(view)
    SaveScreenshot("%s-reference%s.png" % (cfg["out"], suffix), view, ImageResolution=[w, h])
    display.Representation = shown


if cfg.get("reference"):
    colour()
    reference("")

available = list(display.Representation.Available)
display.Representation = cfg.get("representation", "IBFVS")
if cfg.get("vectors"):
    display.SelectInputVectors = cfg["vectors"]
for name, value in cfg.get("properties", {}).items():
    setattr(display, name, value)
if cfg.get("color"):
    colour()

shots = set(cfg.get("shots", []))
for frame in range(1, cfg["frames"] + 1):
    Render(view)
    if frame in shots:
        SaveScreenshot("%s-%d.png" % (cfg["out"], frame), view, ImageResolution=[w, h])
if calculator is not None:
    calculator.Function = cfg["calculator"][2]
    calculator.UpdatePipeline()
    display.RescaleTransferFunctionToDataRange(False, True)  # as Apply does in the GUI
    for frame in range(cfg["frames"]):
        Render(view)
    SaveScreenshot(cfg["out"] + "-changed.png", view, ImageResolution=[w, h])
    reference("-changed")
animation = cfg.get("animation")
if animation:
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    times = list(GetTimeKeeper().TimestepValues)
    if animation["mode"] == "save":
        SaveAnimation(cfg["out"] + ".png", view, ImageResolution=[w, h])
    elif animation["mode"] == "sequence":
        scene.PlayMode = "Sequence"
        scene.NumberOfFrames = animation["frames"]
        SaveAnimation(cfg["out"] + ".png", view, ImageResolution=[w, h])
    else:
        renders = animation["renders"]
        for k, t in enumerate(times):
            view.ViewTime = t  # as Play's next step, without the scene's own extra render
            for r in range(renders):
                Render(view)
                if r in (0, renders - 2, renders - 1):
                    SaveScreenshot("%s-step%d-r%d.png" % (cfg["out"], k, r), view,
                                   ImageResolution=[w, h])
export = cfg.get("export")
if export:
    try:
        ExportView(export["file"], view=view, **export.get("properties", {}))
        print("ibfvs-test: exported", export["file"], flush=True)
    except Exception as e:  # ParaView's own refusal (no exporter for the name)
        print("ibfvs-test: export failed:", " ".join(str(a) for a in e.args), flush=True)
with open(cfg["out"] + ".json", "w") as f:
    json.dump({"available": available,
               "remote": bool(view.GetClientSideObject().GetUseDistributedRenderingForRender())},
              f)
print("rendered", cfg["frames"], "frames")
