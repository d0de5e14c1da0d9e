// The runtime model's two kinds of body kernels: a mode count compiled with a fixed size
// (FLEXSTRESS_MODE_COUNTS) and the bounded fallback that runs any count. Both run the same
// arithmetic in different storage, so a flexible pendulum must move the same way with either, to
// round-off; the physics of that pendulum is checked against the FE model in
// tests/model/test_flexible_models.cpp. That a step allocates nothing, with either kernel, is
// tests/model/test_no_alloc.cpp's.
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_model_flexible {

using namespace flexstress;

namespace {

// The hinged beam of tests/model/test_flexible_models.cpp: a 2 m steel RHS 40 x 20 x 2 mm,
// hinged at x = 0 about z, released horizontal under gravity.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(kLength, kSection, 24, {0.0}, fixed_modes);
}

struct RuntimeBeam {
  Model<double> model;
  BodyId beam;
  MarkerId tip;
};

RuntimeBeam runtime_beam(const testing::BeamBody& beam, int modes, bool bounded) {
  ModelBuilder<double> b;
  b.use_bounded_kernels(bounded);
  const BodyId body = b.add_flexible_body("beam", beam.data, modes);
  b.set_damping_ratio(body, 0.02);
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1);
  const MarkerId root = b.add_marker("root", body, beam.interface_nodes[0]);
  const MarkerId tip = b.add_marker("tip", body, beam.line.nodes.back());
  b.add_joint("hinge", JointKind::revolute, pivot, root);
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  return {std::move(*m), body, tip};
}

// The state after 0.3 s of swing from a spin of 1 rad/s downward, stacked, and the kernel used.
Eigen::VectorXd swing(const testing::BeamBody& beam, int modes, bool bounded, int* kernel) {
  const RuntimeBeam rt = runtime_beam(beam, modes, bounded);
  *kernel = rt.model.body(rt.beam).kernels->fixed_modes;
  Data<double> d(rt.model);
  set_body_velocity(rt.model, d, rt.beam, Vector3d::Zero(), Vector3d(0, 0, -1.0));
  REQUIRE(initialize(rt.model, d).ok());
  for (int i = 0; i < 300; ++i) REQUIRE(step(rt.model, d) == StepStatus::ok);
  CHECK(marker_frame(rt.model, d, rt.tip).origin.y() < -0.2);  // it swung
  const auto p = modal_coordinates(rt.model, d, rt.beam);
  const auto p_dot = modal_velocities(rt.model, d, rt.beam);
  Eigen::VectorXd out(3 + 4 + 2 * modes + 6);
  out << body_position(rt.model, d, rt.beam),
      Eigen::Vector4d(body_orientation(rt.model, d, rt.beam)), p, p_dot,
      body_velocity(rt.model, d, rt.beam), body_angular_velocity(rt.model, d, rt.beam);
  return out;
}

// The beam of hinged_beam() with `modes` modes on its hinge, added to b, and the hinge's
// markers (where a driver goes).
struct HingedParts {
  BodyId body;
  MarkerId pivot, root;
};
HingedParts add_hinge(ModelBuilder<double>& b, const testing::BeamBody& beam, int modes) {
  HingedParts h;
  h.body = b.add_flexible_body("beam", beam.data, modes);
  h.pivot = b.add_marker("pivot", b.ground(), -1);
  h.root = b.add_marker("root", h.body, beam.interface_nodes[0]);
  b.add_joint("hinge", JointKind::revolute, h.pivot, h.root);
  return h;
}

// The same under gravity.
BodyId add_hinged(ModelBuilder<double>& b, const testing::BeamBody& beam, int modes) {
  const BodyId body = add_hinge(b, beam, modes).body;
  b.set_gravity(Vector3d(0, -9.81, 0));
  return body;
}

// An empty damage meter: IIW FAT 100 on 128 classes of -window .. window.
DamageMeter<double> fat100_meter(double window) {
  auto grid = fatigue::ClassGrid<double>::create(-window, window, 128);
  REQUIRE(grid.ok());
  auto curve = fatigue::iiw_normal_curve(100.0, fatigue::IiwBeyondKnee::haibach);
  REQUIRE(curve.ok());
  auto damage = fatigue::DamageModel<double>::create(*curve);
  REQUIRE(damage.ok());
  auto meter = DamageMeter<double>::create(*grid, 0, *damage);
  REQUIRE(meter.ok());
  return *meter;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1e-30, b.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST_CASE("runtime model: fixed-size and bounded kernels move a flexible pendulum alike") {
  for (int modes : {10, 16}) {
    CAPTURE(modes);
    const auto beam = hinged_beam(modes);
    int fixed = 0, bounded = 0;
    const auto a = swing(beam, modes, false, &fixed);
    const auto b = swing(beam, modes, true, &bounded);
    CHECK(fixed == modes);             // a count compiled with a fixed size
    CHECK(bounded == Eigen::Dynamic);  // the bounded kernels, asked for
    MESSAGE(modes << " modes, fixed vs bounded kernels: " << relative_difference(a, b));
    CHECK(relative_difference(a, b) < 1e-12);
  }
  // Any other count takes the bounded kernels by itself.
  const auto beam = hinged_beam(7);
  int kernel = 0;
  swing(beam, 7, false, &kernel);
  CHECK(kernel == Eigen::Dynamic);
}

TEST_CASE("runtime model: a mode count the data lacks is an error naming the body") {
  const auto beam = hinged_beam(2);
  ModelBuilder<double> b;
  b.add_flexible_body("boom", beam.data, beam.data.num_modes + 1);
  auto m = b.finalize();
  REQUIRE_FALSE(m.ok());
  CHECK(m.error().what().find("body 'boom'") != std::string::npos);
}

TEST_CASE("runtime model: a set's outputs by index are its rows times the modal coordinates") {
  const auto beam = hinged_beam(4);
  ModelBuilder<double> b;
  const BodyId body = add_hinged(b, beam, 4);
  Eigen::MatrixXd rows(3, 4);
  rows << 1, 2, 3, 4, -5, 6, -7, 8, 0.5, 0, 0, -0.25;
  const OutputRange set = b.add_stress_outputs("rows", body, rows);
  const OutputRange other = b.add_stress_outputs("other", body, rows.topRows(1));
  CHECK(set.size() == 3);
  CHECK_FALSE(set[3].valid());
  CHECK_FALSE(set[-1].valid());
  CHECK(other[0] != set[0]);
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  REQUIRE(initialize(*m, d).ok());
  for (int i = 0; i < 50; ++i) REQUIRE(step(*m, d) == StepStatus::ok);
  REQUIRE(evaluate_outputs(*m, d) == StepStatus::ok);
  const Eigen::VectorXd p = modal_coordinates(*m, d, body);
  CHECK(p.norm() > 0);  // the beam bends under its weight
  for (int k = 0; k < set.size(); ++k)
    CHECK(output_value(d, set[k]) == doctest::Approx(rows.row(k).dot(p)).epsilon(1e-14));
  CHECK(output_value(d, other[0]) == doctest::Approx(rows.row(0).dot(p)).epsilon(1e-14));

  // A meter on a row the set does not have is refused, naming the meter.
  ModelBuilder<double> bad;
  const BodyId bad_body = bad.add_flexible_body("beam", beam.data, 4);
  const OutputRange bad_set = bad.add_stress_outputs("rows", bad_body, rows);
  bad.add_damage_meter("gauge", bad_set[3], fat100_meter(1.0));
  auto refused = bad.finalize();
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().what().find("meter 'gauge'") != std::string::npos);
}

TEST_CASE("runtime model: a meter counts the samples outside its window; a checkpoint keeps it") {
  const auto beam = hinged_beam(4);
  ModelBuilder<double> b;
  const BodyId body = add_hinged(b, beam, 4);
  const OutputRange modal_sum =
      b.add_stress_outputs("sum of modes", body, Eigen::MatrixXd::Ones(1, 4));
  constexpr double kNarrow = 1e-12;
  const MeterId wide = b.add_damage_meter("wide", modal_sum[0], fat100_meter(1.0));
  const MeterId narrow = b.add_damage_meter("narrow", modal_sum[0], fat100_meter(kNarrow));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m), resumed(*m);
  REQUIRE(initialize(*m, d).ok());
  std::vector<unsigned char> saved;
  long outside = 0, refused_steps = 0;
  std::string first_refusal;
  for (int i = 0; i < 60; ++i) {
    REQUIRE(step(*m, d) == StepStatus::ok);
    const StepStatus s = evaluate_outputs(*m, d);
    // The grid's window is the class edges: a sample beyond +-kNarrow is outside it.
    outside += std::abs(output_value(d, modal_sum[0])) > kNarrow ? 1 : 0;
    refused_steps += s == StepStatus::capacity_exceeded ? 1 : 0;
    if (s != StepStatus::ok && first_refusal.empty()) first_refusal = d.message.data();
    if (i == 29) {
      auto bytes = save_checkpoint(*m, d);
      REQUIRE(bytes.ok());
      saved = std::move(*bytes);
    }
  }
  CHECK(outside > 30);  // the beam bends under its weight within the first steps
  CHECK(meter_refused_samples(d, narrow) == outside);
  CHECK(refused_steps == outside);  // evaluate_outputs said so at each of them
  CHECK(meter_refused_samples(d, wide) == 0);
  MESSAGE(first_refusal);  // names the meter, the sample and the window
  CHECK(first_refusal.find("meter 'narrow'") != std::string::npos);
  CHECK(first_refusal.find("outside its class window") != std::string::npos);
  REQUIRE(restore_checkpoint(*m, resumed, saved.data(), saved.size(), "at step 30").ok());
  for (int i = 30; i < 60; ++i) {
    REQUIRE(step(*m, resumed) == StepStatus::ok);
    evaluate_outputs(*m, resumed);
  }
  CHECK(meter_refused_samples(resumed, narrow) == meter_refused_samples(d, narrow));
  CHECK(meter_damage(resumed, wide) == meter_damage(d, wide));
  // A read-out of a Data seen as const (a viewer thread's copy, a report): the same figure.
  const Data<double>& view = d;
  CHECK(meter_damage(view, wide) == meter_damage(d, wide));
}

TEST_CASE("runtime model: initialize turns a flexible body to meet a driver's law, not bends it") {
  // A driver whose law starts at 0.5 rad on a beam lying at 0 rad: the one assembly without
  // strain is the beam turned rigidly by 0.5 rad about the hinge.
  const auto beam = hinged_beam(4);
  ModelBuilder<double> b;
  const auto [body, pivot, root] = add_hinge(b, beam, 4);
  const MarkerId tip = b.add_marker("tip", body, beam.line.nodes.back());
  constexpr double kAngle = 0.5;
  b.add_driver("drive", JointKind::revolute_driver, pivot, root,
               MotionLaw<double>::constant_acceleration(kAngle));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  REQUIRE(initialize(*m, d).ok());
  const Vector3d x = marker_frame(*m, d, root).axes.col(0);
  MESSAGE("root axis at " << std::atan2(x.y(), x.x()) << " rad, modal coordinates |p| "
                          << modal_coordinates(*m, d, body).norm() << ", elastic energy "
                          << energy(*m, d).elastic << " J");
  CHECK(std::atan2(x.y(), x.x()) == doctest::Approx(kAngle).epsilon(1e-9));
  CHECK(energy(*m, d).elastic < 1e-9);
  const Vector3d at = marker_frame(*m, d, tip).origin;
  CHECK(at.x() == doctest::Approx(kLength * std::cos(kAngle)).epsilon(1e-9));
  CHECK(at.y() == doctest::Approx(kLength * std::sin(kAngle)).epsilon(1e-9));
}

TEST_CASE("runtime model: a driver's law that turns NaN stops the step naming the joint") {
  // A callback law (a controller, say) that returns NaN from t = 5 ms on.
  const auto beam = hinged_beam(4);
  ModelBuilder<double> b;
  const HingedParts hinge = add_hinge(b, beam, 4);
  b.add_driver("drive", JointKind::revolute_driver, hinge.pivot, hinge.root,
               MotionLaw<double>::from_callback(
                   [](double t, double* out, void*) {
                     out[0] = t < 0.005 ? 0.1 * t : std::nan("");
                     out[1] = 0.1;
                     out[2] = 0.0;
                   },
                   nullptr));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  REQUIRE(initialize(*m, d).ok());
  StepStatus status = StepStatus::ok;
  int steps = 0;
  while (status == StepStatus::ok && steps < 20) {
    status = step(*m, d);
    steps += status == StepStatus::ok ? 1 : 0;
  }
  const std::string why = std::string(to_string(status)) + ": " + d.message.data();
  MESSAGE(why);
  CHECK(status == StepStatus::invalid_input);
  CHECK(steps == 4);  // t = 1 .. 4 ms passed; the step to 5 ms reads the NaN
  CHECK(std::string(d.message.data()).find("joint 'drive'") != std::string::npos);
  CHECK(std::string(d.message.data()).find("not finite") != std::string::npos);
  CHECK(d.q.allFinite());  // the failed step left the state as it was
}

}  // namespace test_model_flexible
