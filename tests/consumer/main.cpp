// Builds against the installed flexstress package and checks one computed result.
#include <cmath>
#include <cstdio>

#include <flexstress/flexstress.hpp>

int main() {
  using namespace flexstress;
  // A quarter turn about z maps x onto y.
  const EulerParameters<double> theta =
      from_axis_angle<double>(Vector3d::UnitZ(), 0.5 * 3.14159265358979323846);
  const Vector3d y = rotation_matrix(theta) * Vector3d::UnitX();
  const bool ok = std::abs(y.y() - 1.0) < 1e-12 && std::abs(y.x()) < 1e-12;
  std::printf("flexstress %s consumer: %s\n", version_string, ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
