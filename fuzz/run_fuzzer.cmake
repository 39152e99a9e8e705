# One fuzzer's CTest run: SECONDS of fuzzing from the committed SEEDS, new
# inputs kept in WORK (the build tree). Fails on any crash, sanitizer
# report, leak, timeout or out-of-memory; libFuzzer writes the input that
# did it (crash-*, leak-*, timeout-*, oom-*) into WORK/artifacts.
file(MAKE_DIRECTORY ${WORK}/corpus ${WORK}/artifacts)
# A fixed seed: the same inputs in the same order on every machine, so CI
# explores what was explored here before it landed (campaigns with random
# seeds are scripts/fuzz.sh's).
set(args -seed=1 -max_total_time=${SECONDS} -timeout=20 -rss_limit_mb=2560 -max_len=65536
         -print_final_stats=1 -artifact_prefix=${WORK}/artifacts/)
if(DICT)
  list(APPEND args ${DICT})
endif()
if(OPTIONS)
  list(APPEND args ${OPTIONS})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_LIST_DIR}/lsan.supp"
                        ${FUZZER} ${args} ${WORK}/corpus ${SEEDS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${rc}); the input is in ${WORK}/artifacts")
endif()
