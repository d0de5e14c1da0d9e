// The spin-up beam (Kane, Ryan & Banerjee 1987) with and without geometric stiffening, with the
// body frame attached to the hub and floating. Writes <output>/spin_up.csv (time, hub rate, the
// tip's in-plane deflection relative to the hub for each model, the tip's axial stretch) and
// prints a summary. Plot: gnuplot -e "dir='<output>'" examples/spin_up_beam/plot.gp
//
//   spin_up_beam [--output DIR] [--duration S] [--step H]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "spin_up_model.hpp"

using namespace flexstress;

namespace {

constexpr int kModes = 10;

struct History {
  std::string name;
  std::vector<double> tip, stretch;  // NaN after a failed step
  std::string outcome = "completed";
};

History run(const char* name, bool stiffening, spin_up::Frame frame, const spin_up::Spec& spec,
            double duration, double h) {
  History hist;
  hist.name = name;
  auto beam = spin_up::make_beam(spec, kModes, frame);
  if (!beam) {
    std::cerr << name << ": " << beam.error().what() << "\n";
    std::exit(1);
  }
  auto built = spin_up::make_model(*beam, spec, stiffening, kModes);
  if (!built) {
    std::cerr << name << ": " << built.error().what() << "\n";
    std::exit(1);
  }
  const spin_up::SpinUp& s = *built;
  for (const std::string& w : s.model.warnings()) std::cerr << name << ": warning: " << w << "\n";
  Data<double> d(s.model);
  set_step_size(d, h);
  if (Status st = initialize(s.model, d); !st) {
    std::cerr << name << ": " << st.error().what() << "\n";
    std::exit(1);
  }
  const long steps = std::lround(duration / h);
  bool failed = false;
  for (long k = 0; k < steps; ++k) {
    if (!failed) {
      const StepStatus st = step(s.model, d);
      if (st != StepStatus::ok) {
        failed = true;
        hist.outcome = std::string(to_string(st)) + " at t = " + std::to_string(d.t) + " s";
      }
    }
    if (failed) {
      hist.tip.push_back(std::nan(""));
      hist.stretch.push_back(std::nan(""));
      continue;
    }
    const spin_up::TipDeflection tip = spin_up::tip_deflection(s, d, spec.length);
    hist.tip.push_back(tip.in_plane);
    hist.stretch.push_back(tip.axial);
  }
  return hist;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "spin-up-out";
  double duration = 30.0, h = 2e-3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--output" && i + 1 < argc) {
      out = argv[++i];
    } else if (a == "--duration" && i + 1 < argc) {
      duration = std::atof(argv[++i]);
    } else if (a == "--step" && i + 1 < argc) {
      h = std::atof(argv[++i]);
    } else {
      std::cerr << "usage: spin_up_beam [--output DIR] [--duration S] [--step H]\n";
      return 2;
    }
  }
  if (!(duration > 0) || !(h > 0) || h > duration) {
    std::cerr << "spin_up_beam: need 0 < step <= duration (got " << h << ", " << duration << ")\n";
    return 2;
  }
  const spin_up::Spec spec;
  const std::vector<History> runs = {
      run("attached_linear", false, spin_up::Frame::attached, spec, duration, h),
      run("attached_stiffened", true, spin_up::Frame::attached, spec, duration, h),
      run("floating_linear", false, spin_up::Frame::floating, spec, duration, h),
      run("floating_stiffened", true, spin_up::Frame::floating, spec, duration, h)};
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/spin_up.csv");
  csv << "t,hub_rate";
  for (const auto& r : runs) csv << "," << r.name << "_tip";
  csv << ",attached_stiffened_stretch\n";
  const spin_up::HubAngle<double> law{spec.spin_up_time, spec.final_rate};
  const std::size_t n = runs.front().tip.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k + 1) * h;
    csv << t << "," << law(t).rate;
    for (const auto& r : runs) csv << "," << r.tip[k];
    csv << "," << runs[1].stretch[k] << "\n";
  }
  std::cout << "spin-up beam, " << kModes << " modes, h = " << h << " s, " << duration
            << " s simulated; tip deflection in the plane of rotation, relative to the hub:\n";
  for (const auto& r : runs) {
    double peak = 0;
    for (double v : r.tip)
      if (std::isfinite(v)) peak = std::max(peak, std::abs(v));
    std::printf("  %-20s max |tip| %10.4g m   %s\n", r.name.c_str(), peak, r.outcome.c_str());
  }
  std::cout << "written: " << out << "/spin_up.csv\n";
  return 0;
}
