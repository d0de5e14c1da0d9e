// Status and Result: errors carry their code and message, values come through untouched.
#include <doctest/doctest.h>

#include <flexstress/core/status.hpp>

namespace test_status {

using namespace flexstress;

namespace {
Result<int> parse_positive(int x) {
  if (x <= 0)
    return make_error(ErrorCode::invalid_argument, "value ", x, " at index ", 3,
                      " is not positive (", 0.5, ")");
  return x;
}
}  // namespace

TEST_CASE("Result holds a value or an error that names what and where") {
  auto good = parse_positive(4);
  REQUIRE(good.ok());
  CHECK(*good == 4);
  auto bad = parse_positive(-2);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::invalid_argument);
  CHECK(bad.error().message == "value -2 at index 3 is not positive (0.5)");
  CHECK(bad.error().what() == "invalid argument: value -2 at index 3 is not positive (0.5)");
  CHECK_FALSE(bad.status().ok());
  CHECK(good.status().ok());
}

TEST_CASE("StepStatus has readable names") {
  CHECK(std::string(to_string(StepStatus::ok)) == "ok");
  CHECK(std::string(to_string(StepStatus::non_finite_state)) == "non-finite state");
}

}  // namespace test_status
