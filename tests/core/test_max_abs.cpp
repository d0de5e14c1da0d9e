// max_abs: the largest absolute entry, and NaN whenever an entry is NaN (every tolerance test of
// the step relies on it to refuse a NaN state), wherever the NaN sits in a vector of any length.
#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <flexstress/core/types.hpp>

namespace test_max_abs {

using flexstress::max_abs;

TEST_CASE("max_abs: largest absolute entry, 0 when empty") {
  CHECK(max_abs(Eigen::VectorXd()) == 0.0);
  CHECK(max_abs(Eigen::Vector3d(1, -4, 2)) == 4.0);
  for (int n = 1; n <= 19; ++n)
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, -0.5, 0.5);
      v(k) = -7.0;
      CHECK(max_abs(v) == 7.0);
      CHECK(max_abs(v.cwiseProduct(Eigen::VectorXd::Constant(n, 2.0))) == 14.0);
    }
  Eigen::VectorXf f(5);
  f << 1, 2, -3, 0.5f, 0;
  CHECK(max_abs(f) == 3.0f);
}

TEST_CASE("max_abs: NaN anywhere gives NaN; an infinity gives infinity") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int n = 1; n <= 19; ++n)
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd v = Eigen::VectorXd::Constant(n, 1.0);
      v(k) = nan;
      CHECK(std::isnan(max_abs(v)));
      v(k) = -inf;
      CHECK(max_abs(v) == inf);
      if (n > 1) {  // +inf and -inf: their sum is NaN, the largest magnitude is not
        v((k + 1) % n) = inf;
        CHECK(max_abs(v) == inf);
      }
      v(n - 1 - k) = nan;  // both: NaN wins
      CHECK(std::isnan(max_abs(v)));
    }
  CHECK(std::isnan(max_abs(Eigen::Vector2f(1.0f, std::nanf("")))));
}

}  // namespace test_max_abs
