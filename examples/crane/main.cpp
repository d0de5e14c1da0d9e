// The paper's crane: a work cycle of the flexible boom driven by its cylinder stroke, the
// hot-spot stress at the welded detail D per step from fused modal rows, and its fatigue damage.
// Run with --help for the options. Writes <output>/crane_history.csv, detail_d_peak.vtu and
// crane_history.png (if gnuplot is installed); prints a summary, then "key: value" lines. With
// --export-c-model it writes the crane for the C interface instead (c_api/demo.c builds it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "crane_run.hpp"

namespace {

const char* kUsage =
    "usage: crane [options]\n"
    "  --payload KG     added mass at x = 2.5 m (default 100)\n"
    "  --stroke FILE    work cycle as CSV rows 'time,stroke' (s, m; stroke = cylinder\n"
    "                   extension from the start; header lines allowed). Default: the\n"
    "                   synthetic cycle of docs/crane.md\n"
    "  --step S         time step (default 0.001)\n"
    "  --tolerance T    Newton tolerance in m/s^2 (default 1e-5; 1e-3 gives the same\n"
    "                   stress history in fewer iterations, docs/accuracy-vs-time.md)\n"
    "  --newton-budget N  real-time budget: at most N Newton iterations per step\n"
    "                   (default: 30, and a step that reaches them stops the run); a\n"
    "                   step at the budget keeps its last iterate and the run goes on.\n"
    "                   Reports the steps kept at it and the largest final correction\n"
    "                   over the tolerance (1: converged)\n"
    "  --modes N        boom deformation modes, 1 to 64: 10 (default, the paper's: 6\n"
    "                   static + 4 fixed-interface; 2.4 % off the converged hot-spot\n"
    "                   history; 16 are within 0.1 %, docs/accuracy-vs-time.md)\n"
    "  --density D      sub-model mesh density (default 1.0: 1792 bricks)\n"
    "  --hydraulic      drive the cylinder by its valve (lumped-fluid hydraulics, the\n"
    "                   chamber pressures solved in the implicit step) with commands made\n"
    "                   from the stroke cycle, instead of prescribing the stroke\n"
    "  --submodel-inertia  add the detail's own weight and inertia to its stresses (the\n"
    "                   paper leaves it out; off by default)\n"
    "  --force-driven   drive the detail's far end by the boom's section force and\n"
    "                   moment instead of its displacement (not the paper's; closer to a\n"
    "                   brick model of the whole boom, docs/accuracy-vs-time.md)\n"
    "  --operators K    batch mode: K operators each drive their own version of the\n"
    "                   cycle (lift height, pace, corrections), in parallel; writes\n"
    "                   operators.csv and a line per operator (stroke drive)\n"
    "  --first-operator F  start the batch at operator F (default 0), to split a\n"
    "                   campaign into ranges, e.g. the tasks of a job array\n"
    "  --threads T      threads of the batch (default 0: one per hardware thread)\n"
    "  --game-loop      run the cycle in a fixed-step game loop: frames at their own\n"
    "                   rate, states interpolated for display, the boom's deformed shape\n"
    "                   at render vertices and a live damage read-out; writes\n"
    "                   game_loop.csv\n"
    "  --render-hz HZ   the game loop's frame rate (default 60)\n"
    "  --realtime       pace the game loop's frames by the wall clock (default: a\n"
    "                   simulated clock with jitter, reproducible)\n"
    "  --export-c-model DIR  write the stroke-driven crane (as --payload, --stroke,\n"
    "                   --step, --tolerance, --modes, --density and --force-driven make\n"
    "                   it) as files a C program builds it from through flexstress.h, and\n"
    "                   stop: crane.txt, boom.fsmodal, detail_d.txt, cycle.csv\n"
    "                   (docs/crane.md; crane_c_demo DIR runs them)\n"
    "  --output DIR     output folder (default crane-out)\n"
    "  --quiet          no progress line\n";

// Rows 'time,stroke' (s, m; stroke = extension from the start), within the cylinder: the piston
// starts `start` out of a cylinder of travel `travel` (CraneSpec::hydraulics).
bool read_stroke_csv(const std::string& path, double start, double travel, std::vector<double>& t,
                     std::vector<double>& s) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "error: cannot open stroke file '%s'\n", path.c_str());
    return false;
  }
  std::string line;
  int row = 0;
  while (std::getline(in, line)) {
    ++row;
    std::string fields = line;
    std::replace(fields.begin(), fields.end(), ',', ' ');
    std::istringstream ls(fields);
    double a = 0, b = 0;
    if (!(ls >> a >> b)) {
      if (t.empty() && line.find_first_of("0123456789") == std::string::npos) continue;  // header
      std::fprintf(stderr, "error: %s line %d: expected 'time,stroke', got '%s'\n", path.c_str(),
                   row, line.c_str());
      return false;
    }
    if (!(b >= -start && b <= travel - start)) {
      std::fprintf(stderr,
                   "error: %s line %d: stroke %g m takes the piston out of the cylinder (travel "
                   "%g m, %g m out at the start: the stroke may range from %g to %g m)\n",
                   path.c_str(), row, b, travel, start, -start, travel - start);
      return false;
    }
    t.push_back(a);
    s.push_back(b);
  }
  if (t.size() < 2) {
    std::fprintf(stderr, "error: %s: needs at least two rows of 'time,stroke'\n", path.c_str());
    return false;
  }
  return true;
}

bool parse_number(const std::string& key, const std::string& value, double& out) {
  char* end = nullptr;
  out = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end != '\0' || !(out == out)) {
    std::fprintf(stderr, "error: %s expects a number, got '%s'\n", key.c_str(), value.c_str());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  crane::RunOptions o;
  auto& spec = o.spec;
  double modes = o.crane.modes;
  double operators = 0, first_operator = 0, threads = 0, render_hz = 60, budget = 0;
  bool game_loop = false, realtime = false;
  std::string export_dir;  // --export-c-model
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help" || key == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (key == "--quiet") {
      o.quiet = true;
      continue;
    }
    if (key == "--hydraulic") {
      o.crane.hydraulic = true;
      continue;
    }
    if (key == "--game-loop" || key == "--realtime") {
      (key == "--game-loop" ? game_loop : realtime) = true;
      continue;
    }
    if (key == "--submodel-inertia") {
      o.crane.with_inertia = true;
      continue;
    }
    if (key == "--force-driven") {
      spec.submodel_drive = flexstress::stress::AttachmentDrive::force;
      continue;
    }
    const bool known = key == "--payload" || key == "--step" || key == "--tolerance" ||
                       key == "--density" || key == "--stroke" || key == "--output" ||
                       key == "--modes" || key == "--operators" || key == "--first-operator" ||
                       key == "--threads" || key == "--render-hz" || key == "--export-c-model" ||
                       key == "--newton-budget";
    if (!known) {
      std::fprintf(stderr, "error: unknown option '%s'\n%s", key.c_str(), kUsage);
      return 2;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "error: %s needs a value\n%s", key.c_str(), kUsage);
      return 2;
    }
    const std::string value = argv[++i];
    bool ok = true;
    if (key == "--payload")
      ok = parse_number(key, value, spec.payload_mass) && spec.payload_mass >= 0;
    else if (key == "--step")
      ok = parse_number(key, value, o.step) && o.step > 0 && o.step <= 0.05;
    else if (key == "--tolerance")
      ok = parse_number(key, value, o.tolerance) && o.tolerance > 0 && o.tolerance <= 1;
    else if (key == "--newton-budget")
      ok = parse_number(key, value, budget) && budget >= 1 && budget <= 1000 &&
           budget == std::floor(budget);
    else if (key == "--modes")
      ok = parse_number(key, value, modes) && modes >= 1 &&
           modes <= flexstress::max_runtime_modes && modes == std::floor(modes);
    else if (key == "--density")
      ok = parse_number(key, value, spec.submodel_density) && spec.submodel_density > 0;
    else if (key == "--operators")
      ok = parse_number(key, value, operators) && operators >= 1 && operators <= 100000 &&
           operators == std::floor(operators);
    else if (key == "--first-operator")
      ok = parse_number(key, value, first_operator) && first_operator >= 0 &&
           first_operator <= 1e9 && first_operator == std::floor(first_operator);
    else if (key == "--threads")
      ok = parse_number(key, value, threads) && threads >= 0 && threads <= 1024 &&
           threads == std::floor(threads);
    else if (key == "--render-hz")
      ok = parse_number(key, value, render_hz) && render_hz >= 1 && render_hz <= 1000;
    else if (key == "--stroke")
      o.stroke_file = value;
    else if (key == "--export-c-model")
      export_dir = value;
    else
      o.output = value;
    if (!ok && key == "--modes") {
      std::fprintf(stderr, "error: --modes: a boom mode count from 1 to %d, got '%s'\n",
                   flexstress::max_runtime_modes, value.c_str());
      return 2;
    }
    if (!ok) {
      std::fprintf(stderr, "error: bad value '%s' for %s\n", value.c_str(), key.c_str());
      return 2;
    }
  }
  if (o.stroke_file.empty())
    crane::synthetic_cycle(o.t, o.ds);
  else if (!read_stroke_csv(o.stroke_file, spec.hydraulics.initial_position, spec.hydraulics.stroke,
                            o.t, o.ds))
    return 1;
  o.crane.modes = static_cast<int>(modes);
  o.newton_budget = static_cast<int>(budget);
  if (!export_dir.empty()) {
    // flexstress.h has no hydraulic cylinder, no output inertia and no Newton budget.
    if (o.crane.hydraulic || o.crane.with_inertia || game_loop || operators > 0 ||
        o.newton_budget > 0) {
      std::fprintf(stderr,
                   "error: --export-c-model writes the stroke-driven crane; it has no "
                   "--hydraulic, --submodel-inertia, --game-loop, --operators or "
                   "--newton-budget form\n");
      return 2;
    }
    return crane::export_c_model(o, export_dir);
  }
  std::error_code dir_error;
  std::filesystem::create_directories(o.output, dir_error);
  if (dir_error) {
    std::fprintf(stderr, "error: cannot create output folder '%s': %s\n", o.output.c_str(),
                 dir_error.message().c_str());
    return 1;
  }

  if (game_loop) {
    if (operators > 0) {
      std::fprintf(stderr, "error: --game-loop and --operators are separate runs\n");
      return 2;
    }
    return crane::run_game_loop(o, render_hz, realtime);
  }
  if (operators > 0) {
    if (o.crane.hydraulic) {
      std::fprintf(stderr, "error: --operators drives the stroke; it has no --hydraulic form\n");
      return 2;
    }
    return crane::run_operators(o, static_cast<int>(first_operator), static_cast<int>(operators),
                                static_cast<unsigned>(threads));
  }
  return crane::run(o);
}
