"""ParaView's Surface LIC of a sphere turning about the view axis, the static
picture docs/quality.md compares ibfvs with. Run with ParaView's Python
(Debian: python3-paraview; X only, so under xvfb-run):

  xvfb-run -a pvpython scripts/vtk_lic_reference.py OUT.png [enhance]

then measure it: ibfvs quality --png OUT.png. The sphere (radius 1, seen from
4.5 units along +Z, 30 degree view angle) covers the same part of the image as
ibfvs's `globe` mesh with --camera 0,0,1.3, and the field v = (-y, x, 0) turns
about the view axis, as ibfvs's rotate:0,0,1. The LIC is shown as it is (white
surface, ambient light only, LIC intensity 1) on a red background;
`enhance` turns on ParaView's contrast enhancement of the LIC.
"""
import sys

from paraview.simple import (Calculator, CreateRenderView, Render, SaveScreenshot, Show,
                             Sphere)

out = sys.argv[1]
enhance = len(sys.argv) > 2 and sys.argv[2] == "enhance"
size = 512
sphere = Sphere(Radius=1.0, ThetaResolution=256, PhiResolution=128)
field = Calculator(Input=sphere, ResultArrayName="v", Function="-coordsY*iHat + coordsX*jHat")
view = CreateRenderView()
view.ViewSize = [size, size]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 0.0, 0.0]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
shown = Show(field, view)
shown.SetRepresentationType("Surface LIC")
shown.SelectInputVectors = ["POINTS", "v"]
shown.ColorArrayName = ["POINTS", ""]
shown.DiffuseColor = [1.0, 1.0, 1.0]
shown.AmbientColor = [1.0, 1.0, 1.0]
shown.Ambient = 1.0
shown.Diffuse = 0.0
shown.Specular = 0.0
shown.LICIntensity = 1.0
if enhance:
    shown.EnhanceContrast = "LIC and Color"
Render(view)  # the first render resets the camera; set it after
view.CameraPosition = [0.0, 0.0, 4.5]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraViewAngle = 30
Render(view)
SaveScreenshot(out, view, ImageResolution=[size, size])
