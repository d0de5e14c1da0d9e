/* flexstress version. CMake reads the three numbers below; keep the format. C and C++: the C
 * interface (flexstress.h) includes it, so that a program can compare the header it was
 * compiled against with the library it runs with (fs_version_number() == FLEXSTRESS_VERSION). */
#pragma once

#define FLEXSTRESS_VERSION_MAJOR 0
#define FLEXSTRESS_VERSION_MINOR 4
#define FLEXSTRESS_VERSION_PATCH 0

#define FLEXSTRESS_VERSION \
  (FLEXSTRESS_VERSION_MAJOR * 10000 + FLEXSTRESS_VERSION_MINOR * 100 + FLEXSTRESS_VERSION_PATCH)

/* "major.minor.patch", from the three numbers above (one place to change). */
#define FLEXSTRESS_VERSION_STRINGIZE_(x) #x
#define FLEXSTRESS_VERSION_STRINGIZE(x) FLEXSTRESS_VERSION_STRINGIZE_(x)
#define FLEXSTRESS_VERSION_STRING                                                              \
  FLEXSTRESS_VERSION_STRINGIZE(FLEXSTRESS_VERSION_MAJOR)                                       \
  "." FLEXSTRESS_VERSION_STRINGIZE(FLEXSTRESS_VERSION_MINOR) "." FLEXSTRESS_VERSION_STRINGIZE( \
      FLEXSTRESS_VERSION_PATCH)

#ifdef __cplusplus
namespace flexstress {
/// Version as "major.minor.patch".
inline constexpr const char* version_string = FLEXSTRESS_VERSION_STRING;
}  // namespace flexstress
#endif
