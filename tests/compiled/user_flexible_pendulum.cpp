// A user program of the runtime model, compiled against flexstress::compiled (the model layer's
// templates declared extern, so this unit only parses them): a flexible beam hinged at one end,
// loaded from a modal body file (tests/c_api/make_pendulum_files.cpp), released under gravity
// and stepped 1000 times. Also the unit whose compile time the compiled library is measured
// on: built header-only (without FLEXSTRESS_COMPILED) it instantiates the whole model layer.
#include <cmath>
#include <cstdio>

#include <flexstress/model/all.hpp>
#include <flexstress/reduction/modal_body_io.hpp>

int main(int argc, char** argv) {
  using namespace flexstress;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s beam.fsmodal\n", argv[0]);
    return 2;
  }
  auto data = reduction::load_modal_body(argv[1]);
  if (!data) {
    std::fprintf(stderr, "%s\n", data.error().what().c_str());
    return 1;
  }
  ModelBuilder<double> b;
  const BodyId beam = b.add_flexible_body("beam", *data, 10);
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1);
  const MarkerId root = b.add_marker("root", beam, 0);
  b.add_joint("hinge", JointKind::revolute, pivot, root);
  b.set_gravity(Vector3d(0, -9.81, 0));
  b.settings().step = 1e-3;
  auto model = b.finalize();
  if (!model) {
    std::fprintf(stderr, "%s\n", model.error().what().c_str());
    return 1;
  }
  Data<double> d(*model);
  if (!initialize(*model, d).ok()) return 1;
  const double e0 = energy(*model, d).total();
  for (int i = 0; i < 1000; ++i)
    if (step(*model, d) != StepStatus::ok) {
      std::fprintf(stderr, "step %d failed: %s\n", i, d.message.data());
      return 1;
    }
  const double e1 = energy(*model, d).total();
  const Vec3<double> tip = body_position(*model, d, beam);
  std::printf("t = %.3f s, frame at (%.4f, %.4f), energy %.6g -> %.6g J, %ld iterations\n",
              double(d.t), tip.x(), tip.y(), e0, e1, d.statistics.iterations);
  // The hinge does no work: the energy stays within 0.1 % of the swing's potential m g L / 2.
  return std::abs(e1 - e0) <= 1e-3 * data->mass() * 9.81 * 1.0 ? 0 : 1;
}
