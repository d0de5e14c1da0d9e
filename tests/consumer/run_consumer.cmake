# Run by ctest: install flexstress into a scratch prefix, then configure, build and run the
# consumer project against that prefix (not against the source tree); then build the same
# program with the flags of the installed pkg-config file alone.
file(REMOVE_RECURSE "${SCRATCH_DIR}")
set(prefix "${SCRATCH_DIR}/prefix")

function(run_step)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

run_step("${CMAKE_COMMAND}" --install "${FLEXSTRESS_BINARY_DIR}" --prefix "${prefix}")
run_step("${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${SCRATCH_DIR}/build"
  "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}")
run_step("${CMAKE_COMMAND}" --build "${SCRATCH_DIR}/build")
run_step("${SCRATCH_DIR}/build/consumer")
# An install with the compiled libraries must give a working model program too.
file(GLOB_RECURSE compiled_targets "${prefix}/*/flexstressCompiledTargets.cmake")
if(compiled_targets)
  run_step("${SCRATCH_DIR}/build/model_consumer")
endif()

# pkg-config: the installed flexstress.pc (and Eigen's own eigen3.pc) give every flag needed.
find_program(PKG_CONFIG_EXECUTABLE NAMES pkg-config pkgconf REQUIRED)
set(ENV{PKG_CONFIG_PATH} "${prefix}/share/pkgconfig")
execute_process(COMMAND "${PKG_CONFIG_EXECUTABLE}" --cflags flexstress
  RESULT_VARIABLE rc OUTPUT_VARIABLE cflags ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags flexstress failed: ${err}")
endif()
message(STATUS "pkg-config --cflags flexstress: ${cflags}")
separate_arguments(cflags UNIX_COMMAND "${cflags}")
run_step("${CMAKE_CXX_COMPILER}" ${cflags} "${CONSUMER_SOURCE_DIR}/main.cpp"
  -o "${SCRATCH_DIR}/consumer-pkgconfig")
run_step("${SCRATCH_DIR}/consumer-pkgconfig")
