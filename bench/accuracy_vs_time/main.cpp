// The accuracy-versus-time study: for each approximation a user of flexstress can choose, the
// error it causes in the crane's hot-spot stress history and fatigue damage against the time it
// costs. A reference run (finest of everything), per knob runs that change that knob alone, and
// a few combined fast configurations. The float, effect, recovery and Newton knobs vary around
// 16 modes and h = 1 ms on the reference sub-model. Writes
// <output>/accuracy_vs_time.csv, accuracy_vs_time.md, histories.csv and, with gnuplot, the
// plots of bench/accuracy_vs_time/plot.gp. docs/accuracy-vs-time.md explains the results.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>

#include "study.hpp"

using namespace flexstress;
using study::Knobs;
using study::Recovery;
using study::RunResult;

namespace {

const char* kUsage =
    "usage: accuracy_vs_time [--output DIR] [--groups g1,g2,...]\n"
    "  --output DIR   where the CSV, the Markdown table and the plot go (default\n"
    "                 accuracy-out)\n"
    "  --groups LIST  only these knob groups (the reference always runs): modes, step,\n"
    "                 integrator, reduction, formulation, density, attachment, paper,\n"
    "                 base, scalar, effects, recovery, newton, fast\n";

const char* name_of(Recovery r) {
  switch (r) {
    case Recovery::fused: return "fused row";
    case Recovery::influence: return "influence matrix";
    case Recovery::stress_modes: return "modal stress modes";
    default: return "full re-solve";
  }
}

const char* name_of(study::EffectSet e) {
  switch (e) {
    case study::EffectSet::all: return "G+QV+MD";
    case study::EffectSet::no_quadratic_velocity: return "G+MD";
    case study::EffectSet::no_damping: return "G+QV";
    case study::EffectSet::with_stiffening: return "G+QV+MD+GS";
    default: return "G";
  }
}

// The reference: the finest of every knob.
Knobs reference() {
  Knobs k;
  k.name = "reference";
  k.group = "reference";
  k.modes = 24;
  k.step = 1e-4;
  k.acceleration_tolerance = 1e-6;
  k.submodel_inertia = true;
  k.spec.submodel_density = 2.0;
  return k;
}

// The paper's configuration as the crane example runs it (10 modes, h = 1 ms, mesh density 1).
Knobs paper() {
  Knobs k;
  k.name = "paper: 10 modes, h 1 ms, density 1";
  k.group = "paper";
  return k;
}

// The base of the float, effect, recovery and Newton knobs: the reference with 16 modes and
// h = 1 ms.
Knobs base16() {
  Knobs k = reference();
  k.name = "16 modes, h 1 ms";
  k.group = "base";
  k.modes = 16;
  k.step = 1e-3;
  k.acceleration_tolerance = 1e-5;
  return k;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<Knobs> configurations() {
  std::vector<Knobs> runs;
  auto add = [&](Knobs k, const std::string& group, const std::string& name) {
    k.group = group;
    k.name = name;
    runs.push_back(k);
  };
  // One knob at a time from the reference.
  const Knobs ref = reference();
  for (int n : {2, 4, 6, 8, 10, 12, 16}) {
    Knobs k = ref;
    k.modes = n;
    add(k, "modes", std::to_string(n) + " modes");
  }
  for (double h : {2e-4, 5e-4, 1e-3, 2e-3, 5e-3}) {
    Knobs k = ref;
    k.step = h;
    add(k, "step", "h " + number(h * 1e3) + " ms");
  }
  // RK4 at a step inside its stability limit (h omega_max < 2.78; omega_max is 2.8e4 rad/s with
  // 8 modes and 6.9e4 with 16): its cost grows with the highest mode it carries.
  for (const auto& [n, h] : {std::pair{6, 1e-4}, std::pair{8, 8e-5}, std::pair{16, 3e-5}}) {
    Knobs k = ref;
    k.modes = n;
    k.step = h;
    k.integrator = study::Integrator::explicit_rk4;
    add(k, "integrator", "RK4, " + std::to_string(n) + " modes, h " + number(h * 1e3) + " ms");
  }
  // The boom reduced by Craig-Chang (free-free modes and inertia-relief attachment modes)
  // instead of Craig-Bampton, at the reference's 24 modes and at the paper's 10.
  for (int n : {24, 10}) {
    Knobs k = ref;
    k.modes = n;
    k.spec.boom_reduction = reduction::ReductionMethod::craig_chang;
    add(k, "reduction", "Craig-Chang boom, " + std::to_string(n) + " modes");
  }
  {
    Knobs k = ref;
    k.spec.formulation = fe::Hex8Formulation::full_integration;
    add(k, "formulation", "full-integration hex8");
  }
  for (double d : {0.5, 1.0, 1.5}) {
    Knobs k = ref;
    k.spec.submodel_density = d;
    add(k, "density", "mesh density " + number(d));
  }
  for (auto kind :
       {stress::BoundaryInterpolation::linear, stress::BoundaryInterpolation::hermite}) {
    Knobs k = ref;
    k.spec.attach_between_nodes = true;
    k.spec.interpolation = kind;
    add(k, "attachment",
        std::string("between nodes, ") +
            (kind == stress::BoundaryInterpolation::linear ? "linear" : "Hermite"));
  }
  {
    Knobs k = ref;
    k.submodel_inertia = false;
    add(k, "effects", "no sub-model inertia");
  }
  runs.push_back(paper());
  // One knob at a time from the 16-mode, 1 ms base.
  const Knobs base = base16();
  runs.push_back(base);
  {
    Knobs k = base;
    k.single_precision = true;
    k.acceleration_tolerance = 1e-2;  // float's default: 1e-5 is below its resolution
    add(k, "scalar", "16 modes, h 1 ms, float");
  }
  for (auto e : {study::EffectSet::no_quadratic_velocity, study::EffectSet::no_damping,
                 study::EffectSet::gravity_only, study::EffectSet::with_stiffening}) {
    Knobs k = base;
    k.effects = e;
    add(k, "effects", std::string("16 modes, h 1 ms, ") + name_of(e));
  }
  {
    Knobs k = base;
    k.submodel_inertia = false;
    add(k, "effects", "16 modes, h 1 ms, no sub-model inertia");
  }
  for (Recovery r : {Recovery::influence, Recovery::stress_modes, Recovery::resolve}) {
    Knobs k = base;
    k.recovery = r;
    add(k, "recovery", std::string("16 modes, h 1 ms, ") + name_of(r));
  }
  for (int it : {1, 2, 3}) {
    Knobs k = base;
    k.max_iterations = it;
    k.accept_at_iteration_limit = true;
    add(k, "newton", "16 modes, h 1 ms, at most " + std::to_string(it) + " Newton iterations");
  }
  for (double tol : {1e-4, 1e-3, 1e-2, 1e-1}) {
    Knobs k = base;
    k.acceleration_tolerance = tol;
    add(k, "newton", "16 modes, h 1 ms, tolerance " + number(tol));
  }
  // Combined fast configurations, on the reference sub-model (its mesh costs nothing per step).
  {
    Knobs k = base;
    k.acceleration_tolerance = 1e-3;
    k.step = 2e-3;
    add(k, "fast", "16 modes, h 2 ms, tol 1e-3");
    k.effects = study::EffectSet::no_quadratic_velocity;
    add(k, "fast", "16 modes, h 2 ms, tol 1e-3, G+MD");
    k.step = 1e-3;
    add(k, "fast", "16 modes, h 1 ms, tol 1e-3, G+MD");
    k.modes = 8;
    add(k, "fast", "8 modes, h 1 ms, tol 1e-3, G+MD");
    k.step = 2e-3;
    add(k, "fast", "8 modes, h 2 ms, tol 1e-3, G+MD");
    k.effects = study::EffectSet::all;
    k.single_precision = true;
    k.acceleration_tolerance = 1e-2;
    add(k, "fast", "float, 8 modes, h 2 ms");
    k.modes = 16;
    add(k, "fast", "float, 16 modes, h 2 ms");
  }
  // Toward 5 us per millisecond simulated: longer steps and a Newton budget on 16 modes.
  {
    Knobs k = base;
    k.acceleration_tolerance = 1e-3;
    k.step = 2e-3;
    k.max_iterations = 2;
    k.accept_at_iteration_limit = true;
    add(k, "fast", "16 modes, h 2 ms, tol 1e-3, 2 Newton iterations");
    k.step = 2.5e-3;
    add(k, "fast", "16 modes, h 2.5 ms, tol 1e-3, 2 Newton iterations");
    k.max_iterations = 30;
    k.accept_at_iteration_limit = false;
    add(k, "fast", "16 modes, h 2.5 ms, tol 1e-3");
    k.step = 2e-3;
    k.acceleration_tolerance = 1e-2;
    add(k, "fast", "16 modes, h 2 ms, tol 1e-2");
  }
  return runs;
}

// Reference value at time tq by linear interpolation (the reference is finer than every run).
double interpolate(const RunResult& ref, double tq) {
  const auto& t = ref.time;
  auto it = std::lower_bound(t.begin(), t.end(), tq);
  if (it == t.begin()) return ref.hot_spot.front();
  if (it == t.end()) return ref.hot_spot.back();
  const auto i = static_cast<std::size_t>(it - t.begin());
  const double w = (tq - t[i - 1]) / (t[i] - t[i - 1]);
  return (1 - w) * ref.hot_spot[i - 1] + w * ref.hot_spot[i];
}

struct Errors {
  double max_rel = 0, rms_rel = 0, damage = 0, damage_rel = 0;
};

// Damage per work cycle, IIW FAT 100 with Haibach beyond the knee, unclassed rainflow (the
// crane example's curve; classes would add their own error).
double damage_of(const std::vector<double>& history) {
  static const auto model = *fatigue::DamageModel<double>::create(
      *fatigue::iiw_normal_curve(100.0, fatigue::IiwBeyondKnee::haibach));
  auto d = fatigue::damage_per_work_cycle(history, model);
  return d ? *d : std::nan("");
}

Errors compare(const RunResult& run, const RunResult& ref, double ref_range, double ref_damage) {
  Errors e;
  double sum = 0;
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    const double d = std::abs(run.hot_spot[i] - interpolate(ref, run.time[i]));
    e.max_rel = std::max(e.max_rel, d);
    sum += d * d;
  }
  e.max_rel /= ref_range;
  e.rms_rel = std::sqrt(sum / double(run.time.size())) / ref_range;
  e.damage = damage_of(run.hot_spot);
  e.damage_rel = (e.damage - ref_damage) / ref_damage;
  return e;
}

// The process's resident memory (MB) from /proc/self/status: "VmRSS" now, "VmHWM" its peak.
// Linux resets the peak to the current size when "5" is written to /proc/self/clear_refs, so the
// peak read after a run is that run's (with what the process already held). NaN elsewhere.
double resident_mb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key, 0) == 0)
      return std::strtod(line.c_str() + std::strlen(key), nullptr) / 1024;
  return std::nan("");
}
void reset_peak_resident() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
}

struct Row {
  Knobs knobs;
  RunResult result;
  Errors errors;
  bool pareto = false;
  double rss_start_mb = std::nan(""), rss_peak_mb = std::nan("");
  double total_us() const { return result.step_us_median + result.recovery_us_median; }
  /// CPU time per simulated second (ms/s; 1000 is real time): what a step size really costs,
  /// since a larger step is dearer per step but needs fewer of them.
  double cost_ms_per_s() const { return total_us() / (knobs.step * 1e3); }
};

void mark_pareto(std::vector<Row>& rows) {
  for (Row& a : rows) {
    if (!a.result.error.empty() || a.knobs.group == "reference") continue;
    a.pareto = true;
    for (const Row& b : rows) {
      if (&a == &b || !b.result.error.empty() || b.knobs.group == "reference") continue;
      const bool no_worse =
          b.cost_ms_per_s() <= a.cost_ms_per_s() && b.errors.max_rel <= a.errors.max_rel;
      const bool better =
          b.cost_ms_per_s() < a.cost_ms_per_s() || b.errors.max_rel < a.errors.max_rel;
      if (no_worse && better) {
        a.pareto = false;
        break;
      }
    }
  }
}

std::string csv_name(std::string s) {
  std::replace(s.begin(), s.end(), ',', ';');
  return s;
}

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "name,group,modes,scalar,effects,step_ms,integrator,max_iterations,tolerance,recovery,"
       "density,formulation,attachment,submodel_inertia,step_us_median,step_us_p99,step_us_max,"
       "recovery_us_median,recovery_us_max,total_us,step_bytes,max_error_pct,rms_error_pct,"
       "damage,damage_error_pct,iterations_per_step,over_budget,violations,precompute_ms,pareto,"
       "cpu_ms_per_simulated_s,rss_start_mb,rss_peak_mb,error\n";
  f.precision(6);
  for (const Row& r : rows) {
    const Knobs& k = r.knobs;
    const RunResult& x = r.result;
    f << csv_name(k.name) << ',' << k.group << ',' << k.modes << ','
      << (k.single_precision ? "float" : "double") << ',' << name_of(k.effects) << ','
      << k.step * 1e3 << ',' << (k.integrator == study::Integrator::implicit ? "implicit" : "RK4")
      << ',' << k.max_iterations << (k.accept_at_iteration_limit ? "(budget)" : "") << ','
      << k.acceleration_tolerance << ',' << name_of(k.recovery) << ',' << k.spec.submodel_density
      << ','
      << (k.spec.formulation == fe::Hex8Formulation::full_integration ? "full" : "incompatible")
      << ','
      << (k.spec.attach_between_nodes
              ? (k.spec.interpolation == stress::BoundaryInterpolation::linear ? "between-linear"
                                                                               : "between-hermite")
              : "nodes")
      << ',' << (k.submodel_inertia ? 1 : 0) << ',' << x.step_us_median << ',' << x.step_us_p99
      << ',' << x.step_us_max << ',' << x.recovery_us_median << ',' << x.recovery_us_max << ','
      << r.total_us() << ',' << x.step_bytes << ',' << 100 * r.errors.max_rel << ','
      << 100 * r.errors.rms_rel << ',' << r.errors.damage << ',' << 100 * r.errors.damage_rel << ','
      << x.iterations_per_step << ',' << x.over_budget << ',' << x.violations << ','
      << x.precompute_ms << ',' << (r.pareto ? 1 : 0) << ',' << r.cost_ms_per_s() << ','
      << r.rss_start_mb << ',' << r.rss_peak_mb << ',' << csv_name(x.error) << '\n';
  }
}

void write_markdown(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "| run | knob | step us (median / p99) | recovery us | CPU ms per simulated s | "
       "max error % | RMS error % | damage error % | step bytes | peak RSS MB | Pareto |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|\n";
  char buf[512];
  for (const Row& r : rows) {
    const RunResult& x = r.result;
    if (!x.error.empty()) {
      f << "| " << r.knobs.name << " | " << r.knobs.group << " | failed: " << x.error
        << " | | | | | | | | |\n";
      continue;
    }
    std::snprintf(
        buf, sizeof buf,
        "| %s | %s | %.2f / %.2f | %.3f | %.1f | %.3g | %.3g | %+.3g | %s | %.0f | %s |\n",
        r.knobs.name.c_str(), r.knobs.group.c_str(), x.step_us_median, x.step_us_p99,
        x.recovery_us_median, r.cost_ms_per_s(), 100 * r.errors.max_rel, 100 * r.errors.rms_rel,
        100 * r.errors.damage_rel,
        x.step_bytes < 0 ? "-" : std::to_string(long(x.step_bytes)).c_str(), r.rss_peak_mb,
        r.pareto ? "yes" : "");
    f << buf;
  }
}

// Hot-spot histories on a 10 ms grid: the reference and the named runs, for the picture.
void write_histories(const std::string& path, const std::vector<Row>& rows,
                     const std::vector<std::string>& names) {
  std::vector<const Row*> picked;
  for (const std::string& n : names)
    for (const Row& r : rows)
      if (r.knobs.name == n && r.result.error.empty()) picked.push_back(&r);
  std::ofstream f(path);
  f << "time_s";
  for (const Row* r : picked) f << ',' << csv_name(r->knobs.name);
  f << '\n';
  const RunResult& ref = picked.front()->result;
  for (double t = 0; t <= ref.time.back() + 1e-9; t += 0.01) {
    f << t;
    for (const Row* r : picked) f << ',' << interpolate(r->result, t);
    f << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string output = "accuracy-out", groups;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help" || key == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if ((key == "--output" || key == "--groups") && i + 1 < argc) {
      (key == "--output" ? output : groups) = argv[++i];
      continue;
    }
    std::fprintf(stderr, "error: unknown option or missing value '%s'\n%s", key.c_str(), kUsage);
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(output, ec);
  if (ec) {
    std::fprintf(stderr, "error: cannot create '%s': %s\n", output.c_str(), ec.message().c_str());
    return 1;
  }
  std::vector<Row> rows;
  rows.push_back({reference(), {}, {}, false});
  for (const Knobs& k : configurations())
    if (groups.empty() || ("," + groups + ",").find("," + k.group + ",") != std::string::npos)
      rows.push_back({k, {}, {}, false});

  for (Row& r : rows) {
    std::fprintf(stderr, "  %-48s", r.knobs.name.c_str());
    reset_peak_resident();
    r.rss_start_mb = resident_mb("VmRSS:");
    r.result = study::run(r.knobs);
    r.rss_peak_mb = resident_mb("VmHWM:");
    if (r.result.error.empty())
      std::fprintf(stderr, " %8.2f us/step\n", r.result.step_us_median);
    else
      std::fprintf(stderr, " failed: %s\n", r.result.error.c_str());
    if (&r == &rows.front() && !r.result.error.empty()) return 1;
  }
  const RunResult& ref = rows.front().result;
  const auto [lo, hi] = std::minmax_element(ref.hot_spot.begin(), ref.hot_spot.end());
  const double ref_range = *hi - *lo, ref_damage = damage_of(ref.hot_spot);
  for (Row& r : rows)
    if (r.result.error.empty()) r.errors = compare(r.result, ref, ref_range, ref_damage);
  mark_pareto(rows);

  write_csv(output + "/accuracy_vs_time.csv", rows);
  write_markdown(output + "/accuracy_vs_time.md", rows);
  write_histories(output + "/histories.csv", rows,
                  {"reference", "paper: 10 modes, h 1 ms, density 1", "4 modes",
                   "16 modes, h 2 ms, tol 1e-3, G+MD"});
  std::printf("reference: hot spot %.3f to %.3f MPa (range %.3f), damage per cycle %.4g\n", *lo,
              *hi, ref_range, ref_damage);
  for (const Row& r : rows)
    if (r.result.error.empty())
      std::printf("%-50s %8.2f us %8.1f ms/s  max err %8.3f %%  damage err %+8.3f %%%s\n",
                  r.knobs.name.c_str(), r.total_us(), r.cost_ms_per_s(), 100 * r.errors.max_rel,
                  100 * r.errors.damage_rel, r.pareto ? "  (Pareto)" : "");
  const std::string plot = std::string(FLEXSTRESS_STUDY_SOURCE_DIR) + "/plot.gp";
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0)
    (void)std::system(("gnuplot -e \"dir='" + output + "'\" '" + plot + "'").c_str());
  return 0;
}
