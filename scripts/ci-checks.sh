#!/usr/bin/env bash
# The checks beyond the Release build and its tests (docs/reliability.md),
# each timed: the sources as clang-format leaves them, and 30 seconds of
# every libFuzzer harness without open findings (the fuzz preset, clang, a
# fixed seed). With --asan also the asan-ubsan preset (the dev preset's
# Debug build with warnings as errors, plus AddressSanitizer and
# UndefinedBehaviorSanitizer) and the whole suite in it, headless GL
# included: not yet in CI (docs/reliability.md says what is left).
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
sanitized() {
  cmake --preset asan-ubsan >/dev/null
  cmake --build build/asan -j2
  LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0" \
    ctest --test-dir build/asan -j2 --output-on-failure
}
fuzz() {
  cmake --preset fuzz >/dev/null
  cmake --build build/fuzz -j2 --target ibfvs_fuzzers
  # The harnesses without open findings in libraries (docs/reliability.md).
  # One at a time: each as it ran here (memory and speed as checked).
  ctest --test-dir build/fuzz -j1 -L ci --output-on-failure
}
stage "clang-format" format
if [[ ${1:-} == --asan ]]; then
  stage "asan-ubsan build (warnings as errors) and tests" sanitized
fi
stage "fuzzers, 30 s each" fuzz
