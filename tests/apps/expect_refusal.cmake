# expect_refusal(EXPECTED COMMAND...): runs COMMAND and expects it to fail
# with one line on stderr that holds EXPECTED (the plugin XML generator's
# tests).
function(expect_refusal expected)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "taken, where a refusal naming ${expected} was expected: ${err}")
  endif()
  string(FIND "${err}" "${expected}" at)
  string(REGEX MATCHALL "\n" lines "${err}")
  list(LENGTH lines count)
  if(at LESS 0 OR NOT count EQUAL 1)
    message(FATAL_ERROR "expected one line naming ${expected}, got: ${err}")
  endif()
endfunction()
