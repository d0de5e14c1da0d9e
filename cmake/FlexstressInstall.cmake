# Install the headers, a relocatable CMake package (flexstressConfig.cmake + version file) and a
# pkg-config file for build systems other than CMake.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Header-only and architecture-independent: the package goes under share/.
set(FLEXSTRESS_INSTALL_CMAKEDIR "${CMAKE_INSTALL_DATADIR}/cmake/flexstress"
  CACHE STRING "Where the flexstress CMake package is installed")

install(TARGETS flexstress EXPORT flexstressTargets)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/flexstress"
  DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(EXPORT flexstressTargets
  NAMESPACE flexstress::
  DESTINATION "${FLEXSTRESS_INSTALL_CMAKEDIR}")
# The compiled libraries (FLEXSTRESS_BUILD_COMPILED) in an export set of their own, which the
# package config loads when present: a header-only install stays architecture-independent.
if(TARGET flexstress_compiled)
  install(TARGETS flexstress_compiled flexstress_c EXPORT flexstressCompiledTargets
    ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  install(EXPORT flexstressCompiledTargets
    NAMESPACE flexstress::
    DESTINATION "${FLEXSTRESS_INSTALL_CMAKEDIR}")
endif()

configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/flexstressConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/flexstressConfig.cmake"
  INSTALL_DESTINATION "${FLEXSTRESS_INSTALL_CMAKEDIR}")
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/flexstressConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion
  ARCH_INDEPENDENT)
install(FILES
  "${PROJECT_BINARY_DIR}/flexstressConfig.cmake"
  "${PROJECT_BINARY_DIR}/flexstressConfigVersion.cmake"
  DESTINATION "${FLEXSTRESS_INSTALL_CMAKEDIR}")

# pkg-config: relocatable (the prefix is found from the .pc file's own location, a pkgconf and
# pkg-config >= 0.29 feature), so `cmake --install --prefix P` works for any P.
configure_file("${PROJECT_SOURCE_DIR}/cmake/flexstress.pc.in" "${PROJECT_BINARY_DIR}/flexstress.pc"
  @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/flexstress.pc" DESTINATION "${CMAKE_INSTALL_DATADIR}/pkgconfig")
