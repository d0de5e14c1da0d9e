// flexstress version. CMake reads the three numbers below; keep the format.
#pragma once

#define FLEXSTRESS_VERSION_MAJOR 0
#define FLEXSTRESS_VERSION_MINOR 1
#define FLEXSTRESS_VERSION_PATCH 0

#define FLEXSTRESS_VERSION \
  (FLEXSTRESS_VERSION_MAJOR * 10000 + FLEXSTRESS_VERSION_MINOR * 100 + FLEXSTRESS_VERSION_PATCH)

namespace flexstress {
/// Version as "major.minor.patch".
inline constexpr const char* version_string = "0.1.0";
}  // namespace flexstress
