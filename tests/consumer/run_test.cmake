# The consumer test (ctest -R consumer): installs the project's build (BUILD) to PREFIX,
# configures and builds tests/consumer against it with find_package, and runs the host.
# cmake -DBUILD=... -DPREFIX=... -DCONSUMER_BUILD=... -DSOURCE=... -P run_test.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${ARGN}\n${output}")
  endif()
  message("${output}")
endfunction()
# docs/integration.md's example is indirect.cpp, word for word.
file(READ ${SOURCE}/indirect.cpp example)
file(READ ${SOURCE}/../../docs/integration.md guide)
string(FIND "${guide}" "${example}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "docs/integration.md does not show tests/consumer/indirect.cpp as it is")
endif()
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD})
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX})
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${CONSUMER_BUILD} -G Ninja -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${PREFIX})
run(${CMAKE_COMMAND} --build ${CONSUMER_BUILD})
run(${CONSUMER_BUILD}/vsgl_consumer)
