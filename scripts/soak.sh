#!/usr/bin/env bash
# Long runs (docs/reliability.md), resident memory sampled every 5 s:
#   scripts/soak.sh render [FRAMES=100000] [SIZE=128x128]
#       ibfvs render of the cow with a turning camera (--orbit), the
#       paper's dynamic case, to the last frame's PNG;
#   scripts/soak.sh view [SECONDS=600]
#       ibfvs view under Xvfb driven by a script that drags, zooms, pans,
#       changes settings and styles, locks, adds flow elements and takes
#       screenshots in a loop, until SECONDS have passed (then SIGTERM).
# Prints the samples and a summary (first, largest, last RSS after the first
# minute); fails if the program died before its time.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ibfvs=${IBFVS:-build/ibfvs}
mode=${1:-render}
mesh=data/meshes/cow.off
[[ -f $mesh ]] || mesh=torus
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sample() {  # PID LABEL: RSS in MiB every 5 s while it runs
  local pid=$1 start=$SECONDS
  while kill -0 "$pid" 2>/dev/null; do
    local kb
    kb=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || echo 0)
    [[ -n $kb && $kb != 0 ]] && echo "$((SECONDS - start)) $((kb / 1024))" >> "$work/rss.txt"
    sleep 5
  done
}
summary() {
  awk 'NR == 1 {first = $2} $1 >= 60 && !seen {after = $2; seen = 1}
       {if ($2 > top) top = $2; last = $2; t = $1}
       END {printf "soak: %d samples over %d s; RSS first %d MiB, after 1 min %d MiB, largest %d MiB, last %d MiB\n",
            NR, t, first, after, top, last}' "$work/rss.txt"
}
case $mode in
  render)
    frames=${2:-100000}
    size=${3:-128x128}
    start=$SECONDS
    "$ibfvs" render --mesh "$mesh" --orbit 0.5 --frames "$frames" --size "$size" -q \
      --out "$work/last.png" &
    pid=$!
    sample "$pid" &
    sampler=$!
    status=0
    wait "$pid" || status=$?
    wait "$sampler" || true
    cat "$work/rss.txt"
    summary
    echo "soak: render of $frames frames at $size exited $status after $((SECONDS - start)) s"
    [[ $status -eq 0 && -s $work/last.png ]]
    ;;
  view)
    seconds=${2:-600}
    # A loop of interaction every 20 frames, long enough for any frame rate.
    python3 - "$work" > "$work/session.txt" <<'PY'
import sys
work = sys.argv[1]
steps = ["drag 120 40 15", "zoom 2", "pan 10 -6", "set alpha 0.15", "mode freeze",
         "drag -80 20 10", "zoom -2", "set beta 0.3", "style bronze", "lock", "unlock",
         "element 0,-1,0,0,1,0,1.5,0.5,0", "style flow", "mode previous",
         "screenshot %s/shot.png" % work, "set step 2", "help", "help", "set color_map coolwarm",
         "set color_map viridis"]
frame = 10
for k in range(200000):
    print(frame, steps[k % len(steps)])
    frame += 20
PY
    xvfb-run -a -s '-screen 0 1024x768x24' "$ibfvs" view --mesh "$mesh" --size 400x400 \
      --script "$work/session.txt" > "$work/view.log" 2>&1 &
    runner=$!
    # The viewer is xvfb-run's child; find it.
    pid=""
    for _ in $(seq 100); do
      pid=$(pgrep -n -x ibfvs || true)
      [[ -n $pid ]] && break
      sleep 0.2
    done
    [[ -n $pid ]] || { cat "$work/view.log"; exit 1; }
    sample "$pid" &
    sampler=$!
    sleep "$seconds"
    alive=0
    kill -0 "$pid" 2>/dev/null && alive=1
    kill -TERM "$pid" 2>/dev/null || true
    wait "$runner" || true
    wait "$sampler" || true
    cat "$work/rss.txt"
    summary
    tail -3 "$work/view.log"
    echo "soak: viewer alive after $seconds s: $([[ $alive == 1 ]] && echo yes || echo no)"
    [[ $alive == 1 ]]
    ;;
  *)
    echo "soak.sh: render or view" >&2
    exit 2
    ;;
esac
