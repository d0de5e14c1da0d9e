# Every public header compiles on its own (it includes what it uses), with warnings as errors;
# and the library compiles without exceptions (one translation unit including every header:
# the same check at a fraction of the compile time of one unit per header). Opt-in integrations that need exceptions are
# listed in FLEXSTRESS_EXCEPTION_HEADERS and left out of the -fno-exceptions check.
set(FLEXSTRESS_EXCEPTION_HEADERS
  flexstress/fe/eigen_solver_spectra.hpp)  # Spectra reports errors by throwing

# Checked in the all-headers unit below instead of in units of their own (about 14 s each
# under clang): the precompute's extern declarations, included there first, so that they are
# compiled alone all the same; and the umbrella header, which only includes headers that each
# have their own unit.
set(_checked_in_all_headers_unit flexstress/precompute_instances.hpp flexstress/flexstress.hpp)

file(GLOB_RECURSE _headers RELATIVE "${PROJECT_SOURCE_DIR}/include"
  CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/include/flexstress/*.hpp")
set(_dir "${CMAKE_CURRENT_BINARY_DIR}/header_check")
set(_all_sources "")
set(_noexcept_includes "#include <flexstress/precompute_instances.hpp>  // first: alone\n")
foreach(h IN LISTS _headers)
  if(NOT h IN_LIST FLEXSTRESS_EXCEPTION_HEADERS)
    string(APPEND _noexcept_includes "#include <${h}>\n")
  endif()
  if(h IN_LIST _checked_in_all_headers_unit)
    continue()
  endif()
  string(REGEX REPLACE "[/.]" "_" _name "${h}")
  set(_src "${_dir}/${_name}.cpp")
  file(CONFIGURE OUTPUT "${_src}" CONTENT "#include <${h}>\n#include <${h}>  // include guard\n")
  list(APPEND _all_sources "${_src}")
endforeach()

# Compile-only checks: nothing here is linked or run, so the units skip the sanitizer
# instrumentation and optimization of the build they are part of (half their compile time), but
# keep the warnings and the project's Eigen configuration.
set(_check_options -O0 -g0 -Wall -Wextra -Wpedantic -Werror)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND _check_options -Wno-maybe-uninitialized)  # as in FlexstressWarnings.cmake
endif()

add_library(flexstress_header_check OBJECT ${_all_sources})
target_link_libraries(flexstress_header_check PRIVATE flexstress::flexstress)
target_compile_options(flexstress_header_check PRIVATE ${_check_options})
target_compile_definitions(flexstress_header_check PRIVATE EIGEN_RUNTIME_NO_MALLOC)
# Eigen/Core, parsed once for all units instead of in each (more than half of a unit's time).
# Every Eigen module includes it, so the check still catches a header that leaves out the
# module it uses (Dense, Sparse, Geometry, ...). A precompiled header counts as a system header,
# but the header under check is included by the unit itself, so its warnings still count.
target_precompile_headers(flexstress_header_check PRIVATE <Eigen/Core>)
if(FLEXSTRESS_HAVE_SPECTRA)
  target_include_directories(flexstress_header_check PRIVATE "${FLEXSTRESS_SPECTRA_INCLUDE_DIR}")
endif()

set(_noexcept_src "${_dir}/all_headers_noexcept.cpp")
file(CONFIGURE OUTPUT "${_noexcept_src}" CONTENT "${_noexcept_includes}")
add_library(flexstress_header_check_noexcept OBJECT "${_noexcept_src}")
target_link_libraries(flexstress_header_check_noexcept PRIVATE flexstress::flexstress)
target_compile_options(flexstress_header_check_noexcept PRIVATE -fno-exceptions ${_check_options})
target_compile_definitions(flexstress_header_check_noexcept PRIVATE EIGEN_RUNTIME_NO_MALLOC)
