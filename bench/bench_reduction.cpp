// Cost of the reduction precompute and of loading its result (Google Benchmark; build Release).
//   beam_reduce/<modes>     the crane boom's beam model (RHS 150x100x4, 4.5 m, 20 elements),
//                           Craig-Bampton with both ends as interface, n fixed-interface modes
//   brick_reduce/<density>  the RHS segment with its welded rib (the crane's sub-model mesh) as
//                           a flexible body: rigid (RBE2) spiders on both end sections,
//                           Craig-Bampton with 4 fixed-interface modes (16 deformation modes)
//   save / load             the brick body's modal data to and from memory (the file format of
//                           reduction/modal_body_io.hpp)
//
// Run: ./build/bench/bench_reduction
#include <optional>

#include <benchmark/benchmark.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/reduction/interface.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_body_io.hpp>

using namespace flexstress;
using namespace flexstress::reduction;

namespace {

void beam_reduce(benchmark::State& bench) {
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(4.5, 0, 0);
  spec.num_elements = 20;
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(fe::rectangular_hollow_section(0.150, 0.100, 0.004));
  const auto line = fe::add_beam_line(mesh, spec);
  ReductionSpec rs;
  rs.interface = {{line.node_at(0.0)}, {line.node_at(4.5)}};
  rs.dynamic_modes.count = static_cast<Index>(bench.range(0));
  for (auto _ : bench) {
    auto d = reduce(mesh, rs);
    if (!d) return bench.SkipWithError(d.error().what().c_str());
    benchmark::DoNotOptimize(d->eigenvalues.data());
  }
}

// The detail mesh with spiders on its end sections, and the spec that reduces it.
struct BrickBody {
  fe::Mesh mesh;
  ReductionSpec spec;
  Index dofs = 0;
  bool ok = false;
  explicit BrickBody(double density) {
    fe::RhsAttachmentSpec rspec;
    rspec.density = density;
    auto detail = fe::make_rhs_attachment_mesh(rspec);
    if (!detail) return;
    mesh = detail->mesh;
    const Index a = add_rigid_spider(mesh, detail->end_section_x0);
    const Index b = add_rigid_spider(mesh, detail->end_section_x1);
    spec.interface = {{a}, {b}};
    spec.dynamic_modes.count = 4;
    dofs = 3 * mesh.num_nodes();
    ok = true;
  }
};

void brick_reduce(benchmark::State& bench) {
  const BrickBody body(static_cast<double>(bench.range(0)) / 10.0);
  if (!body.ok) return bench.SkipWithError("mesh generation failed");
  for (auto _ : bench) {
    auto d = reduce(body.mesh, body.spec);
    if (!d) return bench.SkipWithError(d.error().what().c_str());
    benchmark::DoNotOptimize(d->eigenvalues.data());
  }
  bench.counters["bricks"] = static_cast<double>(body.mesh.hexes().size());
  bench.counters["dofs"] = static_cast<double>(body.dofs);
}

std::optional<ModalBodyData> brick_data() {
  const BrickBody body(1.0);
  if (!body.ok) return std::nullopt;
  auto d = reduce(body.mesh, body.spec);
  if (!d) return std::nullopt;
  return std::move(*d);
}

void save(benchmark::State& bench) {
  const auto d = brick_data();
  if (!d) return bench.SkipWithError("reduction failed");
  std::size_t bytes = 0;
  for (auto _ : bench) {
    auto image = serialize(*d);
    bytes = image->size();
    benchmark::DoNotOptimize(image->data());
  }
  bench.counters["bytes"] = static_cast<double>(bytes);
}

void load(benchmark::State& bench) {
  const auto d = brick_data();
  if (!d) return bench.SkipWithError("reduction failed");
  const auto image = *serialize(*d);
  for (auto _ : bench) {
    auto back = deserialize(image.data(), image.size());
    if (!back) return bench.SkipWithError(back.error().what().c_str());
    benchmark::DoNotOptimize(back->eigenvalues.data());
  }
}

}  // namespace

BENCHMARK(beam_reduce)->Arg(4)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(brick_reduce)->Arg(6)->Arg(10)->Unit(benchmark::kMillisecond);
BENCHMARK(save)->Unit(benchmark::kMillisecond);
BENCHMARK(load)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
