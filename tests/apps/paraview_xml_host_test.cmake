# Runs the plugin's XML generator on the real template and the
# representation's real header with one host key's part taken out of one of
# them (MODE header: its Set<Host> declaration; MODE template: its
# @KEY.property@), and expects it to fail in one line that names what is
# missing.
cmake_minimum_required(VERSION 3.20)  # quoted strings are not variables' names
file(READ ${TEMPLATE} template_text)
file(READ ${HEADER} header_text)
if(MODE STREQUAL "header")
  string(REPLACE "void SetAlpha(double value);" "" header_text "${header_text}")
  set(expected "void SetAlpha(double)")
else()
  string(REPLACE "@alpha.property@" "name=\"Alpha\"" template_text "${template_text}")
  set(expected "@alpha.property@")
endif()
file(WRITE ${DIR}/paraview_xml_host_${MODE}.xml.in "${template_text}")
file(WRITE ${DIR}/paraview_xml_host_${MODE}.h "${header_text}")
execute_process(COMMAND ${GEN} ${DIR}/paraview_xml_host_${MODE}.xml.in
                        ${DIR}/paraview_xml_host_${MODE}.xml ${DIR}/paraview_xml_host_${MODE}.h
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "a ${MODE} without ${expected} was taken")
endif()
string(FIND "${err}" "${expected}" at)
string(REGEX MATCHALL "\n" lines "${err}")
list(LENGTH lines count)
if(at LESS 0 OR NOT count EQUAL 1)
  message(FATAL_ERROR "expected one line naming ${expected}, got: ${err}")
endif()
