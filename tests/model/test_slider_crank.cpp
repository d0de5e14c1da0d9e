// Simeon's flexible slider crank (B. Simeon, Math. Modelling of Systems 2 (1996) 1-18), as the
// IVP Test Set defines it (Mazzia, Magherini & Iavernaro, Test Set for IVP Solvers, release
// 2.3, problem "crank"): its reference solution at t = 0.1 s from the smooth start gives the
// rod's midpoint deflection relative to its pin line, q1 = 1.893192899613509e-4 m. The model
// (examples/slider_crank/slider_crank_model.hpp) is an FE beam line reduced by Craig-Bampton,
// not the Test Set's two sine modes, so it agrees to its discretization.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "../../examples/slider_crank/slider_crank_model.hpp"

namespace test_slider_crank {

using namespace flexstress;

TEST_CASE("flexible slider crank: the midpoint deflection at 0.1 s matches the IVP Test Set") {
  const slider_crank::Spec spec;
  const auto rod = slider_crank::make_rod(spec);
  REQUIRE(rod.ok());
  // The defaults, at h = 0.1 ms: at 1 ms the history is about 5 % of its peak off the converged
  // one at its worst.
  ImplicitSettings<double> settings;
  settings.step = 1e-4;
  auto built = slider_crank::make_model(spec, *rod, 4, &settings);
  REQUIRE(built.ok());
  Data<double> d(built->model);
  REQUIRE(slider_crank::set_start_velocities(spec, *rod, *built, d, /*smooth=*/true).ok());
  REQUIRE(initialize(built->model, d).ok());
  double peak = 0;
  for (int i = 0; i < 1000; ++i) {
    const StepStatus st = step(built->model, d);
    REQUIRE_MESSAGE(st == StepStatus::ok, to_string(st) << ": " << d.message.data());
    peak = std::max(peak, std::abs(slider_crank::midpoint_deflection(*built, d)));
  }
  const double q1 = slider_crank::midpoint_deflection(*built, d);
  const double reference = 1.893192899613509e-4;
  MESSAGE("q1(0.1) = " << q1 << " m (Test Set " << reference << "), largest |q1| " << peak
                       << " m, iterations/step "
                       << double(d.statistics.iterations) / double(d.statistics.steps)
                       << ", drift projections " << d.statistics.drift_projections);
  CHECK(d.t == doctest::Approx(0.1));
  CHECK(q1 == doctest::Approx(reference).epsilon(0.01));
}

}  // namespace test_slider_crank
