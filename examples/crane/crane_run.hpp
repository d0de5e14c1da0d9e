// The crane program's runs (main.cpp parses the options and picks one): the work cycle step by
// step with the detail's stresses and damage per step (crane_run.cpp), the batch of operators
// and the game loop (crane_programs.cpp), and the export for the C interface (crane_export.cpp).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "crane_model.hpp"

namespace crane {

/// What main() parsed from the command line.
struct RunOptions {
  CraneSpec spec;
  CraneOptions crane;         ///< modes, hydraulic drive, the detail's own inertia
  std::vector<double> t, ds;  ///< the work cycle: time and stroke offset
  double step = 1e-3;
  /// Newton tolerance in m/s^2 (ImplicitSettings::acceleration_tolerance). 1e-3 gives the same
  /// stress history as the default in fewer Newton iterations (docs/accuracy-vs-time.md).
  double tolerance = 1e-5;
  /// Real-time Newton budget (--newton-budget): at most this many iterations per step, a step
  /// that reaches them kept at its last iterate (ImplicitSettings::accept_at_iteration_limit).
  /// 0: the integrator's limit, at which a step fails.
  int newton_budget = 0;
  bool quiet = false;
  std::string stroke_file, output = "crane-out";
};

/// The steps a run kept at the Newton budget and the largest final Newton correction among
/// them, over its tolerance (StepStatistics::last_correction: 1 is converged).
struct BudgetCount {
  long steps = 0;
  double largest_correction = 0;
  /// Whether the run goes on after a step that returned `st`: converged, or kept at the budget
  /// (counted).
  bool keep(StepStatus st, const StepStatistics& s) {
    if (st != StepStatus::budget_reached) return st == StepStatus::ok;
    ++steps;
    largest_correction = std::max(largest_correction, s.last_correction);
    return true;
  }
  void add(const BudgetCount& other) {
    steps += other.steps;
    largest_correction = std::max(largest_correction, other.largest_correction);
  }
};
/// With a budget (of `steps` steps run): a summary line and the "key: value" lines
/// newton_budget, steps_at_budget and budget_correction_max.
void print_budget(const RunOptions& o, const BudgetCount& b, long steps);

/// The crane for the run's options; its error, if any, goes to stderr.
std::optional<Crane> build_crane(const RunOptions& o);
/// Data for a run of the crane: its initial state with the run's integrator settings.
Data<double> start_data(const Crane& cr, const RunOptions& o);

/// The work cycle: writes <output>/crane_history.csv, detail_d_peak.vtu, crane_history.png and
/// prints a summary and "key: value" lines. Returns the exit code.
int run(const RunOptions& o);
/// Operators first .. first + count - 1, each driving their own version of the cycle, on
/// `threads` threads (0: all hardware threads).
int run_operators(const RunOptions& o, int first, int count, unsigned threads);
/// The cycle in a fixed-step game loop with frames at render_hz.
int run_game_loop(const RunOptions& o, double render_hz, bool realtime);
/// Writes what a C program needs to build the same stroke-driven crane through flexstress.h
/// into `dir` (crane.txt, boom.fsmodal, detail_d.txt, cycle.csv; docs/crane.md has the
/// format; c_api/demo.c reads them). Returns the exit code.
int export_c_model(const RunOptions& o, const std::string& dir);

}  // namespace crane
