// The crane's assembly for double: the crane program and the benchmarks.
#include "crane_model_impl.hpp"

namespace crane {
template Result<BasicCrane<double>> make_crane<double>(const CraneSpec&, const CraneOptions&,
                                                       const std::vector<double>&,
                                                       const std::vector<double>&);
}  // namespace crane
