// Andrews' squeezing mechanism (tests/support/andrews_squeezer.hpp), whose every 1 ms step the
// local error control splits into pieces: the options of the pieces' Newton, each run checked
// against the IVP Test Set's beta(0.03 s). The same mechanism on the defaults is a case of the
// stress suite (test_stress_suite.cpp).
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "support/andrews_squeezer.hpp"

namespace test_andrews_squeezer {

using namespace flexstress;
namespace andrews = testing::andrews;

namespace {

/// The squeezer's 30 steps of 1 ms on `settings`, each step passing: beta(0.03 s), iterations
/// per piece (every step is split).
struct SqueezerRun {
  double beta = 0, per_piece = 0;
  StepStatistics statistics;
};
SqueezerRun run_squeezer(const andrews::Squeezer& s, const ImplicitSettings<double>& settings) {
  SqueezerRun r;
  Data<double> d(s.model);
  REQUIRE(set_settings(s.model, d, settings).ok());
  REQUIRE(initialize(s.model, d).ok());
  r.beta = andrews::beta;
  for (int i = 0; i < 30; ++i) {
    const StepStatus st = step(s.model, d);
    REQUIRE_MESSAGE(st == StepStatus::ok, to_string(st) << ": " << d.message.data());
    r.beta += std::remainder(andrews::heading(s.model, d, s.crank) - r.beta, 2 * 3.14159265358979);
  }
  r.statistics = d.statistics;
  r.per_piece = double(d.statistics.iterations) / double(d.statistics.substeps);
  MESSAGE("pieces " << d.statistics.substeps << ", iterations per piece " << r.per_piece
                    << ", beta(0.03 s) " << r.beta << " (" << 100 * (r.beta / andrews::beta_end - 1)
                    << " % from the Test Set)");
  CHECK(d.statistics.split_steps == 30);
  CHECK(std::abs(r.beta / andrews::beta_end - 1) < 1e-3);
  return r;
}
}  // namespace

// The pieces' Newton with and without its multiplier pass (linearized_multipliers) and a matrix
// of each iterate (refactorize_pieces): without both, a piece's multipliers move only between
// corrections, each correction first answers the multipliers' predictor error with motion, and
// Newton contracts linearly (5.08 iterations per piece); with them, quadratically. Either way
// beta(0.03 s) within 0.1 % of the Test Set's 15.8108 (andrews.f, SOLN).
TEST_CASE("Andrews' squeezing mechanism: the pieces' Newton with and without the multiplier pass") {
  const auto s = andrews::make_squeezer();
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  const auto per_piece = [&](LinearizedMultipliers where, bool refactorize) {
    ImplicitSettings<double> settings;
    settings.linearized_multipliers = where;
    settings.refactorize_pieces = refactorize;
    return run_squeezer(*s, settings).per_piece;
  };
  const double off = per_piece(LinearizedMultipliers::off, false);
  const double pieces = per_piece(LinearizedMultipliers::pieces, true);
  const double always = per_piece(LinearizedMultipliers::always, true);
  CHECK(off > 4.0);
  CHECK(pieces < 3.0);
  CHECK(always < 3.0);
  ImplicitSettings<double> bad;
  bad.linearized_multipliers = static_cast<LinearizedMultipliers>(7);
  Data<double> d(s->model);
  const Status refused = set_settings(s->model, d, bad);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().what().find("linearized_multipliers") != std::string::npos);
}

// The option piece_newton_tolerance_fraction (off by default): Newton's corrections in the
// pieces of a split step stop at a fraction of the local error tolerance. On the squeezer, whose
// every step is split, each piece then takes fewer than 3 iterations, and beta(0.03 s) stays
// within 0.1 % of the Test Set's 15.8108 (andrews.f, SOLN).
TEST_CASE("Andrews' squeezing mechanism with pieces converged to a fraction of the local error") {
  const auto s = andrews::make_squeezer();
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  ImplicitSettings<double> settings;
  settings.piece_newton_tolerance_fraction = 1.5;
  Data<double> d(s->model);
  CHECK_FALSE(set_settings(s->model, d, settings).ok());  // a fraction above 1 is refused
  settings.piece_newton_tolerance_fraction = 1e-2;
  const double per_piece = run_squeezer(*s, settings).per_piece;
  CHECK(per_piece < 3.0);
}

}  // namespace test_andrews_squeezer
