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

# The precompute (FE kernel, reductions, sub-model influence matrices) compiled once, and
# declared `extern template` in every other translation unit of the tests, examples and
# benchmarks (see include/flexstress/precompute_instances.hpp): without this each unit that
# calls the precompute spends tens of seconds instantiating it again. flexstress::compiled holds
# it, as it does for users; a build without that library compiles the same sources here.
if(NOT FLEXSTRESS_BUILD_COMPILED)
  add_library(flexstress_precompute_instances OBJECT ${FLEXSTRESS_PRECOMPUTE_SOURCES})
  target_link_libraries(flexstress_precompute_instances PUBLIC flexstress::flexstress
    flexstress_dev_flags)
endif()

# The headers declare the precompute extern themselves (core/precompute.hpp). With PCH, the
# library comes precompiled (flexstress.hpp), which must then be the first thing a unit includes.
function(flexstress_use_precompute_instances target)
  cmake_parse_arguments(arg "PCH" "" "" ${ARGN})
  if(TARGET flexstress_compiled)
    target_link_libraries(${target} PRIVATE flexstress::compiled)
  else()
    target_sources(${target} PRIVATE $<TARGET_OBJECTS:flexstress_precompute_instances>)
    target_compile_definitions(${target} PRIVATE FLEXSTRESS_EXTERN_PRECOMPUTE)
  endif()
  if(arg_PCH)
    target_precompile_headers(${target} PRIVATE <flexstress/flexstress.hpp>
      ${arg_UNPARSED_ARGUMENTS})
  endif()
endfunction()
