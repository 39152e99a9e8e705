"""Frame time and memory of the IBFVS representation in pvbatch, beside
ParaView's Surface and Surface LIC in the same session, for
docs/paraview.md and docs/performance.md.

  xvfb-run -a pvbatch scripts/bench_paraview.py PLUGIN|none [THETA PHI [W H [FRAMES [TURN]]]]
  xvfb-run -a mpiexec -n 2 pvbatch --symmetric scripts/bench_paraview.py PLUGIN ...

A sphere of THETA x PHI points (2 THETA (PHI - 2) triangles; the sphere
source splits it over the ranks) with a swirl; Surface, Surface LIC and
IBFVS in turn, each timed over FRAMES renders of a W x H view after its
first frame (geometry and set-up, timed alone) and warm-up frames; TURN
degrees of azimuth a timed frame (default 0: a still camera, where Surface
LIC draws the picture it computed once again). Prints
one line per representation (rank 0's clock: the collective frame), and
with --symmetric (every rank runs the script) each rank's resident memory
after each (VmRSS; the peak, VmHWM, at the end). Without it, rank 0's only.
"""
import sys
import time

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkParallelCore import vtkMultiProcessController

plugin = sys.argv[1]
theta, phi = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (2000, 1000)
w, h = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (1024, 768)
frames = int(sys.argv[6]) if len(sys.argv) > 6 else 30
turn = float(sys.argv[7]) if len(sys.argv) > 7 else 0.0
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks_running = controller.GetNumberOfProcesses() if controller else 1


def say(text):
    if rank == 0:
        print(text, flush=True)


def memory(field="VmRSS"):
    """This process's resident memory in MB (/proc/self/status)."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def gathered(value):
    """Every rank's value on rank 0 (symmetric: each runs this), or ours."""
    if not (controller and ranks_running > 1):
        return [value]
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    send, receive = vtkDoubleArray(), vtkDoubleArray()
    send.InsertNextValue(value)
    controller.Gather(send, receive, 0)
    return [receive.GetValue(i) for i in range(receive.GetNumberOfTuples())]


def total(count):
    """A count over the ranks: symmetric, each rank's data information is
    its own piece's."""
    return int(sum(gathered(float(count))))


def memory_line(label, field="VmRSS"):
    """Every rank's memory (symmetric), or rank 0's, as one line on rank 0."""
    values = gathered(memory(field))
    say("%-12s %s %s" % (label, "peak" if field == "VmHWM" else "resident",
                         ", ".join("rank %d %.0f MB" % (r, v) for r, v in enumerate(values))))


if plugin != "none":  # "none": ParaView alone, Surface and Surface LIC only
    LoadPlugin(plugin, remote=False, ns=globals())

sphere = Sphere(ThetaResolution=theta, PhiResolution=phi)
swirl = Calculator(Input=sphere, ResultArrayName="v", Function="-coordsY*iHat+coordsX*jHat+0.3*kHat")
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [w, h]
view.OrientationAxesVisibility = 0
display = Show(swirl, view)
view.CameraPosition = [2.5, 1.5, 2.0]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
info = swirl.GetDataInformation()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
say("ranks %d, %d points, %d triangles, view %dx%d" % (
    ranks, total(info.GetNumberOfPoints()), total(info.GetNumberOfCells()), w, h))
memory_line("data")


def timed(representation):
    display.Representation = representation
    if representation != "Surface":
        display.SelectInputVectors = ["POINTS", "v"]
    start = time.perf_counter()
    Render(view)  # the first frame: geometry and set-up
    setup = time.perf_counter() - start
    for _ in range(3):
        Render(view)
    camera = GetActiveCamera()
    start = time.perf_counter()
    for _ in range(frames):
        if turn:
            camera.Azimuth(turn)
        Render(view)
    per_frame = (time.perf_counter() - start) / frames
    say("%-12s first frame %6.2f s, then %7.1f ms per frame (%5.2f fps)" % (
        representation, setup, 1000 * per_frame, 1 / per_frame))
    memory_line(representation)


timed("Surface")
timed("Surface LIC")
if plugin != "none":
    timed("IBFVS")
memory_line("end", "VmHWM")
