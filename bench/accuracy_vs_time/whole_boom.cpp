// The independent reference of the accuracy study (issue: "a brick model of the whole boom with
// the detail meshed in"): how far is the beam + sub-model method from a brick model of the whole
// boom loaded with the same forces?
//
// The crane runs its work cycle in the study's reference configuration (24 modes, h = 0.1 ms).
// At 25 instants (every 0.5 s, and the instants of the hot spot's maximum and minimum) the
// boom's loads are taken from the simulated state: gravity and the d'Alembert force of every
// material point (frame acceleration, centrifugal, Coriolis and elastic acceleration from the
// modal coordinates), the payload's weight and inertia, and the rod's force at B (the spherical
// joint's multiplier). A brick model of the whole boom (the same RHS and welded rib, meshed by
// the same generator at the same density, so the detail's mesh is the sub-model's) is clamped at
// A and solved for them quasi-statically; its hot spot (the same read-out rows) is compared with
// the sub-model's at the same instant, and with that of the same sub-model driven at its x1 end by
// the beam's section forces (CraneSpec::submodel_drive). The clamp's reaction checks the load
// set: the rod's and A's forces from the simulation balance the inertia and gravity loads on the
// bricks only if both describe the same boom, so the program prints the residual force and the
// moment about A's hinge axis (which a revolute does not carry).
//
// Writes <output>/whole_boom.csv (one row per instant), whole_boom_history.csv (the sub-model's
// hot spot every 10 ms) and whole_boom.md (the summary), and renders whole_boom.gp with gnuplot.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "../../examples/crane/crane_scene.hpp"

using namespace flexstress;

namespace {

constexpr int kModes = 24;
using CraneT = crane::Crane<kModes>;
using SceneT = CraneT::SceneT;
using State = SceneT::State;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Elastic motion of the boom's sections: per distinct x of the brick nodes, the 6 rows
// (translations, rotations of the beam's cross-section there) per mode, Hermite between nodes.
struct SectionModes {
  std::map<long long, Index> row_of;  // x in micrometres -> block index
  MatrixXd phi;                       // 6 per section x modes

  static long long key(double x) { return std::llround(x * 1e6); }

  static Result<SectionModes> build(const crane::Boom& boom,
                                    const std::vector<const fe::Mesh*>& meshes) {
    SectionModes s;
    std::vector<stress::HostPoint> hosts;
    for (const fe::Mesh* bricks : meshes)
      for (Index n = 0; n < bricks->num_nodes(); ++n) {
        const double x = bricks->node(n).x();
        if (s.row_of.emplace(key(x), static_cast<Index>(hosts.size())).second)
          hosts.push_back(crane::host_point(boom, x, stress::BoundaryInterpolation::hermite));
      }
    auto phi = stress::boundary_modes(boom.data, hosts);
    if (!phi) return phi.error();
    s.phi = std::move(*phi);
    return s;
  }
  // Displacement of material point r (body frame) for modal vector q: u_c + theta x (r - axis).
  Vector3d at(const Vector3d& r, const VectorXd& section_values) const {
    const Index b = 6 * row_of.at(key(r.x()));
    const Vector3d d(0.0, r.y(), r.z());
    return section_values.segment<3>(b) + section_values.segment<3>(b + 3).cross(d);
  }
};

struct Instant {
  double t = 0;
  State state;
  double hot_sub = 0, hot_sub_inertia = 0, nominal_sub = 0;
  double hot_forced = 0;  ///< the force-driven sub-model's, with its inertia
};

// A crane and the rows of its sub-model's own inertia.
struct CraneWithInertia {
  CraneT crane;
  stress::SubModelInertia<double> inertia;
};

Result<CraneWithInertia> make_crane_with_inertia(const crane::CraneSpec& spec,
                                                 const std::vector<double>& t,
                                                 const std::vector<double>& ds) {
  auto made = crane::make_crane<kModes>(spec, t, ds);
  if (!made) return made.error();
  auto inertia = stress::SubModelInertia<double>::build(*made->sub, made->outputs);
  if (!inertia) return inertia.error();
  return CraneWithInertia{std::move(*made), std::move(*inertia)};
}

struct Options {
  std::string output = "whole-boom-out";
  double density = 1.0;
  double max_element_length = 0.025;
  double submodel_x0 = 0.5, submodel_x1 = 0.8;
  double submodel_max_element_length = 0.0;
};

const char* kUsage =
    "usage: whole_boom_reference [--output DIR] [--density D] [--max-element-length L]\n"
    "  --output DIR              where the CSVs, the summary and the plot go\n"
    "                            (default whole-boom-out)\n"
    "  --density D               mesh density of the detail, in the sub-model and the whole\n"
    "                            boom alike (default 1)\n"
    "  --max-element-length L    longest brick along the boom away from the detail, m\n"
    "                            (default 0.025)\n"
    "  --submodel X0,X1          the sub-model's extent along the boom, m (default 0.5,0.8)\n"
    "  --submodel-max-element-length L  cap the sub-model's graded bricks too (default: the\n"
    "                            crane's sub-model, graded without a cap)\n";

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    const char* v = value();
    if (!v) {
      std::fprintf(stderr, "whole_boom_reference: %s needs a value\n%s", a.c_str(), kUsage);
      return false;
    }
    char* end = nullptr;
    if (a == "--output") {
      o.output = v;
    } else if (a == "--submodel") {
      if (std::sscanf(v, "%lf,%lf", &o.submodel_x0, &o.submodel_x1) != 2 ||
          !(o.submodel_x0 < o.submodel_x1)) {
        std::fprintf(stderr,
                     "whole_boom_reference: --submodel wants X0,X1 with X0 < X1, got '%s'\n", v);
        return false;
      }
    } else if (a == "--density" || a == "--max-element-length" ||
               a == "--submodel-max-element-length") {
      const double d = std::strtod(v, &end);
      if (end == v || *end != '\0' || !(d > 0)) {
        std::fprintf(stderr, "whole_boom_reference: %s wants a positive number, got '%s'\n",
                     a.c_str(), v);
        return false;
      }
      (a == "--density"              ? o.density
       : a == "--max-element-length" ? o.max_element_length
                                     : o.submodel_max_element_length) = d;
    } else {
      std::fprintf(stderr, "whole_boom_reference: unknown option '%s'\n%s", a.c_str(), kUsage);
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (!parse(argc, argv, opt)) return 2;
  std::filesystem::create_directories(opt.output);

  // The crane in the study's reference configuration (bench/accuracy_vs_time/main.cpp).
  crane::CraneSpec spec;
  spec.submodel_density = opt.density;
  spec.submodel_x0 = opt.submodel_x0;
  spec.submodel_x1 = opt.submodel_x1;
  spec.submodel_max_element_length = opt.submodel_max_element_length;
  std::vector<double> tt, ds;
  crane::synthetic_cycle(tt, ds);
  auto t0 = Clock::now();
  auto made = make_crane_with_inertia(spec, tt, ds);
  // The same crane with a force-driven x1 end (CraneSpec::submodel_drive): same boom and
  // dynamics, so its hot spot is read from the same states.
  crane::CraneSpec force_spec = spec;
  force_spec.submodel_drive = stress::AttachmentDrive::force;
  auto made_force = make_crane_with_inertia(force_spec, tt, ds);
  for (const Status& st : {made.status(), made_force.status()})
    if (!st) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", st.error().what().c_str());
      return 1;
    }
  CraneT& cr = made->crane;
  const auto& inertia = made->inertia;
  CraneT& crf = made_force->crane;
  const auto& inertia_force = made_force->inertia;
  std::printf("cranes (24 modes, sub-model density %g, %zu bricks): %.0f ms\n", opt.density,
              cr.sub->mesh().hexes().size(), ms_since(t0));
  Eigen::VectorXd y_force(crf.fused->num_outputs());

  // The cycle, twice (deterministic): the first run finds the hot spot's extremes, the second
  // keeps the states at the chosen instants.
  ImplicitIntegrator<SceneT>::Settings set;
  set.step = 1e-4;
  set.acceleration_tolerance = 1e-6;
  const long steps = std::lround((tt.back() - tt.front()) / set.step);
  Eigen::VectorXd y(cr.fused->num_outputs());
  auto sub_outputs = [&](const State& s, double& hot, double& hot_inertia, double& nominal) {
    cr.fused->evaluate(s.coordinates<0>().p, y);
    hot = y(cr.hot_spot_row) / 1e6;
    nominal = y(cr.nominal_row) / 1e6;
    hot_inertia =
        hot +
        inertia.rows().row(cr.hot_spot_row).dot(crane::boom_inertia_coordinates(cr.scene, s)) / 1e6;
  };
  std::vector<long> keep;
  for (long k = 0; k <= steps; k += 5000) keep.push_back(k);  // every 0.5 s
  std::vector<double> history_t, history_hot;
  for (int pass = 0; pass < 2; ++pass) {
    State s = cr.initial;
    ImplicitIntegrator<SceneT> integ(cr.scene, set);
    if (Status st = integ.initialize(s); !st) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", st.error().what().c_str());
      return 1;
    }
    long arg_max = 0, arg_min = 0;
    double hot_max = -1e300, hot_min = 1e300;
    std::vector<Instant> instants;
    t0 = Clock::now();
    for (long k = 0; k <= steps; ++k) {
      if (k > 0) {
        const StepStatus st = integ.step(s);
        if (st != StepStatus::ok && st != StepStatus::constraint_violation) {
          std::fprintf(stderr, "whole_boom_reference: step %ld: %s\n", k, to_string(st));
          return 1;
        }
      }
      Instant in;
      sub_outputs(s, in.hot_sub, in.hot_sub_inertia, in.nominal_sub);
      if (pass == 0) {
        if (in.hot_sub_inertia > hot_max) hot_max = in.hot_sub_inertia, arg_max = k;
        if (in.hot_sub_inertia < hot_min) hot_min = in.hot_sub_inertia, arg_min = k;
        if (k % 100 == 0) {
          history_t.push_back(double(s.t));
          history_hot.push_back(in.hot_sub_inertia);
        }
      } else if (std::binary_search(keep.begin(), keep.end(), k)) {
        crf.fused->evaluate(s.coordinates<0>().p, y_force);
        in.hot_forced =
            (y_force(crf.hot_spot_row) + inertia_force.rows()
                                             .row(crf.hot_spot_row)
                                             .dot(crane::boom_inertia_coordinates(cr.scene, s))) /
            1e6;
        in.t = double(s.t);
        in.state = s;
        instants.push_back(in);
      }
    }
    std::printf("cycle pass %d: %ld steps in %.0f ms\n", pass + 1, steps, ms_since(t0));
    if (pass == 0) {
      keep.push_back(arg_max);
      keep.push_back(arg_min);
      std::sort(keep.begin(), keep.end());
      keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
      continue;
    }

    // The whole boom in bricks: the detail's generator over [0, L], with sections at B's node
    // and at the payload for the links, clamped at A through a rigid web to the hinge point.
    t0 = Clock::now();
    fe::RhsAttachmentSpec ws;
    ws.density = opt.density;
    ws.x0 = 0.0;
    ws.x1 = spec.boom_length;
    ws.wall = spec.wall;
    ws.formulation = spec.formulation;
    ws.max_element_length = opt.max_element_length;
    ws.extra_x_stations = {spec.b_node_x, spec.payload_x};
    auto whole = fe::make_rhs_attachment_mesh(ws);
    if (!whole) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", whole.error().what().c_str());
      return 1;
    }
    fe::Mesh mesh = whole->mesh;
    const Index node_b = mesh.add_node(spec.b);  // B in the boom frame: 0.125 below x = 0.32
    mesh.add_rigid_link(node_b, whole->section_nodes(spec.b_node_x));
    const Vector3d payload_point(spec.payload_x, 0, 0);
    const Index node_payload = mesh.add_node(payload_point);
    mesh.add_rigid_link(node_payload, whole->section_nodes(spec.payload_x));
    auto modes = SectionModes::build(cr.boom, {&whole->mesh, &cr.detail.mesh});
    if (!modes) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", modes.error().what().c_str());
      return 1;
    }
    const std::size_t num_bricks = mesh.hexes().size();
    auto boom =
        stress::SubModel::build(std::move(mesh), {{Vector3d::Zero(), whole->end_section_x0}});
    if (!boom) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", boom.error().what().c_str());
      return 1;
    }
    const fe::DofMap& dofs = boom->model().dofs;
    std::printf("whole boom: %zu bricks, %ld DOFs, factorized in %.0f ms\n", num_bricks,
                static_cast<long>(dofs.size()), ms_since(t0));

    // Loads per instant, in the boom frame.
    t0 = Clock::now();
    const auto& p_spec = spec;
    MatrixXd loads = MatrixXd::Zero(dofs.size(), static_cast<Index>(instants.size()));
    std::vector<double> force_residual, moment_residual;
    constexpr int i_rev = SceneT::joint_offset[0], i_sph = SceneT::joint_offset[2];
    for (std::size_t k = 0; k < instants.size(); ++k) {
      const State& s = instants[k].state;
      const Matrix3d a = rotation_matrix(s.coordinates<0>().theta);
      const Vector3d g = a.transpose() * cr.scene.gravity;
      const Vector3d a_o = a.transpose() * s.v_dot.head<3>();
      const Vector3d w = s.v.segment<3>(3), alpha = s.v_dot.segment<3>(3);
      const VectorXd u = modes->phi * s.coordinates<0>().p;
      const VectorXd u_dot = modes->phi * s.v.segment<kModes>(6);
      const VectorXd u_ddot = modes->phi * s.v_dot.segment<kModes>(6);
      // a = a_O + alpha x r + w x (w x r) + 2 w x u_dot + u_ddot, r = r0 + u (deformed point).
      auto acceleration = [&](const Vector3d& r0) -> Vector3d {
        const Vector3d r = r0 + modes->at(r0, u);
        return a_o + alpha.cross(r) + w.cross(w.cross(r)) + 2.0 * w.cross(modes->at(r0, u_dot)) +
               modes->at(r0, u_ddot);
      };
      VectorXd field = VectorXd::Zero(dofs.size());
      for (Index n = 0; n < whole->mesh.num_nodes(); ++n) {
        const Vector3d f = g - acceleration(whole->mesh.node(n));
        for (int c = 0; c < 3; ++c) field(dofs.dof(n, c)) = f(c);
      }
      VectorXd f = boom->model().mass_all * field;
      const Vector3d payload_force = p_spec.payload_mass * (g - acceleration(payload_point));
      const Vector3d rod_force = a.transpose() * s.lambda.segment<3>(i_sph);  // on the boom
      for (int c = 0; c < 3; ++c) {
        f(dofs.dof(node_payload, c)) += payload_force(c);
        f(dofs.dof(node_b, c)) += rod_force(c);
      }
      loads.col(static_cast<Index>(k)) = f;
      // Balance with the hinge force of the simulation (-lambda on the boom, marker j).
      Vector3d total = a.transpose() * -s.lambda.segment<3>(i_rev);
      double moment_z = 0;
      for (Index n = 0; n < boom->mesh().num_nodes(); ++n) {
        if (dofs.num_node_dofs(n) == 0) continue;
        const Vector3d fn(f(dofs.dof(n, 0)), f(dofs.dof(n, 1)), f(dofs.dof(n, 2)));
        total += fn;
        moment_z += boom->mesh().node(n).cross(fn).z();
      }
      force_residual.push_back(total.norm() / rod_force.norm());
      moment_residual.push_back(std::abs(moment_z) /
                                std::abs(Vector3d(spec.b).cross(rod_force).z()));
    }
    MatrixXd response(dofs.size(), loads.cols());
    for (Index k = 0; k < loads.cols(); ++k) response.col(k) = boom->load_response(loads.col(k));
    auto rows = cr.outputs.rows(*boom, response);
    if (!rows) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", rows.error().what().c_str());
      return 1;
    }
    std::printf("whole boom: %zu load cases solved in %.0f ms\n", instants.size(), ms_since(t0));

    // Results.
    std::ofstream csv(opt.output + "/whole_boom.csv");
    csv << "t,hot_spot_sub_model_MPa,hot_spot_sub_model_with_inertia_MPa,hot_spot_whole_boom_MPa,"
           "nominal_sub_model_MPa,nominal_whole_boom_MPa,force_residual,moment_residual,"
           "hot_spot_force_driven_MPa\n";
    double lo = 1e300, hi = -1e300;
    for (double h : history_hot) lo = std::min(lo, h), hi = std::max(hi, h);
    const double range = hi - lo;
    double max_err = 0, max_err_inertia = 0, sum2 = 0, sum2_inertia = 0, max_nominal = 0;
    double max_force = 0, max_moment = 0, max_err_forced = 0, sum2_forced = 0;
    for (std::size_t k = 0; k < instants.size(); ++k) {
      const double whole_hot = (*rows)(cr.hot_spot_row, static_cast<Index>(k)) / 1e6;
      const double whole_nominal = (*rows)(cr.nominal_row, static_cast<Index>(k)) / 1e6;
      const Instant& in = instants[k];
      const double forced_hot = in.hot_forced;
      char line[320];
      std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.3e,%.3e,%.6f\n", in.t,
                    in.hot_sub, in.hot_sub_inertia, whole_hot, in.nominal_sub, whole_nominal,
                    force_residual[k], moment_residual[k], forced_hot);
      max_err_forced = std::max(max_err_forced, std::abs(forced_hot - whole_hot));
      sum2_forced += (forced_hot - whole_hot) * (forced_hot - whole_hot);
      csv << line;
      const double e = in.hot_sub - whole_hot, ei = in.hot_sub_inertia - whole_hot;
      max_err = std::max(max_err, std::abs(e));
      max_err_inertia = std::max(max_err_inertia, std::abs(ei));
      sum2 += e * e;
      sum2_inertia += ei * ei;
      max_nominal = std::max(max_nominal, std::abs(in.nominal_sub - whole_nominal));
      max_force = std::max(max_force, force_residual[k]);
      max_moment = std::max(max_moment, moment_residual[k]);
    }
    std::ofstream hist(opt.output + "/whole_boom_history.csv");
    hist << "t,hot_spot_sub_model_with_inertia_MPa\n";
    for (std::size_t k = 0; k < history_t.size(); ++k)
      hist << history_t[k] << ',' << history_hot[k] << '\n';
    const double n = double(instants.size());
    std::ofstream md(opt.output + "/whole_boom.md");
    char text[2048];
    std::snprintf(
        text, sizeof text,
        "| quantity | value |\n|---|---|\n"
        "| instants | %zu |\n"
        "| hot-spot range of the cycle (sub-model with inertia) | %.3f MPa |\n"
        "| max abs difference, sub-model (no inertia) - whole boom | %.3f MPa = %.2f %% of the "
        "range |\n"
        "| RMS difference, sub-model (no inertia) - whole boom | %.3f MPa |\n"
        "| max abs difference, sub-model with inertia - whole boom | %.3f MPa = %.2f %% of the "
        "range |\n"
        "| RMS difference, sub-model with inertia - whole boom | %.3f MPa |\n"
        "| max abs difference, force-driven sub-model - whole boom | %.3f MPa = %.2f %% of the "
        "range |\n"
        "| RMS difference, force-driven sub-model - whole boom | %.3f MPa |\n"
        "| max abs difference of the nominal bottom-flange stress | %.3f MPa |\n"
        "| load balance: max residual force / rod force | %.2e |\n"
        "| load balance: max moment about the hinge / rod's moment | %.2e |\n",
        instants.size(), range, max_err, 100 * max_err / range, std::sqrt(sum2 / n),
        max_err_inertia, 100 * max_err_inertia / range, std::sqrt(sum2_inertia / n), max_err_forced,
        100 * max_err_forced / range, std::sqrt(sum2_forced / n), max_nominal, max_force,
        max_moment);
    md << text;
    std::fputs(text, stdout);
  }
  const std::string plot = std::string(FLEXSTRESS_STUDY_SOURCE_DIR) + "/whole_boom.gp";
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0)
    (void)std::system(("gnuplot -e \"dir='" + opt.output + "'\" '" + plot + "'").c_str());
  return 0;
}
