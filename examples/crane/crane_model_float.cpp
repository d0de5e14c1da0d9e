// The crane's assembly for float: the accuracy study's single-precision runs.
#include "crane_model_impl.hpp"

namespace crane {
template Result<BasicCrane<float>> make_crane<float>(const CraneSpec&, const CraneOptions&,
                                                     const std::vector<double>&,
                                                     const std::vector<double>&);
}  // namespace crane
