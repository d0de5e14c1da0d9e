// The crane's run with 10 boom modes (crane_run.hpp), in its own unit.
#include "crane_operators.hpp"
#include "crane_run.hpp"
#include "crane_session_impl.hpp"  // the session behind the C interface (c_api/)
#include "game_loop.hpp"

template int crane::run<10, crane::fixed_storage_limit>(const crane::RunOptions&);
// The stroke-driven crane the hydraulic one starts from (run_hydraulic_10.cpp uses this one).
template crane::Result<crane::Crane<10, crane::fixed_storage_limit, double, crane::CraneEffects>>
crane::make_stroke_crane<10, crane::fixed_storage_limit, double, crane::CraneEffects>(
    const crane::CraneSpec&, const std::vector<double>&, const std::vector<double>&);
// The batch of operators (--operators) is built for the 10-mode crane.
template int crane::run_operators<10, crane::fixed_storage_limit>(const crane::RunOptions&, int,
                                                                  int, unsigned);
// The game loop (--game-loop) is built for the 10-mode crane.
template int crane::run_game_loop<10, crane::fixed_storage_limit>(const crane::RunOptions&, double,
                                                                  bool);
