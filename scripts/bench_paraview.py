"""Frame time of the IBFVS representation in pvbatch, for docs/performance.md.

  xvfb-run -a pvbatch scripts/bench_paraview.py PLUGIN|none [THETA PHI [W H [FRAMES]]]
  xvfb-run -a mpiexec -n 2 pvbatch scripts/bench_paraview.py PLUGIN ...

A sphere of THETA x PHI points (2 THETA (PHI - 2) triangles; the sphere
source splits it over the ranks) with a swirl; the Surface representation
and IBFVS, each timed over FRAMES renders of a W x H view after warm-up
frames. Prints one line per representation (rank 0's clock: the collective
frame)."""
import sys
import time

from paraview.simple import *  # noqa: F401,F403

plugin = sys.argv[1]
theta, phi = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (2000, 1000)
w, h = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (1024, 768)
frames = int(sys.argv[6]) if len(sys.argv) > 6 else 30
if plugin != "none":  # "none": ParaView alone, the Surface representation only
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
print("ranks %d, %d points, %d triangles, view %dx%d" % (
    ranks, info.GetNumberOfPoints(), info.GetNumberOfCells(), w, h), flush=True)


def timed(representation):
    display.Representation = representation
    if representation == "IBFVS":
        display.SelectInputVectors = ["POINTS", "v"]
    start = time.perf_counter()
    Render(view)  # the first frame: geometry and set-up
    setup = time.perf_counter() - start
    for _ in range(5):
        Render(view)
    start = time.perf_counter()
    for _ in range(frames):
        Render(view)
    per_frame = (time.perf_counter() - start) / frames
    print("%-8s first frame %6.2f s, then %7.1f ms per frame (%5.2f fps)" % (
        representation, setup, 1000 * per_frame, 1 / per_frame), flush=True)


timed("Surface")
if plugin != "none":
    timed("IBFVS")
