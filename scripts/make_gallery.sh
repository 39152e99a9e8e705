#!/usr/bin/env bash
# Regenerates docs/gallery/ (small stills and short animations of the paper's
# figures 2-9, every one rendered by ibfvs from the scenes in scenes/) and
# docs/gallery.md, which shows each with the command that made it. The
# commands listed are the ones run here, so page and pictures cannot drift.
# Usage: scripts/make_gallery.sh [BUILD_DIR]   (default: build)
# Needs the fetched data (scripts/fetch_data.sh) and ffmpeg for the videos.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
ibfvs=$build/ibfvs
[[ -x $ibfvs ]] || { echo "make_gallery.sh: $ibfvs not built (cmake --build $build)" >&2; exit 1; }
export IBFVS_DATA_DIR=${IBFVS_DATA_DIR:-$here/data}
[[ -s $IBFVS_DATA_DIR/earth/etopo20.cdf ]] || {
  echo "make_gallery.sh: data missing in $IBFVS_DATA_DIR (run scripts/fetch_data.sh)" >&2
  exit 1
}
cd "$here"
out=docs/gallery
rm -rf "$out"
mkdir -p "$out"
page=docs/gallery.md
still_size=400x400
video_size=320x320

{
  echo "# Gallery: the paper's figures, rendered by ibfvs"
  echo
  echo "Every picture here was rendered by \`scripts/make_gallery.sh\` (which also"
  echo "wrote this page) from the scenes in \`scenes/\`, headless with EGL on"
  echo "$("$ibfvs" render --mesh torus --size 16x16 --frames 1 --out "$out/probe.png" |
    sed -n 's/.* fps on \([^|]*\) |.*/\1/p'), at ${still_size} pixels (stills) and"
  echo "${video_size} (videos). The command under each picture reproduces it; drop"
  echo "\`--size\` and \`--out\` for the scene's own size and video. Figure numbers"
  echo "are those of van Wijk, *Image Based Flow Visualization for Curved"
  echo "Surfaces*, IEEE Visualization 2003."
} >"$page"
rm -f "$out/probe.png"

section() {  # section TITLE TEXT
  printf '\n## %s\n\n%s\n' "$1" "$2" >>"$page"
}

# render NAME KIND ARGS...: KIND still (PNG) or video (MP4); prints the image
# markdown into the page and the command into a code block after it.
pending_images=()
pending_commands=()
render() {
  local name=$1 kind=$2
  shift 2
  local file size
  if [[ $kind == still ]]; then file=$out/$name.png size=$still_size; else file=$out/$name.mp4 size=$video_size; fi
  echo "make_gallery.sh: $file" >&2
  "$ibfvs" render "$@" --size "$size" --out "$file" -q
  local shown=()
  for a in "$@"; do
    if [[ $a == *" "* ]]; then shown+=("'$a'"); else shown+=("$a"); fi
  done
  pending_commands+=("ibfvs render ${shown[*]} --size $size --out $file")
  if [[ $kind == still ]]; then
    pending_images+=("![$name](gallery/$name.png)")
  else
    pending_images+=("[$name.mp4](gallery/$name.mp4) ($(du -k "$file" | cut -f1) KB)")
  fi
}

flush() {  # flush CAPTION: the pictures side by side, the caption, the commands
  {
    echo
    echo "${pending_images[*]}"
    echo
    echo "*$1*"
    echo
    echo '```sh'
    printf '%s\n' "${pending_commands[@]}"
    echo '```'
  } >>"$page"
  pending_images=()
  pending_commands=()
}

section "Figure 2: boundary inflow (section 3.5)" \
  "A landscape with the flow downhill along the gradient, normalised in image space, alpha 0.1, beta 0.4, seen at a grazing angle with the horizon in view. The paper: \"When red is used as background color, some inflow across the horizon is visible, when grey is used, no artifacts are visible.\""
render figure2-red still scenes/figure2-landscape.toml --background 0.8,0.1,0.1
render figure2-grey still scenes/figure2-landscape.toml
flush "Left: red background. The paper's red streaks entering where the flow comes over the horizon (top edge) are gone: where t(x) leaves the last frame's surface, ibfvs starts from fresh noise instead of the image's background (docs/quality.md). Right: the default grey background."

section "Figure 3: uniform density in screen and in world space (section 3.6)" \
  "Two cylinders with the flow along their axes, in strong perspective. IBFVS gives a texture of constant density on the screen; a solid (object-space) noise gives constant density on the surface."
render figure3-image still scenes/figure3-cylinders.toml
render figure3-object still scenes/figure3-cylinders.toml --noise-space object
flush "Left: \`--noise-space image\` (the paper's method): the grain is the same near and far. Right: \`--noise-space object\`: the grain shrinks with distance and follows the curvature of the cylinders, like the paper's texture-mapped right picture."

section "Figure 4: velocity projected on the surface and in 3D (section 3.8)" \
  "A torus in a vertical uniform flow. Projected on the tangent plane the texture shows the shape, with the separation line along the top of the tube; used as given in 3D it shows a simple uniform upward stream, like hairs on a wire mesh aligned with the flow."
render figure4-projected still scenes/figure4-torus.toml
render figure4-3d still scenes/figure4-torus.toml --tangent 3d
flush "Left: \`--tangent project\`: the flow parts along the top and bottom crest circles of the tube (no motion there, so the noise stays unstreaked). Right: \`--tangent 3d\`: vertical streaks everywhere."

section "Figure 5: potential flow on the bunny (section 4.1)" \
  "Two line elements: a repelling, rotating line source through the head and an attracting, rotating one through the legs."
render figure5-bunny still scenes/figure5-bunny.toml
render figure5-bunny video scenes/figure5-bunny.toml --frames 120
flush "The flow swirls away from the head and spirals into the legs. The video shows the texture moving (120 frames)."

section "Figure 6: winds on the earth (section 4.1)" \
  "The COADS climatological winds on a geodesic globe. Left: the texture strength follows the wind speed over a land/sea map (ETOPO20 relief, blue sea, red land). Right: the speed as colour; COADS has no winds over land, which therefore stays plain. The video plays the 12 months: the Indian monsoon turns from north-easterly (January) to south-westerly (July), and the westerlies circle Antarctica all year."
render figure6-january-map still scenes/figure6-earth-wind.toml --time 0 --frames 150
render figure6-january-speed still scenes/figure6-earth-speed.toml
render figure6-july-map still scenes/figure6-earth-wind.toml --time 6 --frames 150
render figure6-year video scenes/figure6-earth-wind.toml --frames-per-step 12 --frames 144
flush "January with the map and strength by speed; January with speed as colour (viridis, 0-10 m/s); July: the monsoon has reversed over the Arabian Sea and the Bay of Bengal. The video: a year, 12 frames a month."

section "Figure 7: topological decomposition (section 4.1)" \
  "alpha = 0, F_t started with random colours per noise cell, flow downhill: each pixel takes the colour of the summit that steepest ascent from it reaches. Then the texture is locked and the surface is seen obliquely; the borders between colours are the valley lines. Regions whose ascent leaves the map take the background grey (their summit is off the map)."
render figure7-top still scenes/figure7-topology.toml --frames 40
render figure7-locked still scenes/figure7-topology.toml
render figure7-relief-top still scenes/figure7-relief-topology.toml --frames 40
render figure7-relief-locked still scenes/figure7-relief-topology.toml
render figure7-topology video scenes/figure7-topology.toml
flush "A B-spline landscape from the top after 40 steps, then locked and oblique; the same for the ETOPO20 relief of the Alps (5-16 E, 43-48.5 N). The video shows the colours spreading downhill, the lock, and the camera moving with the texture fixed on the surface. Faint rings inside some basins are the history of the summit's own colour, which the bilinear lookups mix during the first steps and the flow then carries outward."

section "Figure 8: moving particles and a dense texture along principal directions (section 4.2)" \
  "The twice Loop-subdivided elephant. Particles: a spike time profile, so that few noise values are bright at a time, added rather than blended, along kappa_min. Dense: the standard noise along kappa_min, signed along +Y (the sign rule leaves a seam where the direction turns horizontal, as the paper shows on the breast)."
render figure8-particles still scenes/figure8-particles.toml --frames 120
render figure8-principal still scenes/figure8-principal.toml --frames 120
render figure8-particles video scenes/figure8-particles.toml --frames 120
flush "Left: \`--style particles\`. Right: \`--style principal\`. The video shows the particles moving."

section "Figure 9: dirty bronze (section 4.2)" \
  "Colour and texture strength both follow kappa_max: clean metal on the convex parts, patina and the dirt of the texture in the hollows, \"as if a dirty surface has superficially been cleaned\". Only the mesh is input; the bounds are percentiles of kappa_max."
render figure9-bronze still scenes/figure9-bronze.toml --frames 120
render figure9-bronze-zoomed still scenes/figure9-bronze.toml --frames 120 --camera 40,10,0.5
flush "Left: \`--style bronze\` on the bunny. Right: zoomed in; the texture is regenerated at the new scale, so detail stays sharp."

echo "make_gallery.sh: wrote $page and $(ls "$out" | wc -l) files in $out ($(du -sh "$out" | cut -f1))" >&2
