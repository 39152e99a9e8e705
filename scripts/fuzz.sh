#!/usr/bin/env bash
# Runs the libFuzzer harnesses (build them first: cmake --preset fuzz &&
# cmake --build build/fuzz -j2) for SECONDS each, JOBS at a time, from their
# committed seeds, and prints what each did: executions, coverage, and the
# inputs that crashed, leaked, hung or ran out of memory (kept under
# build/fuzz/campaign/NAME/artifacts). Unlike the 12-second CTest runs, a run
# here goes on after a finding (libFuzzer's fork mode), so one campaign lists
# them all.
#   scripts/fuzz.sh [SECONDS=600] [JOBS=1] [NAME...]   (NAME: off, ply, vtk, ...)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-600}
jobs=${2:-1}
shift $(($# < 2 ? $# : 2))
bin=build/fuzz/fuzz
[[ -d $bin ]] || { echo "fuzz.sh: no $bin; build the fuzz preset first" >&2; exit 1; }
names=("$@")
if ((${#names[@]} == 0)); then
  for f in "$bin"/*_fuzzer; do names+=("$(basename "$f" _fuzzer)"); done
fi
export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp
run_one() {
  local name=$1 out=build/fuzz/campaign/$1
  rm -rf "$out"
  mkdir -p "$out/corpus" "$out/artifacts"
  local dict=fuzz/dictionaries/${name}_fuzzer.dict args=()
  [[ -f $dict ]] && args+=(-dict="$dict")
  [[ -f fuzz/options/${name}_fuzzer.txt ]] && mapfile -t -O "${#args[@]}" args < "fuzz/options/${name}_fuzzer.txt"
  "$bin/${name}_fuzzer" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 -max_len=65536 \
    -artifact_prefix="$out/artifacts/" "${args[@]}" "$out/corpus" "fuzz/corpus/${name}_fuzzer" \
    > "$out/log.txt" 2>&1 || true
  local stats execs
  stats=$(grep -E '^#[0-9]+: cov' "$out/log.txt" | tail -1)
  execs=$(echo "$stats" | sed -n 's/.*exec\/s: \([0-9]*\).*/\1/p')
  printf '%-9s %s  findings: %s\n' "$name" "${stats:-no statistics (see $out/log.txt)}" \
    "$(ls "$out/artifacts" | wc -l)"
}
export -f run_one
export bin seconds
printf '%s\n' "${names[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'
