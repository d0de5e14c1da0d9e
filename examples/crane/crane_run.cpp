// The crane's work cycle (crane_run.hpp): precompute, static equilibrium, the cycle step by step
// with the detail's stresses from fused modal rows and the hot spot's damage meter, the energy
// balance, and the outputs (CSV, VTU, plot, summary and "key: value" lines).
#include "crane_run.hpp"

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <flexstress/fe/beam_section.hpp>

namespace crane {

namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The plot of docs/crane.md: stroke and boom angle, hot-spot and nominal stress, gauges (or,
// for a hydraulic run whose chamber pressures are in CSV columns pressure_column and the next,
// the pressures and the valve command).
void write_plot(const std::string& dir, int pressure_column = 0) {
  const std::string script = dir + "/crane_history.gp";
  std::ofstream gp(script);
  gp << "set terminal pngcairo size 1000,700 font ',10'\n"
        "set output '"
     << dir
     << "/crane_history.png'\n"
        "set datafile separator ','\n"
        "set multiplot layout 3,1 title 'Crane work cycle: stroke, boom angle and the stress at "
        "detail D'\n"
        "set grid\nset ylabel 'stroke (m)'\nset y2label 'boom angle (deg)'\nset y2tics\n"
        "set ytics nomirror\n"
        "f = '"
     << dir
     << "/crane_history.csv'\n"
        "plot f u 1:2 w l lw 2 t 'cylinder stroke', '' u 1:3 axes x1y2 w l lw 2 t 'boom angle'\n"
        "unset y2tics\nunset y2label\nset ylabel 'stress (MPa)'\n"
        "plot f u 1:4 w l lw 2 t 'hot spot (IIW type a, toe centre)', "
        "'' u 1:5 w l lw 1 t 'hot spot (paper, 4/10 mm)', "
        "'' u 1:9 w l lw 1 t 'hot spot, max along the toe line', "
        "'' u 1:(-$8) w l lw 1 t 'nominal (minus bottom flange)'\n"
        "set xlabel 'time (s)'\n";
  if (pressure_column > 0)
    gp << "set ylabel 'pressure (bar)'\nset y2label 'valve command'\nset y2tics\n"
          "plot f u 1:"
       << pressure_column << " w l lw 2 t 'cap side', '' u 1:" << pressure_column + 1
       << " w l lw 2 t 'rod side', '' u 1:" << pressure_column - 1
       << " axes x1y2 w l lw 1 t 'valve command'\n";
  else
    gp << "set ylabel 'strain (microstrain)'\n"
          "plot f u 1:6 w l lw 2 t 'gauge at 0.4t', '' u 1:7 w l lw 2 t 'gauge at 1.0t'\n";
  gp << "unset multiplot\n";
  gp.close();
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0)
    (void)std::system(("gnuplot '" + script + "'").c_str());
}

}  // namespace

std::optional<Crane> build_crane(const RunOptions& o) {
  auto made = make_crane(o.spec, o.crane, o.t, o.ds);
  if (!made) {
    std::fprintf(stderr, "error: %s\n", made.error().what().c_str());
    return std::nullopt;
  }
  for (const std::string& w : made->model.warnings())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  return std::move(*made);
}

Data<double> start_data(const Crane& cr, const RunOptions& o) {
  Data<double> d = cr.initial;
  d.settings.step = o.step;
  d.settings.acceleration_tolerance = o.tolerance;
  d.settings.refresh_workspace = false;  // nothing reads the workspace after a step
  if (o.newton_budget > 0) {
    d.settings.max_iterations = o.newton_budget;
    d.settings.accept_at_iteration_limit = true;
  }
  return d;
}

void print_budget(const RunOptions& o, const BudgetCount& b, long steps) {
  if (o.newton_budget <= 0) return;
  std::printf(
      "  Newton budget %d iterations: %ld of %ld steps kept at it, the largest final correction "
      "%.3g x the tolerance\n",
      o.newton_budget, b.steps, steps, b.largest_correction);
  std::printf("newton_budget: %d\n", o.newton_budget);
  std::printf("steps_at_budget: %ld\n", b.steps);
  std::printf("budget_correction_max: %.3g\n", b.largest_correction);
}

int run(const RunOptions& o) {
  using Clock = std::chrono::steady_clock;
  const bool hydraulic = o.crane.hydraulic;
  const int n = o.crane.modes;
  const auto t_setup = Clock::now();
  auto made = build_crane(o);
  if (!made) return 1;
  const Crane& cr = *made;
  const Model<double>& model = cr.model;
  const Detail& dt = cr.detail;
  Data<double> d = start_data(cr, o);
  if (Status st = initialize(model, d); !st) {
    std::fprintf(stderr, "error: %s\n", st.error().what().c_str());
    return 1;
  }
  // The energy balance of the run: E - E0 - W_driver + D_damping.
  EnergyBalance<double> audit;
  audit.start(model, d);
  const double precompute_ms =
      std::chrono::duration<double, std::milli>(Clock::now() - t_setup).count();
  const auto out = [&](Index row) { return output_value(d, cr.output(row)); };
  // What the detail's own weight and inertia add to the hot spot (--submodel-inertia).
  const auto& inertia = model.output_sets().front().inertia;
  double inertia_hot_max = 0;

  (void)evaluate_outputs(model, d, /*feed_meters=*/false);  // at rest: not a cycle's sample
  const double static_hot = out(dt.hot_spot) / 1e6, static_nominal = out(dt.nominal) / 1e6;
  // Beam theory for the boom at rest: moment at the detail from the payload and the boom's own
  // weight outboard of it, sigma = M c / I at the flange.
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, o.spec.wall);
  const double xd = 0.5 * (o.spec.submodel_x0 + o.spec.submodel_x1), g = 9.81;
  const double m_beam = 7850 * sec.area * g * std::pow(o.spec.boom_length - xd, 2) / 2 +
                        o.spec.payload_mass * g * (o.spec.payload_x - xd);
  const double beam_theory = m_beam * 0.075 / sec.iz / 1e6;

  std::ofstream csv(o.output + "/crane_history.csv");
  if (!csv) {
    std::fprintf(stderr, "error: cannot write %s/crane_history.csv\n", o.output.c_str());
    return 1;
  }
  csv << "time_s,stroke_m,boom_angle_deg,hot_spot_MPa,hot_spot_paper_MPa,gauge_04t_microstrain,"
         "gauge_10t_microstrain,bottom_flange_MPa,toe_line_max_MPa,newton_iterations";
  for (int k = 0; k < n; ++k) csv << ",p" << k;
  if (hydraulic) csv << ",valve_command,p_cap_bar,p_rod_bar";
  csv << '\n';
  csv.precision(9);
  const double t_end = o.t.back();
  const auto steps = static_cast<long>(std::ceil((t_end - o.t.front()) / o.step));
  std::vector<double> step_us, recovery_ns;
  step_us.reserve(static_cast<std::size_t>(steps));
  recovery_ns.reserve(static_cast<std::size_t>(steps));
  double hot_min = 1e300, hot_max = -1e300, toe_max = -1e300, t_peak = 0;
  double p_cap_max = -1e300, p_cap_min = 1e300, stroke_max = -1e300;  // hydraulic runs
  VectorXd p_peak = modal_coordinates(model, d, cr.boom_body);
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO);
  long failed_at = -1;
  BudgetCount budget;  // steps kept at --newton-budget
  int most_iterations = 0;
  double largest_velocity_violation = 0;
  for (long i = 0; i < steps; ++i) {
    const auto a = Clock::now();
    const StepStatus st = step(model, d);
    const auto b = Clock::now();
    if (!budget.keep(st, d.statistics)) {
      failed_at = i;
      std::fprintf(stderr, "error: step %ld at t = %g s: %s%s%s\n", i, d.t, to_string(st),
                   d.message[0] ? ": " : "", d.message.data());
      break;
    }
    most_iterations = std::max(most_iterations, d.statistics.last_iterations);
    (void)evaluate_outputs(model, d);
    const auto c = Clock::now();
    audit.record(model, d);
    // B of the last Newton iterate (refresh_workspace is off): drift would show here first.
    largest_velocity_violation = std::max(largest_velocity_violation, velocity_violation(model, d));
    step_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    recovery_ns.push_back(std::chrono::duration<double, std::nano>(c - b).count());
    if (inertia.size() > 0)
      inertia_hot_max =
          std::max(inertia_hot_max,
                   std::abs(inertia.row(dt.hot_spot)
                                .dot(body_inertia_coordinates(model, d, cr.boom_body.index))) /
                       1e6);
    const double hot = out(dt.hot_spot) / 1e6;
    double line_max = -1e300;
    for (Index k = 0; k < dt.toe_line_count; ++k)
      line_max = std::max(line_max, out(dt.toe_line_first + k) / 1e6);
    if (hot > hot_max) {
      hot_max = hot;
      t_peak = d.t;
      p_peak = modal_coordinates(model, d, cr.boom_body);
    }
    hot_min = std::min(hot_min, hot);
    toe_max = std::max(toe_max, line_max);
    const double s = stroke(cr, d);
    csv << d.t << ',' << s << ',' << boom_angle(cr, d) * 180 / M_PI << ',' << hot << ','
        << out(dt.paper_hot_spot) / 1e6 << ',' << out(dt.gauge_04t) * 1e6 << ','
        << out(dt.gauge_10t) * 1e6 << ',' << out(dt.nominal) / 1e6 << ',' << line_max << ','
        << d.statistics.last_iterations;
    const VectorXd p = modal_coordinates(model, d, cr.boom_body);
    for (int k = 0; k < n; ++k) csv << ',' << p(k);
    if (hydraulic) {
      const auto& ch = d.force_states[std::size_t(cr.hydraulic_cylinder.index)];
      csv << ',' << valve_command(model, d, cr.hydraulic_cylinder.index) << ',' << ch.p1 / 1e5
          << ',' << ch.p2 / 1e5;
      p_cap_max = std::max(p_cap_max, ch.p1 / 1e5);
      p_cap_min = std::min(p_cap_min, ch.p1 / 1e5);
      stroke_max = std::max(stroke_max, s);
    }
    csv << '\n';
    if (progress && i % 500 == 0) std::fprintf(stderr, "\r  t = %6.2f of %.2f s", d.t, t_end);
  }
  if (progress) std::fprintf(stderr, "\r%40s\r", "");
  csv.close();
  if (failed_at >= 0) {
    // A run that stopped has no figures of the cycle to report: its history so far is in the
    // CSV file.
    std::fprintf(stderr,
                 "error: the run stopped at step %ld of %ld; %s/crane_history.csv holds "
                 "the history up to there\n",
                 failed_at, steps, o.output.c_str());
    if (o.newton_budget > 0)
      std::fprintf(stderr,
                   "  %ld steps before it were kept at the Newton budget of %d, the largest "
                   "final correction %.3g x the tolerance\n",
                   budget.steps, o.newton_budget, budget.largest_correction);
    return 1;
  }
  // The sub-model at the peak, for ParaView (and docs/crane.md's picture).
  (void)write_detail_vtu(dt, p_peak, o.output + "/detail_d_peak.vtu");
  write_plot(o.output, hydraulic ? 12 + n : 0);  // p_cap_bar: column 12 + n

  const double damage = meter_damage(d, cr.hot_spot_meter);
  auto life = fatigue::predict_life(damage, t_end - o.t.front());
  std::printf(
      "crane: FFRF boom with %d modes, %zu-brick sub-model at detail D, %s cycle of %g s%s\n", n,
      dt.num_bricks, o.stroke_file.empty() ? "synthetic" : "user", t_end - o.t.front(),
      hydraulic ? ", hydraulic drive (valve commands from the cycle)" : "");
  if (hydraulic)
    std::printf("  hydraulics: cap side %.1f to %.1f bar, largest stroke %.4f m (planned %.4f m)\n",
                p_cap_min, p_cap_max, stroke_max, *std::max_element(o.ds.begin(), o.ds.end()));
  std::printf(
      "  at rest: bottom flange %.2f MPa (beam theory M c / I: %.2f), hot spot %.2f MPa "
      "(%.3f x nominal)\n",
      static_nominal, -beam_theory, static_hot, static_hot / beam_theory);
  std::printf("  hot spot %.2f to %.2f MPa (peak at t = %.3f s); toe line max %.2f MPa\n", hot_min,
              hot_max, t_peak, toe_max);
  const double steps_taken = static_cast<double>(std::max<std::size_t>(1, step_us.size()));
  std::printf(
      "  stress recovery %.0f ns per step for %d outputs; %.2f Newton iterations/step (at most "
      "%d), %.3f factorizations/step, %ld steps split\n",
      percentile(recovery_ns, 0.5), model.num_outputs(),
      static_cast<double>(d.statistics.iterations) / steps_taken, most_iterations,
      static_cast<double>(d.statistics.factorizations) / steps_taken, d.statistics.split_steps);
  std::printf("  largest local error estimate %.3g\n", d.statistics.largest_error_estimate);
  std::printf("  joints: largest velocity violation |B v + Phi_t| %.3g over the cycle\n",
              largest_velocity_violation);
  std::printf(
      "  energy: the cycle moves up to %.1f J (driver work at the end %.3g J, modal damping "
      "%.3g J); largest |E - E0 - W + D| %.3g J (%.2g of it)\n",
      audit.max_energy_change(), audit.driver_work(), audit.dissipated(), audit.max_abs_residual(),
      audit.max_abs_residual() / audit.max_energy_change());
  std::printf("  fatigue: IIW FAT 100 (Haibach), repeating-history closure per work cycle\n");
  std::printf("  outputs in %s/: crane_history.csv, detail_d_peak.vtu, crane_history.png\n",
              o.output.c_str());
  print_budget(o, budget, static_cast<long>(step_us.size()));
  std::printf("precompute_ms: %.1f\n", precompute_ms);
  std::printf("steps: %zu\n", step_us.size());
  std::printf("step_us_median: %.2f\n", percentile(step_us, 0.5));
  // The mean too: the crane's step times are bimodal (steps that factorize and steps that do
  // not), so its median jumps between the two when their mix moves by a few percent.
  std::printf("step_us_mean: %.2f\n",
              std::accumulate(step_us.begin(), step_us.end(), 0.0) / steps_taken);
  std::printf("step_us_p999: %.2f\n", percentile(step_us, 0.999));
  std::printf("step_us_max: %.2f\n", percentile(step_us, 1.0));
  std::printf("recovery_ns_median: %.0f\n", percentile(recovery_ns, 0.5));
  std::printf("static_nominal_MPa: %.3f\n", static_nominal);
  std::printf("beam_theory_nominal_MPa: %.3f\n", -beam_theory);
  std::printf("static_hotspot_MPa: %.3f\n", static_hot);
  std::printf("hotspot_max_MPa: %.3f\n", hot_max);
  std::printf("hotspot_min_MPa: %.3f\n", hot_min);
  std::printf("damage_per_cycle: %.6g\n", damage);
  std::printf("life_cycles: %.6g\n", life ? life->work_cycles : 0.0);
  std::printf("driver_work_J: %.6g\n", audit.driver_work());
  std::printf("damping_dissipated_J: %.6g\n", audit.dissipated());
  std::printf("energy_balance_J: %.6g\n", audit.max_abs_residual());
  std::printf("energy_balance_rel: %.6g\n", audit.max_abs_residual() / audit.max_energy_change());
  if (hydraulic) {
    std::printf("hydraulic_p_cap_max_bar: %.3f\n", p_cap_max);
    std::printf("hydraulic_p_cap_min_bar: %.3f\n", p_cap_min);
    std::printf("hydraulic_stroke_max_m: %.5f\n", stroke_max);
  }
  if (inertia.size() > 0) std::printf("submodel_inertia_hotspot_max_MPa: %.4f\n", inertia_hot_max);
  return 0;
}

}  // namespace crane
