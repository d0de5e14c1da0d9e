// crane --export-c-model DIR (crane_run.hpp): the stroke-driven crane as four files from which
// a C program builds the same model through flexstress.h (c_api/demo.c; docs/crane.md). The
// boom and the detail's rows are the precomputed parts C cannot make; the rest is numbers.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <flexstress/reduction/modal_body_io.hpp>

#include "crane_run.hpp"

namespace crane {

namespace {

// The shortest decimal that reads back as the same double: the C program must build the very
// model the C++ one does, yet the files stay readable (0.001, not 0.0010000000000000000208).
std::string exact(double v) {
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

// One "key values..." line.
void put(std::FILE* f, const char* key, const double* v, int n) {
  std::fprintf(f, "%s", key);
  for (int i = 0; i < n; ++i) std::fprintf(f, " %s", exact(v[i]).c_str());
  std::fprintf(f, "\n");
}
void put(std::FILE* f, const char* key, double v) {
  put(f, key, &v, 1);
}

// Opens dir/name for writing, or says why not.
std::FILE* open_out(const std::string& dir, const char* name) {
  const std::string path = dir + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) std::fprintf(stderr, "error: cannot write %s\n", path.c_str());
  return f;
}

void write_crane_txt(std::FILE* f, const RunOptions& o, const Crane& cr) {
  const PartsLayout l = parts_layout(o.spec);
  const MeterSpec meter;
  const ImplicitSettings<double>& s = cr.model.settings();
  std::fprintf(f,
               "# The stroke-driven crane of examples/crane for the C interface (crane "
               "--export-c-model).\n"
               "# A line: a key and its values. SI units; 3x3 matrices column-major (columns: "
               "axes),\n"
               "# orientations as Euler parameters e0 e1 e2 e3. docs/crane.md explains each "
               "key.\n");
  put(f, "boom_modes", o.crane.modes);
  put(f, "boom_node_a", double(cr.boom.node_a));
  put(f, "boom_node_b", double(cr.boom.node_b));
  put(f, "boom_b_offset", l.boom_b_offset.data(), 3);
  put(f, "support_a", l.support_a.data(), 3);
  put(f, "support_c", l.support_c.data(), 3);
  put(f, "cylinder_mass", l.cylinder_mass);
  put(f, "cylinder_center_of_mass", l.cylinder_com.data(), 3);
  put(f, "cylinder_inertia", l.cylinder_inertia.data(), 9);
  put(f, "cylinder_position", l.cylinder_position.data(), 3);
  put(f, "cylinder_orientation", l.orientation.data(), 4);
  put(f, "cylinder_c_axes", l.cylinder_c_axes.data(), 9);
  put(f, "rod_mass", l.rod_mass);
  put(f, "rod_center_of_mass", l.rod_com.data(), 3);
  put(f, "rod_inertia", l.rod_inertia.data(), 9);
  put(f, "rod_position", l.rod_position.data(), 3);
  put(f, "rod_orientation", l.orientation.data(), 4);
  put(f, "gravity", l.gravity.data(), 3);
  put(f, "initial_length", cr.initial_length);
  put(f, "hot_spot_output", double(cr.detail.hot_spot));
  put(f, "meter_fat", meter.fat);
  const double range[2] = {meter.lower, meter.upper};
  put(f, "meter_range", range, 2);
  put(f, "meter_scale", meter.scale);
  put(f, "step", o.step);
  put(f, "spectral_radius", s.spectral_radius);
  put(f, "max_iterations", s.max_iterations);
  put(f, "tolerance", o.tolerance);
}

void write_detail_rows(std::FILE* f, const Detail& d) {
  std::fprintf(f,
               "# Detail D's stress outputs (Pa), y = F p over the boom's modal coordinates p:\n"
               "# the line 'outputs N modes M', then a row of F per output, its M coefficients\n"
               "# followed by its name.\n");
  std::fprintf(f, "outputs %ld modes %ld\n", long(d.fused.rows()), long(d.fused.cols()));
  for (Index i = 0; i < d.fused.rows(); ++i) {
    for (Index k = 0; k < d.fused.cols(); ++k) std::fprintf(f, "%s ", exact(d.fused(i, k)).c_str());
    std::fprintf(f, "%s\n", d.names[std::size_t(i)].c_str());
  }
}

}  // namespace

int export_c_model(const RunOptions& o, const std::string& dir) {
  auto made = build_crane(o);
  if (!made) return 1;
  const Crane& cr = *made;
  std::error_code dir_error;
  std::filesystem::create_directories(dir, dir_error);
  if (dir_error) {
    std::fprintf(stderr, "error: cannot create folder '%s': %s\n", dir.c_str(),
                 dir_error.message().c_str());
    return 1;
  }
  if (Status st = reduction::save_modal_body(cr.boom.data, dir + "/boom.fsmodal"); !st) {
    std::fprintf(stderr, "error: %s\n", st.error().what().c_str());
    return 1;
  }
  std::FILE* files[3] = {open_out(dir, "crane.txt"), open_out(dir, "detail_d.txt"),
                         open_out(dir, "cycle.csv")};
  bool ok = files[0] && files[1] && files[2];
  if (ok) {
    write_crane_txt(files[0], o, cr);
    write_detail_rows(files[1], cr.detail);
    // The --stroke format: the C program adds initial_length for the driver's table.
    std::fprintf(files[2], "time,stroke\n");
    for (std::size_t i = 0; i < o.t.size(); ++i)
      std::fprintf(files[2], "%s,%s\n", exact(o.t[i]).c_str(), exact(o.ds[i]).c_str());
  }
  for (std::FILE* f : files)
    if (f && std::fclose(f) != 0) ok = false;
  if (!ok) {
    std::fprintf(stderr, "error: writing the C model into '%s' failed\n", dir.c_str());
    return 1;
  }
  std::printf(
      "crane for the C interface in %s/: crane.txt, boom.fsmodal (%d modes), detail_d.txt (%ld "
      "outputs), cycle.csv (%zu rows)\n",
      dir.c_str(), o.crane.modes, long(cr.detail.fused.rows()), o.t.size());
  return 0;
}

}  // namespace crane
