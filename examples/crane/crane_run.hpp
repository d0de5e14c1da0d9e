// The crane's run for N boom modes: precompute, static equilibrium, the work cycle step by step
// with the hot-spot stress per step from fused modal rows, fatigue, the energy balance, and the
// outputs (CSV, VTU, plot, summary and "key: value" lines). main.cpp parses the options and
// picks N; each supported N is instantiated in its own unit (run_modes_N.cpp) so they compile
// in parallel.
#pragma once

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <flexstress/dynamics/energy_audit.hpp>
#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/fe/vtk_writer.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "crane_model.hpp"

namespace crane {

/// What main() parsed from the command line.
struct RunOptions {
  CraneSpec spec;
  std::vector<double> t, ds;  ///< the work cycle: time and stroke offset
  double step = 1e-3;
  bool quiet = false, with_inertia = false;
  std::string stroke_file, output = "crane-out";
  bool hydraulic = false;  ///< the valve-driven cylinder instead of the prescribed stroke
};

/// Boom mode counts the program is built for (--modes).
inline constexpr int kSupportedModes[] = {10, 16};

/// The run with N boom modes. StorageLimit as in Scene: the default (10) mode count uses
/// fixed-size storage, 16 modes dynamic storage (3-6 % slower per step, docs/performance.md,
/// and a quarter less compile time for this unit).
template <int N, int StorageLimit, class EffectList = CraneEffects>
int run(const RunOptions& o);

// One unit per mode count instantiates run<N>; the others only declare it.
extern template int run<10, fixed_storage_limit>(const RunOptions&);
extern template int run<16, 0>(const RunOptions&);
extern template int run<10, fixed_storage_limit, CraneHydraulicEffects>(const RunOptions&);

namespace detail {

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The plot of docs/crane.md: stroke and boom angle, hot-spot and nominal stress, gauges (or,
// for a hydraulic run whose chamber pressures are in CSV columns pressure_column and the next,
// the pressures and the valve command).
inline void write_plot(const std::string& dir, int pressure_column = 0) {
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

}  // namespace detail

template <int N, int StorageLimit, class EffectList>
int run(const RunOptions& o) {
  constexpr bool hydraulic = EffectList::template has<HydraulicDrive>;
  using Clock = std::chrono::steady_clock;
  using detail::percentile;
  const auto t_setup = Clock::now();
  auto made = make_crane<N, StorageLimit, double, EffectList>(o.spec, o.t, o.ds);
  if (!made) {
    std::fprintf(stderr, "error: %s\n", made.error().what().c_str());
    return 1;
  }
  auto& cr = *made;
  auto& scene = cr.scene;
  auto s = cr.initial;
  using Scene = CraneScene<N, StorageLimit, double, EffectList>;
  typename ImplicitIntegrator<Scene>::Settings settings;
  settings.step = o.step;
  ImplicitIntegrator<Scene> integ(scene, settings);
  if (Status st = integ.initialize(s); !st) {
    std::fprintf(stderr, "error: %s\n", st.error().what().c_str());
    return 1;
  }
  // The energy balance of the run (dynamics/energy_audit.hpp): E - E(0) - W_driver + D_damping.
  EnergyAudit<Scene> audit(scene);
  audit.start(s);
  // Fatigue: IIW hot-spot FAT 100, slope 3 to the knee at 1e7 and Haibach (5) beyond, as IIW
  // recommends for variable amplitude; streaming rainflow on 128 classes.
  auto curve = fatigue::iiw_normal_curve(100.0, fatigue::IiwBeyondKnee::haibach);
  if (!curve) {
    std::fprintf(stderr, "error: %s\n", curve.error().what().c_str());
    return 1;
  }
  auto model = fatigue::DamageModel<double>::create(*curve);
  auto grid = fatigue::ClassGrid<double>::create(-400.0, 400.0, 128);
  if (!model || !grid) {
    std::fprintf(stderr, "error: fatigue setup failed\n");
    return 1;
  }
  auto meter = fatigue::StreamingDamage<double, 128>::create(*grid, 0, *model);
  if (!meter) {
    std::fprintf(stderr, "error: %s\n", meter.error().what().c_str());
    return 1;
  }
  // Optional: the detail's own weight and inertia (stress/sub_model_inertia.hpp), from the
  // boom frame's acceleration, angular velocity and angular acceleration.
  std::optional<stress::SubModelInertia<>> inertia;
  if (o.with_inertia) {
    auto built = stress::SubModelInertia<>::build(*cr.sub, cr.outputs);
    if (!built) {
      std::fprintf(stderr, "error: %s\n", built.error().what().c_str());
      return 1;
    }
    inertia.emplace(std::move(*built));
  }
  VectorXd y_inertia = VectorXd::Zero(cr.fused->num_outputs());
  auto add_inertia = [&](const typename Scene::State& st, VectorXd& out) {
    y_inertia.setZero();
    inertia->add_to(boom_inertia_coordinates(scene, st), y_inertia);
    out += y_inertia;
  };
  double inertia_hot_max = 0;
  const double precompute_ms =
      std::chrono::duration<double, std::milli>(Clock::now() - t_setup).count();

  VectorXd y(cr.fused->num_outputs());
  cr.fused->evaluate(s.template coordinates<0>().p, y);
  if (inertia) add_inertia(s, y);
  const double static_hot = y(cr.hot_spot_row) / 1e6, static_nominal = y(cr.nominal_row) / 1e6;
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
  for (int k = 0; k < N; ++k) csv << ",p" << k;
  if constexpr (hydraulic) csv << ",valve_command,p_cap_bar,p_rod_bar";
  csv << '\n';
  csv.precision(9);
  const double t_end = o.t.back();
  const auto steps = static_cast<long>(std::ceil((t_end - o.t.front()) / o.step));
  std::vector<double> step_us, recovery_ns;
  step_us.reserve(static_cast<std::size_t>(steps));
  recovery_ns.reserve(static_cast<std::size_t>(steps));
  double hot_min = 1e300, hot_max = -1e300, toe_max = -1e300, t_peak = 0;
  double p_cap_max = -1e300, p_cap_min = 1e300, stroke_max = -1e300;  // hydraulic runs
  const double l0 = (o.spec.b - o.spec.c).norm();                     // cylinder length at t = 0
  Eigen::Matrix<double, N, 1> p_peak = s.template coordinates<0>().p;
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO);
  long failed = 0;
  for (long i = 0; i < steps; ++i) {
    const auto a = Clock::now();
    const StepStatus st = integ.step(s);
    const auto b = Clock::now();
    cr.fused->evaluate(s.template coordinates<0>().p, y);
    const auto c = Clock::now();
    if (st != StepStatus::ok) {
      ++failed;
      std::fprintf(stderr, "error: step %ld at t = %g s: %s\n", i, s.t, to_string(st));
      break;
    }
    audit.record(s);
    step_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    recovery_ns.push_back(std::chrono::duration<double, std::nano>(c - b).count());
    if (inertia) {
      add_inertia(s, y);
      inertia_hot_max = std::max(inertia_hot_max, std::abs(y_inertia(cr.hot_spot_row)) / 1e6);
    }
    const double hot = y(cr.hot_spot_row) / 1e6;
    double line_max = -1e300;
    for (Index k = 0; k < cr.toe_line_count; ++k)
      line_max = std::max(line_max, y(cr.toe_line_first + k) / 1e6);
    (void)meter->push(hot);
    if (hot > hot_max) {
      hot_max = hot;
      t_peak = s.t;
      p_peak = s.template coordinates<0>().p;
    }
    hot_min = std::min(hot_min, hot);
    toe_max = std::max(toe_max, line_max);
    // The stroke as the bodies have it (cylinder origin at C, rod origin at B).
    const double stroke =
        (s.template coordinates<2>().position - s.template coordinates<1>().position).norm() - l0;
    csv << s.t << ',' << stroke << ',' << boom_angle(s.template coordinates<0>().theta) * 180 / M_PI
        << ',' << hot << ',' << y(cr.paper_hot_spot_row) / 1e6 << ',' << y(cr.gauge_04t) * 1e6
        << ',' << y(cr.gauge_10t) * 1e6 << ',' << y(cr.nominal_row) / 1e6 << ',' << line_max << ','
        << integ.statistics().last_iterations;
    for (int k = 0; k < N; ++k) csv << ',' << s.template coordinates<0>().p(k);
    if constexpr (hydraulic) {
      const auto& ch = std::get<0>(s.force_states);
      csv << ',' << scene.template force<0>().params.command(s.t).value << ',' << ch.p1 / 1e5 << ','
          << ch.p2 / 1e5;
      p_cap_max = std::max(p_cap_max, ch.p1 / 1e5);
      p_cap_min = std::min(p_cap_min, ch.p1 / 1e5);
      stroke_max = std::max(stroke_max, stroke);
    }
    csv << '\n';
    if (progress && i % 500 == 0) std::fprintf(stderr, "\r  t = %6.2f of %.2f s", s.t, t_end);
  }
  if (progress) std::fprintf(stderr, "\r%40s\r", "");
  csv.close();
  // The sub-model at the peak, for ParaView (and docs/crane.md's picture).
  const VectorXd u_peak = cr.sub->solve(cr.boundary_modes.leftCols(N) * p_peak);
  auto fields = fe::standard_fields(cr.sub->mesh(), cr.sub->model().dofs, u_peak);
  if (fields) (void)fe::write_vtu(o.output + "/detail_d_peak.vtu", cr.sub->mesh(), *fields);
  detail::write_plot(o.output, hydraulic ? 12 + N : 0);  // p_cap_bar: column 12 + N

  const double damage = meter->damage(fatigue::CycleClosure::repeating);
  auto life = fatigue::predict_life(damage, t_end - o.t.front());
  std::printf(
      "crane: FFRF boom with %d modes, %zu-brick sub-model at detail D, %s cycle of %g s%s\n", N,
      cr.detail.mesh.hexes().size(), o.stroke_file.empty() ? "synthetic" : "user",
      t_end - o.t.front(), hydraulic ? ", hydraulic drive (valve commands from the cycle)" : "");
  if constexpr (hydraulic)
    std::printf("  hydraulics: cap side %.1f to %.1f bar, largest stroke %.4f m (planned %.4f m)\n",
                p_cap_min, p_cap_max, stroke_max, *std::max_element(o.ds.begin(), o.ds.end()));
  std::printf(
      "  at rest: bottom flange %.2f MPa (beam theory M c / I: %.2f), hot spot %.2f MPa "
      "(%.3f x nominal)\n",
      static_nominal, -beam_theory, static_hot, static_hot / beam_theory);
  std::printf("  hot spot %.2f to %.2f MPa (peak at t = %.3f s); toe line max %.2f MPa\n", hot_min,
              hot_max, t_peak, toe_max);
  std::printf("  stress recovery %.0f ns per step for %lld outputs; %.2f Newton iterations/step\n",
              percentile(recovery_ns, 0.5), static_cast<long long>(cr.fused->num_outputs()),
              static_cast<double>(integ.statistics().iterations) /
                  static_cast<double>(std::max<std::size_t>(1, step_us.size())));
  std::printf(
      "  energy: the cycle moves up to %.1f J (driver work at the end %.3g J, modal damping "
      "%.3g J); largest |E - E0 - W + D| %.3g J (%.2g of it)\n",
      audit.max_energy_change(), audit.driver_work(), audit.dissipated(), audit.max_abs_residual(),
      audit.max_abs_residual() / audit.max_energy_change());
  std::printf("  fatigue: IIW FAT 100 (Haibach), repeating-history closure per work cycle\n");
  std::printf("  outputs in %s/: crane_history.csv, detail_d_peak.vtu, crane_history.png\n",
              o.output.c_str());
  std::printf("precompute_ms: %.1f\n", precompute_ms);
  std::printf("steps: %zu\n", step_us.size());
  std::printf("step_us_median: %.2f\n", percentile(step_us, 0.5));
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
  if constexpr (hydraulic) {
    std::printf("hydraulic_p_cap_max_bar: %.3f\n", p_cap_max);
    std::printf("hydraulic_p_cap_min_bar: %.3f\n", p_cap_min);
    std::printf("hydraulic_stroke_max_m: %.5f\n", stroke_max);
  }
  if (inertia) std::printf("submodel_inertia_hotspot_max_MPa: %.4f\n", inertia_hot_max);
  return failed ? 1 : 0;
}

}  // namespace crane
