# Runs the plugin's XML generator on a template holding @PLACEHOLDER@ and
# expects it to fail in one line that names the placeholder.
set(template ${DIR}/paraview_xml_${PLACEHOLDER}.xml.in)
file(WRITE ${template} "<A b=\"@${PLACEHOLDER}@\"/>\n")
include(${CMAKE_CURRENT_LIST_DIR}/expect_refusal.cmake)
expect_refusal("@${PLACEHOLDER}@" ${GEN} ${template} ${DIR}/paraview_xml_${PLACEHOLDER}.xml)
