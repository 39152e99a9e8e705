#!/usr/bin/env bash
# The checks beyond the Release build and its tests (docs/reliability.md),
# each timed: the sources as clang-format leaves them; the pip package
# (scripts/python-package.sh: the wheel built, repaired and tested with
# PyVista in a fresh venv); every libFuzzer
# harness for 12 seconds from a fixed seed (the fuzz preset: clang,
# AddressSanitizer, UndefinedBehaviorSanitizer); and the asan-ubsan preset
# (the dev preset's build with warnings as errors, plus AddressSanitizer and
# UndefinedBehaviorSanitizer) with the whole suite in it, headless GL and the
# viewer under Xvfb included, less the long runs labelled `optimised` that
# the Release suite makes (tests/optimised_only.cmake). Both sanitized builds
# keep line tables only (-g1): stack traces still name file and line.
# --no-asan leaves out the last (a quick local run).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
stage() {
  local name=$1 start=$SECONDS
  shift
  echo "ci-checks: $name"
  "$@"
  echo "ci-checks: $name took $((SECONDS - start)) s"
}
format() {
  git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run --Werror
}
fuzz() {
  cmake --preset fuzz >/dev/null
  cmake --build build/fuzz -j2 --target ibfvs_fuzzers
  # Two at a time (2 cores; each single-threaded, under 2.5 GiB).
  ctest --test-dir build/fuzz -j2 -L ci --output-on-failure
}
sanitized() {
  cmake --preset asan-ubsan >/dev/null
  cmake --build build/asan -j2
  # intercept_tls_get_addr=0: GCC 12's LeakSanitizer, tracking dynamic TLS
  # through __tls_get_addr, at times reads a stale block of Mesa's after the
  # driver's threads end and its tracer dies ("Tracer caught signal 11",
  # about 1 run in 40 of a GL test); glibc's own bookkeeping suffices.
  ASAN_OPTIONS=intercept_tls_get_addr=0 \
    LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0" \
    ctest --test-dir build/asan -j2 -LE optimised --output-on-failure
}
stage "clang-format" format
stage "pip package: wheel, auditwheel, its tests in a fresh venv" ./scripts/python-package.sh
stage "fuzzers, 12 s each" fuzz
if [[ ${1:-} != --no-asan ]]; then
  stage "asan-ubsan build (warnings as errors) and tests" sanitized
fi
