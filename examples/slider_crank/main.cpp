// Simeon's flexible slider crank (slider_crank_model.hpp): the rod's midpoint deflection
// relative to its pin line, per step, to <output>/slider_crank.csv, and the cost of a step.
// With no option it runs the model on the integrator's default settings (ImplicitSettings, not
// touched) for 0.1 s, the Test Set's interval; the options below change one setting each, for
// comparing variants. The summary's last lines are `key: value`.
//
//   slider_crank [--output DIR] [--duration S] [--modes K] [--start rest|smooth]
//                [--section planar|square] [--joints revolute|nonredundant]
//                [--crank-axial-inertia RATIO] [--reference FILE]
//                [--step H] [--project-velocities] [--project-accelerations]
//                [--no-reuse-factorization] [--no-corotate] [--tolerance A]
//                [--error-tolerance E] [--penalty F] [--rho R] [--max-iterations N]
//                [--accept-at-limit] [--newton-budget N]
//                [--no-extrapolate] [--no-extrapolate-predictor]
//                [--no-extrapolate-multipliers] [--pieces-as-whole-steps]
//                [--multiplier-pass-always] [--drift-limit L]
//
// --newton-budget N: a real-time budget, --max-iterations N with --accept-at-limit: a step that
// reaches N iterations keeps its last iterate and the run goes on; the summary counts those
// steps and gives the largest final correction among them over the tolerance (1: converged).
//
// The rod's out-of-plane velocities, which the joints forbid, grow from round-off; the
// defaults project them when they drift (ImplicitSettings::velocity_drift_limit; --drift-limit
// sets it, 0 never projects). Over runs
// longer than about 0.26 s the redundant loop's extrapolated multipliers drift too
// (--no-extrapolate-multipliers holds them; docs/dynamics.md, "The flexible slider crank").
//
// --start smooth: the Test Set's smooth initial elastic velocity (init1), whose reference at
// t = 0.1 s is q1 = 1.893192899613509e-4 m; rest (default): the rod undeformed and at rest
// relative to its rigid motion (the Test Set's second start). Both set the rigid velocities
// before initialize() (slider_crank_model.hpp, set_start_velocities, says why).
// --reference FILE: a CSV whose first two columns are t and the deflection (simeon_reference's
// output, or this program's own from a finer run); the summary then gives the largest
// difference over the run, interpolated linearly in the reference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "slider_crank_model.hpp"

using namespace flexstress;

namespace {

struct Series {
  std::vector<double> t, y;
  double at(double time) const {  // linear interpolation, clamped
    if (t.empty()) return std::nan("");
    const auto it = std::lower_bound(t.begin(), t.end(), time);
    if (it == t.begin()) return y.front();
    if (it == t.end()) return y.back();
    const std::size_t i = static_cast<std::size_t>(it - t.begin());
    const double s = (time - t[i - 1]) / (t[i] - t[i - 1]);
    return y[i - 1] + s * (y[i] - y[i - 1]);
  }
};

bool read_reference(const std::string& path, Series& s) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double t = 0, y = 0;
    if (row >> t >> y) {
      s.t.push_back(t);
      s.y.push_back(y);
    }
  }
  return !s.t.empty();
}

int usage() {
  std::cerr
      << "usage: slider_crank [--output DIR] [--duration S] [--modes K] [--start rest|smooth]\n"
         "                    [--section planar|square] [--joints revolute|nonredundant]\n"
         "                    [--crank-axial-inertia RATIO] [--reference FILE] [--step H]\n"
         "                    [--project-velocities] [--project-accelerations]\n"
         "                    [--no-reuse-factorization] [--no-corotate] [--tolerance A]\n"
         "                    [--error-tolerance E] [--penalty F] [--rho R]\n"
         "                    [--max-iterations N]\n"
         "                    [--accept-at-limit] [--newton-budget N] [--no-extrapolate]\n"
         "                    [--no-extrapolate-predictor] [--no-extrapolate-multipliers]\n"
         "                    [--pieces-as-whole-steps] [--multiplier-pass-always]\n"
         "                    [--drift-limit L]\n"
         "  --newton-budget N: at most N Newton iterations per step; a step that reaches\n"
         "  them keeps its last iterate and the run goes on (--max-iterations N with\n"
         "  --accept-at-limit); the summary counts the steps kept at the budget\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "slider-crank-out", start = "rest", reference;
  double duration = 0.1;
  int modes = 4;
  slider_crank::Spec spec;
  ImplicitSettings<double> settings;  // the defaults; each option below changes one
  std::vector<std::string> changed;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--output" && has_value) {
      out = argv[++i];
    } else if (a == "--duration" && has_value) {
      duration = std::atof(argv[++i]);
    } else if (a == "--modes" && has_value) {
      modes = std::atoi(argv[++i]);
    } else if (a == "--start" && has_value) {
      start = argv[++i];
      if (start != "rest" && start != "smooth") return usage();
    } else if (a == "--section" && has_value) {
      const std::string v = argv[++i];
      if (v != "planar" && v != "square") return usage();
      spec.planar = v == "planar";
    } else if (a == "--joints" && has_value) {
      const std::string v = argv[++i];
      if (v != "revolute" && v != "nonredundant") return usage();
      spec.nonredundant_joints = v == "nonredundant";
    } else if (a == "--crank-axial-inertia" && has_value) {
      spec.crank_axial_inertia_ratio = std::atof(argv[++i]);
    } else if (a == "--reference" && has_value) {
      reference = argv[++i];
    } else if (a == "--step" && has_value) {
      settings.step = std::atof(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--project-velocities") {
      settings.project_velocities = true;
      changed.push_back(a);
    } else if (a == "--project-accelerations") {
      settings.project_velocities = settings.project_accelerations = true;
      changed.push_back(a);
    } else if (a == "--no-reuse-factorization") {
      settings.reuse_factorization = false;
      changed.push_back(a);
    } else if (a == "--pieces-as-whole-steps") {  // Newton in a split step's pieces
      settings.linearized_multipliers = LinearizedMultipliers::off;
      settings.refactorize_pieces = false;
      changed.push_back(a);
    } else if (a == "--multiplier-pass-always") {  // the Uzawa pass in whole steps too
      settings.linearized_multipliers = LinearizedMultipliers::always;
      changed.push_back(a);
    } else if (a == "--drift-limit" && has_value) {
      settings.velocity_drift_limit = std::atof(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--no-corotate") {
      settings.corotate_factorization = false;
      changed.push_back(a);
    } else if (a == "--tolerance" && has_value) {
      settings.acceleration_tolerance = std::atof(argv[++i]);
      settings.relative_acceleration_tolerance = 0;  // in place of the default
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--error-tolerance" && has_value) {
      settings.local_error_tolerance = std::atof(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--penalty" && has_value) {
      settings.penalty_factor = std::atof(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--rho" && has_value) {
      settings.spectral_radius = std::atof(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--max-iterations" && has_value) {
      settings.max_iterations = std::atoi(argv[++i]);
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--accept-at-limit") {
      settings.accept_at_iteration_limit = true;
      changed.push_back(a);
    } else if (a == "--newton-budget" && has_value) {
      settings.max_iterations = std::atoi(argv[++i]);
      settings.accept_at_iteration_limit = true;
      changed.push_back(a + " " + argv[i]);
    } else if (a == "--no-extrapolate-multipliers") {
      settings.extrapolate_multipliers = false;
      changed.push_back(a);
    } else if (a == "--no-extrapolate-predictor") {
      settings.extrapolate_predictor = false;
      changed.push_back(a);
    } else if (a == "--no-extrapolate") {
      settings.extrapolate_predictor = settings.extrapolate_multipliers = false;
      changed.push_back(a);
    } else {
      return usage();
    }
  }
  if (!(duration > 0) || !(settings.step > 0) || modes < 1 || settings.max_iterations < 1)
    return usage();

  auto rod = slider_crank::make_rod(spec);
  if (!rod) return std::cerr << "slider_crank: " << rod.error().what() << "\n", 1;
  if (modes > rod->data.num_modes)
    return std::cerr << "slider_crank: --modes " << modes << ": the rod's basis has "
                     << rod->data.num_modes << "\n",
           2;
  auto built = slider_crank::make_model(spec, *rod, modes, &settings);
  if (!built) return std::cerr << "slider_crank: " << built.error().what() << "\n", 1;
  slider_crank::SliderCrank& s = *built;
  for (const std::string& w : s.model.warnings())
    std::cerr << "slider_crank: warning: " << w << "\n";
  Data<double> d(s.model);
  if (Status st = slider_crank::set_start_velocities(spec, *rod, s, d, start == "smooth"); !st)
    return std::cerr << "slider_crank: " << st.error().what() << "\n", 1;
  if (Status st = initialize(s.model, d); !st)
    return std::cerr << "slider_crank: " << st.error().what() << "\n", 1;

  Series ref;
  if (!reference.empty() && !read_reference(reference, ref))
    return std::cerr << "slider_crank: cannot read reference '" << reference << "'\n", 1;

  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/slider_crank.csv");
  csv << "t,midpoint_deflection_m,iterations,factorizations,constraint_violation\n";
  csv.precision(10);
  csv << d.t << "," << slider_crank::midpoint_deflection(s, d) << ",0,0,"
      << constraint_violation(s.model, d) << "\n";
  const long steps = std::lround(duration / settings.step);
  std::vector<double> step_us;
  step_us.reserve(static_cast<std::size_t>(steps));
  std::string outcome = "completed";
  double peak = 0, t_peak = 0, max_error = 0, final_deflection = 0;
  long at_budget = 0;            // steps kept at the iteration limit (accept_at_iteration_limit)
  double budget_correction = 0;  // the largest final correction of one, over the tolerance
  for (long k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const StepStatus st = step(s.model, d);
    const auto t1 = std::chrono::steady_clock::now();
    if (st == StepStatus::budget_reached) {
      ++at_budget;
      budget_correction = std::max(budget_correction, d.statistics.last_correction);
    } else if (st != StepStatus::ok) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "failed at step %ld (t = %.6g s -> %.6g s): %s; last iterations %d, "
                    "constraint violation %.3g",
                    k + 1, d.t, d.t + settings.step, to_string(st), d.statistics.last_iterations,
                    constraint_violation(s.model, d));
      outcome = std::string(buf) + "\n  where: " + d.message.data();
      break;
    }
    step_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    const double y = slider_crank::midpoint_deflection(s, d);
    if (std::abs(y) > peak) peak = std::abs(y), t_peak = d.t;
    if (!ref.t.empty()) max_error = std::max(max_error, std::abs(y - ref.at(d.t)));
    final_deflection = y;
    csv << d.t << "," << y << "," << d.statistics.last_iterations << ","
        << d.statistics.last_factorizations << "," << constraint_violation(s.model, d) << "\n";
  }
  const auto& stats = d.statistics;
  std::sort(step_us.begin(), step_us.end());
  const double n = static_cast<double>(std::max(1L, stats.steps));
  std::cout << "flexible slider crank (Simeon 1996; IVP Test Set 'crank'), rod: "
            << rod->line.elements.size() << " beam elements, " << modes << " of "
            << rod->data.num_modes << " modes (" << (spec.planar ? "planar" : "square")
            << " section, " << (spec.nonredundant_joints ? "non-redundant" : "revolute")
            << " joints), start: " << start << "\n  rod frequencies (free, rad/s):";
  for (int i = 0; i < modes; ++i) std::printf(" %.0f", std::sqrt(rod->data.eigenvalues(i)));
  std::cout << "\n  settings: defaults";
  for (const auto& c : changed) std::cout << ", " << c;
  std::cout << "\n  outcome: " << outcome << "\n  written: " << out << "/slider_crank.csv\n";
  std::printf("t_end: %.6g\n", d.t);
  std::printf("steps: %ld\n", stats.steps);
  std::printf("step_us_median: %.1f\n", step_us.empty() ? 0.0 : step_us[step_us.size() / 2]);
  std::printf("iterations_per_step: %.3f\n", static_cast<double>(stats.iterations) / n);
  std::printf("factorizations_per_step: %.3f\n", static_cast<double>(stats.factorizations) / n);
  std::printf("drift_projections: %ld\n", stats.drift_projections);
  if (settings.accept_at_iteration_limit) {
    std::printf("newton_budget: %d\n", settings.max_iterations);
    std::printf("steps_at_budget: %ld\n", at_budget);
    std::printf("budget_correction_max: %.3g\n", budget_correction);
  }
  std::printf("max_abs_deflection_m: %.6e\n", peak);
  std::printf("t_max_abs_deflection: %.6g\n", t_peak);
  std::printf("final_deflection_m: %.6e\n", final_deflection);
  if (!ref.t.empty()) {
    std::printf("max_error_vs_reference_m: %.3e\n", max_error);
    std::printf("reference_final_m: %.6e\n", ref.at(d.t));
  }
  return outcome == "completed" ? 0 : 1;
}
