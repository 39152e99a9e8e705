# Writes OUT, a C++ source holding IN (a bundled browser script) as
# ibfvs::NAME (kWebRuntime: the page's runtime; kWebWidget: the notebook
# widget's module).
#   cmake -DIN=runtime.js -DOUT=web_runtime.cpp -DNAME=kWebRuntime -P embed_runtime.cmake
file(READ "${IN}" js)
string(FIND "${js}" "</script" closing)
if(NOT closing EQUAL -1)
  message(FATAL_ERROR "${IN} contains </script, which would end the page's script element")
endif()
string(FIND "${js}" ")ibfvs_js\"" delimiter)
if(NOT delimiter EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw string's delimiter")
endif()
file(WRITE "${OUT}.tmp" "// Generated from ${IN} by cmake/embed_runtime.cmake: do not edit.\nnamespace ibfvs {\nextern const char* const ${NAME};\nconst char* const ${NAME} = R\"ibfvs_js(${js})ibfvs_js\";\n}  // namespace ibfvs\n")
file(RENAME "${OUT}.tmp" "${OUT}")
