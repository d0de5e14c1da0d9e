// The paper's crane (examples/crane; docs/crane.md) on the runtime model: the 10-mode boom with
// its 100 kg payload, the cylinder and its rod, the cylinder's stroke driven through the
// synthetic 11 s work cycle (lift 0.2 m, hold with two corrections, lower). Without the welded
// detail's sub-model (examples/crane/crane_precompute.cpp), which the test targets do not compile.
#pragma once

#include <utility>
#include <vector>

#include <flexstress/model/all.hpp>

#include "../../examples/crane/boom_reduction.hpp"
#include "../../examples/crane/crane_model_impl.hpp"

namespace flexstress::testing {

struct DrivenCrane {
  Model<double> model;
  crane::assembly::Parts parts;
  JointId stroke;        ///< the cylinder's driver
  MarkerId hinge, tip;   ///< the boom at its hinge A and at its tip
  double cycle_end = 0;  ///< the work cycle's last time (s)
};

inline Result<DrivenCrane> make_driven_crane() {
  const crane::CraneSpec spec;
  const auto boom = crane::make_boom(spec, 10);
  if (!boom) return boom.error();
  ModelBuilder<double> b;
  DrivenCrane c;
  if (Status st = crane::assembly::add_crane_parts(b, spec, *boom, crane::CraneOptions{}, c.parts);
      !st)
    return st.error();
  std::vector<double> t, stroke;
  crane::synthetic_cycle(t, stroke);
  for (double& s : stroke) s += (spec.b - spec.c).norm();
  auto law = TableLaw<double>::create(t, stroke);
  if (!law) return law.error();
  c.stroke = b.add_driver("stroke", JointKind::prismatic_driver, c.parts.cylinder_origin,
                          c.parts.rod_origin, MotionLaw<double>::from_table(std::move(*law)));
  c.hinge = b.add_marker("boom at A", c.parts.boom, boom->node_a);
  c.tip = b.add_marker("boom tip", c.parts.boom, boom->line.nodes.back());
  c.cycle_end = t.back();
  auto m = b.finalize();
  if (!m) return m.error();
  c.model = std::move(*m);
  return c;
}

}  // namespace flexstress::testing
