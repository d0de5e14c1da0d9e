// Builds a runtime model against the installed flexstress::compiled library and checks it: a
// rigid pendulum (1 m, 1 kg point-like bob) released at 0.05 rad swings with the period
// 2 pi sqrt(L / g) (1 + theta0^2 / 16) of the small-amplitude pendulum.
#include <cmath>
#include <cstdio>

#include <flexstress/model/all.hpp>

int main() {
  using namespace flexstress;
  const double g = 9.81, length = 1.0, theta0 = 0.05, pi = 3.14159265358979323846;
  ModelBuilder<double> b;
  const BodyId bob = b.add_rigid_body("bob", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-9);
  b.set_initial_pose(bob, Vector3d(length * std::sin(theta0), -length * std::cos(theta0), 0),
                     from_axis_angle<double>(Vector3d::UnitZ(), theta0));
  b.add_joint("pivot", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("rod end", bob, -1, Vector3d(0, length, 0)));
  b.set_gravity(Vector3d(0, -g, 0));
  auto model = b.finalize();
  if (!model) return std::printf("%s\n", model.error().what().c_str()), 1;
  Data<double> d(*model);
  if (!initialize(*model, d)) return std::printf("initialize failed\n"), 1;
  double first = -1, last = -1, x_prev = body_position(*model, d, bob).x(), t_prev = 0;
  int crossings = 0;
  while (d.t < 10.0) {
    if (step(*model, d) != StepStatus::ok) return std::printf("step failed\n"), 1;
    const double x = body_position(*model, d, bob).x();
    if (x_prev < 0 && x >= 0) {
      last = t_prev + (d.t - t_prev) * (-x_prev) / (x - x_prev);
      if (first < 0) first = last;
      ++crossings;
    }
    x_prev = x;
    t_prev = d.t;
  }
  const double period = (last - first) / (crossings - 1);
  const double expected = 2 * pi * std::sqrt(length / g) * (1 + theta0 * theta0 / 16);
  const bool ok = crossings >= 3 && std::abs(period - expected) < 1e-4 * expected;
  std::printf("flexstress model consumer: period %.6f s, analytic %.6f s: %s\n", period, expected,
              ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
