# Runs the plugin's XML generator on a template holding @PLACEHOLDER@ and
# expects it to fail in one line that names the placeholder.
set(template ${DIR}/paraview_xml_${PLACEHOLDER}.xml.in)
file(WRITE ${template} "<A b=\"@${PLACEHOLDER}@\"/>\n")
execute_process(COMMAND ${GEN} ${template} ${DIR}/paraview_xml_${PLACEHOLDER}.xml
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "@${PLACEHOLDER}@ was filled in: ${err}")
endif()
string(FIND "${err}" "@${PLACEHOLDER}@" at)
string(REGEX MATCHALL "\n" lines "${err}")
list(LENGTH lines count)
if(at LESS 0 OR NOT count EQUAL 1)
  message(FATAL_ERROR "expected one line naming @${PLACEHOLDER}@, got: ${err}")
endif()
