// Euler parameters: the reference is the rotation group itself (orthogonality, composition,
// round trips) and finite differences of the kinematic relations of the FFRF reference sheet
// (Nikravesh 1988; Shabana, Dynamics of Multibody Systems, ch. 2): w_body = 2 G_bar theta_dot.
#include <cmath>
#include <random>

#include <doctest/doctest.h>
#include <Eigen/LU>  // determinant

#include <flexstress/core/euler_parameters.hpp>

namespace test_euler_parameters {

using namespace flexstress;

namespace {

template <class S>
EulerParameters<S> random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vec4<double> v(n(rng), n(rng), n(rng), n(rng));
  return (v / v.norm()).cast<S>();
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST_CASE_TEMPLATE("A(theta) is a proper rotation for unit theta", S, float, double) {
  std::mt19937 rng(7);
  const S tol = S(20) * std::numeric_limits<S>::epsilon();
  for (int i = 0; i < 200; ++i) {
    const auto t = random_unit<S>(rng);
    const Mat3<S> a = rotation_matrix(t);
    CHECK((a.transpose() * a - Mat3<S>::Identity()).norm() < tol);
    CHECK(std::abs(a.determinant() - S(1)) < tol);
    // A = G G_bar^T for unit theta, and G theta = G_bar theta = 0.
    CHECK((g_matrix(t) * g_bar_matrix(t).transpose() - a).norm() < tol);
    CHECK((g_matrix(t) * t).norm() < tol);
    CHECK((g_bar_matrix(t) * t).norm() < tol);
  }
}

TEST_CASE("rotation matrix of a known rotation") {
  // A quarter turn about z: x -> y, y -> -x (right-hand rule).
  const auto t = from_axis_angle<double>(Vector3d::UnitZ(), kPi / 2);
  const Matrix3d a = rotation_matrix(t);
  CHECK((a * Vector3d::UnitX() - Vector3d::UnitY()).norm() < 1e-15);
  CHECK((a * Vector3d::UnitY() + Vector3d::UnitX()).norm() < 1e-15);
}

TEST_CASE("composition: A(a (x) b) = A(a) A(b), conjugate inverts") {
  std::mt19937 rng(11);
  for (int i = 0; i < 100; ++i) {
    const auto a = random_unit<double>(rng);
    const auto b = random_unit<double>(rng);
    CHECK((rotation_matrix(compose(a, b)) - rotation_matrix(a) * rotation_matrix(b)).norm() <
          1e-14);
    CHECK((compose(a, conjugate(a)) - identity_euler_parameters<double>()).norm() < 1e-15);
  }
}

TEST_CASE("round trips: rotation matrix, axis-angle, exp/log") {
  std::mt19937 rng(3);
  for (int i = 0; i < 200; ++i) {
    auto t = random_unit<double>(rng);
    if (t(0) < 0) t = -t;  // the representative the conversions return
    CHECK((from_rotation_matrix<double>(rotation_matrix(t)) - t).norm() < 1e-14);
    CHECK((exp_rotation<double>(log_rotation(t)) - t).norm() < 1e-14);
    Vector3d axis;
    double angle = 0;
    to_axis_angle(t, axis, angle);
    CHECK(angle >= 0.0);
    CHECK(angle <= kPi + 1e-15);
    CHECK((from_axis_angle<double>(axis, angle) - t).norm() < 1e-14);
  }
}

TEST_CASE("behaviour near 180 degree rotations") {
  // Shepperd's method must stay accurate where e0 -> 0 (the trace formula loses all digits).
  std::mt19937 rng(5);
  for (double delta : {1e-3, 1e-6, 1e-9, 0.0}) {
    for (int i = 0; i < 50; ++i) {
      Vector3d axis = random_unit<double>(rng).tail<3>().normalized();
      const double angle = kPi - delta;
      const auto t = from_axis_angle<double>(axis, angle);
      const Matrix3d a = rotation_matrix(t);
      const auto back = from_rotation_matrix<double>(a);
      CHECK((rotation_matrix(back) - a).norm() < 1e-14);
      // The rotation vector has length pi - delta and the right axis (up to sign at exactly pi).
      const Vector3d phi = log_rotation(back);
      CHECK(std::abs(phi.norm() - angle) < 1e-12);
      CHECK(std::abs(std::abs(phi.normalized().dot(axis)) - 1.0) < 1e-12);
    }
  }
}

TEST_CASE("small angles: exp and log are smooth through zero") {
  for (double a : {1e-2, 1e-5, 1e-8, 1e-12, 0.0}) {
    const Vector3d phi = Vector3d(0.3, -0.5, 0.8).normalized() * a;
    const auto t = exp_rotation<double>(phi);
    CHECK(std::abs(t.norm() - 1.0) < 1e-15);
    CHECK((log_rotation(t) - phi).norm() <= 1e-15 * std::max(a, 1.0));
    // A = I + skew(phi) + O(phi^2)
    CHECK((rotation_matrix(t) - Matrix3d::Identity() - skew(phi)).norm() <= a * a + 1e-15);
  }
}

TEST_CASE("w = 2 G_bar theta_dot against finite differences of A") {
  // The body-frame angular velocity is defined by skew(w) = A^T A_dot. Take theta(t) along a
  // smooth curve, difference A numerically, compare with 2 G_bar theta_dot.
  std::mt19937 rng(17);
  for (int i = 0; i < 50; ++i) {
    const auto t0 = random_unit<double>(rng);
    const Vector3d w = Vector3d(1.3, -0.4, 2.1) * (0.5 + i * 0.05);
    const Vec4<double> tdot = euler_parameter_rates(t0, w);
    const double h = 1e-6;
    // theta(t) = normalize(t0 + t tdot) has derivative tdot at t = 0 (tdot is orthogonal to t0).
    const Matrix3d ap = rotation_matrix<double>(normalized<double>(t0 + h * tdot));
    const Matrix3d am = rotation_matrix<double>(normalized<double>(t0 - h * tdot));
    const Matrix3d adot = (ap - am) / (2 * h);
    const Vector3d w_fd = unskew(Matrix3d(rotation_matrix(t0).transpose() * adot));
    CHECK((w_fd - body_angular_velocity(t0, tdot)).norm() < 1e-8 * w.norm());
    CHECK((w_fd - w).norm() < 1e-8 * w.norm());
    // And the global angular velocity: skew(w_global) = A_dot A^T = skew(2 G theta_dot).
    const Vector3d wg_fd = unskew(Matrix3d(adot * rotation_matrix(t0).transpose()));
    CHECK((wg_fd - 2.0 * g_matrix(t0) * tdot).norm() < 1e-8 * w.norm());
  }
}

TEST_CASE("right Jacobian of SO(3): exp(phi + d) = exp(phi) exp(T(phi) d) to first order") {
  std::mt19937 rng(23);
  for (double scale : {1e-6, 0.1, 1.0, 3.0}) {
    const Vector3d phi = random_unit<double>(rng).tail<3>().normalized() * scale;
    const Vector3d d = random_unit<double>(rng).tail<3>() * 1e-6;
    const auto lhs = exp_rotation<double>(phi + d);
    const auto rhs = compose(exp_rotation<double>(phi),
                             exp_rotation<double>(Vector3d(right_jacobian_so3(phi) * d)));
    CHECK((rotation_matrix(lhs) - rotation_matrix(rhs)).norm() < 1e-11);
  }
}

TEST_CASE("skew and unskew") {
  const Vector3d a(1, 2, 3), b(-4, 0.5, 2);
  CHECK((skew(a) * b - a.cross(b)).norm() < 1e-15);
  CHECK((unskew(skew(a)) - a).norm() < 1e-15);
  CHECK((skew(a) + skew(a).transpose()).norm() == 0.0);
}

}  // namespace test_euler_parameters
