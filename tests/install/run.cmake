# ctest -R install: installs the build tree into a fresh prefix, builds the
# consumer against it (nothing from the source tree on its include path) and
# runs it. -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCXX_FLAGS=... (the
# build's own flags: static libraries built with sanitizers need them at link)
# -DCXX_COMPILER=... (the build's compiler: its static libraries are that
# compiler's objects, its sanitizers' runtimes that compiler's)
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/tests/install" -B "${WORK_DIR}/build"
                        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix"
                        "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the consumer failed: ${rc}")
endif()
# The Python package, where it was built: importable from the prefix alone.
if(PYTHON)
  file(GLOB _pkg "${WORK_DIR}/prefix/lib/python3*/dist-packages/ibfvs/__init__.py")
  if(NOT _pkg)
    message(FATAL_ERROR "cmake --install did not install the Python package ibfvs")
  endif()
  get_filename_component(_site "${_pkg}" DIRECTORY)
  get_filename_component(_site "${_site}" DIRECTORY)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${_site}" "${PYTHON}" -c
                          "import ibfvs; assert ibfvs.render('torus', size=(32, 32), frames=2).shape == (32, 32, 3)"
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "the installed Python package failed: ${rc}")
  endif()
endif()
