#!/usr/bin/env bash
# Regenerates docs/paraview-window.png: the ParaView window (Debian's 5.11,
# under Xvfb) showing the IBFVS representation of a swirl on a sphere,
# coloured by ParaView's colour map, with the IBFVS properties in the panel.
# Needs the built plugin and xdotool (apt-get install xdotool), which arranges
# the panels as a user would. Usage: scripts/paraview_screenshot.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
plugin="$build/lib/ibfvs/paraview/IBFVS/IBFVS.so"
[[ -f "$plugin" ]] || { echo "paraview_screenshot: no plugin at $plugin (build first)" >&2; exit 1; }
command -v xdotool >/dev/null || { echo "paraview_screenshot: needs xdotool" >&2; exit 1; }
work="$(mktemp -d)"
trap 'kill "${paraview_pid:-0}" "${xvfb_pid:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
# A fresh settings folder: no welcome dialog, no message window.
mkdir -p "$work/home/.config/ParaView"
printf '[General]\nGeneralSettings.ShowWelcomeDialog=false\nOutputMessages.AlwaysOpenForNewMessages=false\n' \
  > "$work/home/.config/ParaView/ParaView5.11.0.ini"
cat > "$work/scene.py" <<PY
from paraview.simple import *
LoadPlugin("$plugin", remote=False, ns=globals())
sphere = Sphere(ThetaResolution=128, PhiResolution=128)
swirl = Calculator(Input=sphere, ResultArrayName="wind",
                   Function="-coordsY*iHat+coordsX*jHat+0.4*coordsZ*kHat")
view = GetActiveViewOrCreate("RenderView")
display = Show(swirl, view)
display.Representation = "IBFVS"
display.SelectInputVectors = ["POINTS", "wind"]
ColorBy(display, ("POINTS", "wind", "Magnitude"))
view.CameraPosition = [2.6, 1.6, 1.9]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
SetActiveSource(swirl)
Render(view)
PY
display=":$((RANDOM % 400 + 100))"
Xvfb "$display" -screen 0 1600x1000x24 >/dev/null 2>&1 & xvfb_pid=$!
sleep 2
HOME="$work/home" DISPLAY="$display" paraview -geometry 1600x1000+0+0 --script="$work/scene.py" \
  >"$work/paraview.log" 2>&1 & paraview_pid=$!
sleep 30  # start-up, the plugin, and some frames of the animation
export DISPLAY="$display"
xdotool mousemove 60 571 click 1   # fold the calculator's own properties
sleep 1
xdotool mousemove 150 438 mousedown 1 mousemove 150 300 mousemove 150 215 mouseup 1  # taller panel
sleep 1
xdotool mousemove 296 700 mousedown 1 mousemove 400 700 mousemove 470 700 mouseup 1  # wider panel
sleep 3
ffmpeg -v error -y -f x11grab -video_size 1600x1000 -i "$display" -frames:v 1 "$work/window.png"
ffmpeg -v error -y -i "$work/window.png" -vf scale=1200:-1 "$root/docs/paraview-window.png"
echo "wrote docs/paraview-window.png"
