// The independent reference of the accuracy study (issue: "a brick model of the whole boom with
// the detail meshed in"): how far is the beam + sub-model method from a brick model of the whole
// boom loaded with the same forces?
//
// The crane runs its work cycle in the study's reference configuration (24 modes, h = 0.1 ms).
// At 25 instants (every 0.5 s, and the instants of the hot spot's maximum and minimum) the
// boom's loads are taken from the simulated state: gravity and the d'Alembert force of every
// material point (frame acceleration, centrifugal, Coriolis and elastic acceleration from the
// modal coordinates), the payload's weight and inertia, and the rod's force at B (the spherical
// joint's reaction). A brick model of the whole boom (the same RHS and welded rib, meshed by
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

#include <flexstress/stress/sub_model_inertia.hpp>

#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/section_force_modes.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "../../examples/crane/crane_model.hpp"
#include "../../examples/crane/detail_model.hpp"

using namespace flexstress;

namespace {

constexpr int kModes = 24;
using CraneT = crane::Crane;
using State = Data<double>;
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
  VectorXd p_ddot;  ///< the boom's modal accelerations (central difference of its rates)
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
  crane::CraneOptions options;
  options.modes = kModes;
  auto made = crane::make_crane(spec, options, t, ds);
  if (!made) return made.error();
  auto inertia =
      stress::SubModelInertia<double>::build(*made->detail.model->sub, made->detail.model->outputs);
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
              cr.detail.model->sub->mesh().hexes().size(), ms_since(t0));
  const Model<double>& model = cr.model;
  const BodyId boom_body = cr.boom_body;
  const Index hot_row = cr.detail.hot_spot, nominal_row = cr.detail.nominal;
  Eigen::VectorXd y_force(crf.detail.fused.rows());

  // The cycle, twice (deterministic): the first run finds the hot spot's extremes, the second
  // keeps the states at the chosen instants.
  const double step_size = 1e-4;
  const long steps = std::lround((tt.back() - tt.front()) / step_size);
  Eigen::VectorXd y(cr.detail.fused.rows());
  auto sub_outputs = [&](const State& s, double& hot, double& hot_inertia, double& nominal) {
    y.noalias() = cr.detail.fused * modal_coordinates(model, s, boom_body);
    hot = y(hot_row) / 1e6;
    nominal = y(nominal_row) / 1e6;
    hot_inertia =
        hot +
        inertia.rows().row(hot_row).dot(body_inertia_coordinates(model, s, boom_body.index)) / 1e6;
  };
  std::vector<long> keep;
  for (long k = 0; k <= steps; k += 5000) keep.push_back(k);  // every 0.5 s
  std::vector<double> history_t, history_hot;
  for (int pass = 0; pass < 2; ++pass) {
    State s = cr.initial;
    s.settings.step = step_size;
    s.settings.acceleration_tolerance = 1e-6;
    s.settings.relative_acceleration_tolerance = 0;
    if (Status st = initialize(model, s); !st) {
      std::fprintf(stderr, "whole_boom_reference: %s\n", st.error().what().c_str());
      return 1;
    }
    long arg_max = 0, arg_min = 0;
    double hot_max = -1e300, hot_min = 1e300;
    std::vector<Instant> instants;
    // The library reads out modal velocities but not accelerations: p_ddot of a kept instant by
    // central differences of p_dot over its neighbouring steps (one-sided at the ends).
    VectorXd rates_before, pending_from;
    long pending_from_k = -1;  // >= 0: the last kept instant waits for the next step's rates
    const auto finish_pending = [&](long k) {
      instants.back().p_ddot = (modal_velocities(model, s, boom_body) - pending_from) /
                               (double(k - pending_from_k) * step_size);
      pending_from_k = -1;
    };
    t0 = Clock::now();
    for (long k = 0; k <= steps; ++k) {
      rates_before = modal_velocities(model, s, boom_body);  // step k - 1's (k = 0: its own)
      if (k > 0) {
        const StepStatus st = step(model, s);
        if (st != StepStatus::ok && st != StepStatus::constraint_violation) {
          std::fprintf(stderr, "whole_boom_reference: step %ld: %s\n", k, to_string(st));
          return 1;
        }
      }
      if (pending_from_k >= 0) finish_pending(k);
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
        y_force.noalias() = crf.detail.fused * modal_coordinates(model, s, boom_body);
        in.hot_forced = (y_force(crf.detail.hot_spot) +
                         inertia_force.rows()
                             .row(crf.detail.hot_spot)
                             .dot(body_inertia_coordinates(model, s, boom_body.index))) /
                        1e6;
        in.t = double(s.t);
        in.state = s;
        instants.push_back(in);
        pending_from = rates_before;
        pending_from_k = k > 0 ? k - 1 : k;
      }
    }
    if (pending_from_k >= 0) finish_pending(steps);  // the last step: backward
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
    auto modes = SectionModes::build(cr.boom, {&whole->mesh, &cr.detail.model->mesh.mesh});
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
    // Marker i of B (on the boom): the axes its reaction is given in.
    const MarkerId b_on_boom{model.joint(cr.joint_b).marker_i};
    for (std::size_t k = 0; k < instants.size(); ++k) {
      const State& s = instants[k].state;
      const Matrix3d a = rotation_matrix<double>(body_orientation(model, s, boom_body));
      const Vector3d g = a.transpose() * model.gravity();
      // Frame acceleration less gravity and angular acceleration (body frame).
      const Eigen::Matrix<double, 12, 1> inertia_c =
          body_inertia_coordinates(model, s, boom_body.index);
      const Vector3d a_o = inertia_c.head<3>() + g;
      const Vector3d w = body_angular_velocity(model, s, boom_body),
                     alpha = inertia_c.segment<3>(3);
      const VectorXd u = modes->phi * modal_coordinates(model, s, boom_body);
      const VectorXd u_dot = modes->phi * modal_velocities(model, s, boom_body);
      const VectorXd u_ddot = modes->phi * instants[k].p_ddot;
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
      // The rod's force on the boom: minus the joint's force on the rod (its body j).
      const Vector3d rod_force = -(a.transpose() * (marker_frame(model, s, b_on_boom).axes *
                                                    joint_reaction(model, s, cr.joint_b).force));
      for (int c = 0; c < 3; ++c) {
        f(dofs.dof(node_payload, c)) += payload_force(c);
        f(dofs.dof(node_b, c)) += rod_force(c);
      }
      loads.col(static_cast<Index>(k)) = f;
      // Balance with the hinge force of the simulation (on the boom, marker j; marker i on the
      // support has the global axes).
      Vector3d total = a.transpose() * joint_reaction(model, s, cr.joint_a).force;
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
    auto rows = cr.detail.model->outputs.rows(*boom, response);
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
      const double whole_hot = (*rows)(hot_row, static_cast<Index>(k)) / 1e6;
      const double whole_nominal = (*rows)(nominal_row, static_cast<Index>(k)) / 1e6;
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
