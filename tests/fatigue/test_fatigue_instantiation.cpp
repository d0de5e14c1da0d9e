// Every class template of the fatigue layer explicitly instantiated for float and double, so
// member functions no other test calls still compile (and keep compiling) for both Scalars.
#include <doctest/doctest.h>

#include <flexstress/fatigue/class_grid.hpp>
#include <flexstress/fatigue/cycle.hpp>
#include <flexstress/fatigue/cycle_matrix.hpp>
#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/mean_stress.hpp>
#include <flexstress/fatigue/multiaxial.hpp>
#include <flexstress/fatigue/rainflow.hpp>
#include <flexstress/fatigue/reversals.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/fatigue/streaming_rainflow.hpp>
#include <flexstress/fatigue/weld_line.hpp>

namespace flexstress::fatigue {
template struct Cycle<float>;
template struct Cycle<double>;
template class ReversalFilter<float>;
template class ReversalFilter<double>;
template class ReversalFilter<int>;
template class ClassGrid<float>;
template class ClassGrid<double>;
template class Bins<float>;
template class Bins<double>;
template class RangeMeanMatrix<float>;
template class RangeMeanMatrix<double>;
template class FromToMatrix<float>;
template class FromToMatrix<double>;
template class SnCurve<float>;
template class SnCurve<double>;
template class KahanSum<float>;
template class KahanSum<double>;
template class DamageModel<float>;
template class DamageModel<double>;
template class StreamingRainflow<float, 2>;
template class StreamingRainflow<double, 4096>;
template class StreamingDamage<float, 64>;
template class StreamingDamage<double, 256>;
template class StreamingWeldLine<float, 32>;
template class StreamingWeldLine<double, 128>;
template struct InteractionCheck<float>;
template struct InteractionCheck<double>;
}  // namespace flexstress::fatigue

namespace test_fatigue_instantiation {

TEST_CASE("fatigue templates instantiate for float and double") {
  CHECK(flexstress::fatigue::StreamingRainflow<float, 2>::residue_capacity == 4);
  CHECK(flexstress::fatigue::SnCurve<double>::max_segments == 4);
}

}  // namespace test_fatigue_instantiation
