# Finding flexstress's dependencies, with errors that name the Debian package to install.

# Eigen is found without a version request (find_package(Eigen3 3.4) would reject Eigen 5,
# whose version file declares SameMajorVersion) and checked against 3.4 here.
macro(flexstress_find_eigen)
  if(NOT TARGET Eigen3::Eigen)
    find_package(Eigen3 CONFIG QUIET)
  endif()
  if(NOT TARGET Eigen3::Eigen)
    message(FATAL_ERROR
      "flexstress needs Eigen 3.4 or newer, and CMake found no Eigen3 package.\n"
      "On Debian or Ubuntu: apt-get install libeigen3-dev\n"
      "Elsewhere, point Eigen3_DIR at the folder with Eigen3Config.cmake.")
  endif()
  if(DEFINED Eigen3_VERSION AND Eigen3_VERSION VERSION_LESS 3.4)
    message(FATAL_ERROR
      "flexstress needs Eigen 3.4 or newer; found Eigen ${Eigen3_VERSION} in ${Eigen3_DIR}.\n"
      "On Debian 12 or newer: apt-get install libeigen3-dev")
  endif()
endmacro()

# find_package for test/bench dependencies, failing with the Debian package name.
function(flexstress_require_package name debian_package)
  find_package(${name} CONFIG QUIET)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR
      "${name} was not found; it is needed for ${ARGN}.\n"
      "On Debian or Ubuntu: apt-get install ${debian_package}\n"
      "(or configure with the option that turns this part off).")
  endif()
endfunction()

# Spectra (header-only, optional): the sparse shift-invert eigen solver. Debian's
# libspectra-dev ships no CMake package, so look for a header.
function(flexstress_find_spectra out_var)
  find_path(FLEXSTRESS_SPECTRA_INCLUDE_DIR Spectra/SymGEigsShiftSolver.h)
  if(FLEXSTRESS_SPECTRA_INCLUDE_DIR)
    set(${out_var} TRUE PARENT_SCOPE)
  else()
    set(${out_var} FALSE PARENT_SCOPE)
  endif()
endfunction()
