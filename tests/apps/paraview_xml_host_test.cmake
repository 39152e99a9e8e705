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
include(${CMAKE_CURRENT_LIST_DIR}/expect_refusal.cmake)
expect_refusal("${expected}" ${GEN} ${DIR}/paraview_xml_host_${MODE}.xml.in
               ${DIR}/paraview_xml_host_${MODE}.xml ${DIR}/paraview_xml_host_${MODE}.h)
