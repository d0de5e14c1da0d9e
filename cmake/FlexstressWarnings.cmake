# Warning and sanitizer flags for the project's own targets (never forced on users).
add_library(flexstress_dev_flags INTERFACE)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(flexstress_dev_flags INTERFACE -Wall -Wextra -Wpedantic)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12)
    # GCC 12 reports -Wmaybe-uninitialized inside Eigen's fixed-size expression evaluators
    # (comma initializers, Inverse, products) where every coefficient is written before use; a
    # known false positive of its new value-range analysis. Clang and GCC 11 do not warn.
    target_compile_options(flexstress_dev_flags INTERFACE -Wno-maybe-uninitialized)
  endif()
  # Eigen's run-time allocation guard in every project target (consistently, so no translation
  # unit sees a different Eigen): the no-allocation tests switch it off around a step, and with
  # assertions on (the sanitizer build) any Eigen heap allocation there aborts the test.
  target_compile_definitions(flexstress_dev_flags INTERFACE EIGEN_RUNTIME_NO_MALLOC)
  if(FLEXSTRESS_WARNINGS_AS_ERRORS)
    target_compile_options(flexstress_dev_flags INTERFACE -Werror)
  endif()
  if(FLEXSTRESS_SANITIZE)
    target_compile_options(flexstress_dev_flags INTERFACE
      -fsanitize=${FLEXSTRESS_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
    target_link_options(flexstress_dev_flags INTERFACE -fsanitize=${FLEXSTRESS_SANITIZE})
    if(FLEXSTRESS_NO_SANITIZE)
      target_compile_options(flexstress_dev_flags INTERFACE -fno-sanitize=${FLEXSTRESS_NO_SANITIZE})
    endif()
  endif()
endif()

# The precompute (FE kernel, reductions, sub-model influence matrices) compiled once, in one
# object library, and declared `extern template` in every other translation unit of the tests,
# examples and benchmarks (see include/flexstress/precompute_instances.hpp). Without this each
# translation unit that calls the precompute spends tens of seconds instantiating it again.
# In parts (include/flexstress/precompute_instances.hpp), compiled in parallel: no job over
# 1.5 GB with GCC, the default compiler (-O3: 0.72 to 1.31 GB each; the whole in one unit took
# 3.0 GB), at about three times the total compile time of one unit (every part parses the
# headers). Clang compiles the one unit in 1.6 GB and half of GCC's time, so it keeps it.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(_flexstress_precompute_parts_default ON)
else()
  set(_flexstress_precompute_parts_default OFF)
endif()
option(FLEXSTRESS_PRECOMPUTE_PARTS "Compile the precompute in parts of under 1.5 GB each"
  ${_flexstress_precompute_parts_default})
if(FLEXSTRESS_PRECOMPUTE_PARTS)
  set(_precompute_parts "")
  foreach(_part RANGE 1 12)
    list(APPEND _precompute_parts "${PROJECT_SOURCE_DIR}/tests/support/precompute_instances_${_part}.cpp")
  endforeach()
else()
  set(_precompute_parts "${PROJECT_SOURCE_DIR}/tests/support/precompute_instances.cpp")
endif()
add_library(flexstress_precompute_instances OBJECT ${_precompute_parts})
target_link_libraries(flexstress_precompute_instances PUBLIC flexstress::flexstress flexstress_dev_flags)

# With PCH, the extern declarations come from a precompiled header (flexstress.hpp, then
# precompute_instances.hpp), which must be the first thing a unit includes.
function(flexstress_use_precompute_instances target)
  cmake_parse_arguments(arg "PCH" "" "" ${ARGN})
  target_sources(${target} PRIVATE $<TARGET_OBJECTS:flexstress_precompute_instances>)
  target_compile_definitions(${target} PRIVATE FLEXSTRESS_EXTERN_PRECOMPUTE)
  if(arg_PCH)
    target_precompile_headers(${target} PRIVATE <flexstress/flexstress.hpp>
      <flexstress/precompute_instances.hpp> ${arg_UNPARSED_ARGUMENTS})
  else()
    target_compile_options(${target} PRIVATE -include flexstress/precompute_instances.hpp)
  endif()
endfunction()
