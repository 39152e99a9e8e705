# Writes OUT, a C++ source defining ibfvs::shaders::glsl::NAME for each
# GLSL file NAME.glsl in the folder DIR: the file's text as a raw
# string. Run at build time (src/render/glsl/, CMakeLists.txt), so that the
# GLSL lives in .glsl files and the library carries it without reading files.
#   cmake -DDIR=src/render/glsl -DOUT=<file.cpp> -P cmake/embed_glsl.cmake
file(GLOB SOURCES ${DIR}/*.glsl)
list(SORT SOURCES)
set(text "// Generated from src/render/glsl/*.glsl by cmake/embed_glsl.cmake: do not edit.\n")
string(APPEND text "#include \"glsl_sources.h\"\n\nnamespace ibfvs::shaders::glsl {\n\n")
foreach(file IN LISTS SOURCES)
  get_filename_component(name ${file} NAME_WE)
  file(READ ${file} body)
  string(FIND "${body}" ")glsl\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} holds the raw string's delimiter )glsl\"")
  endif()
  string(APPEND text "const char* const ${name} = R\"glsl(${body})glsl\";\n\n")
endforeach()
string(APPEND text "}  // namespace ibfvs::shaders::glsl\n")
file(WRITE "${OUT}.tmp" "${text}")
file(RENAME "${OUT}.tmp" "${OUT}")
