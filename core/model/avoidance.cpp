#include "core/model/avoidance.h"

#include "core/util/numbers.h"

namespace disco {

void add_avoidance(Layout& L, PolynomialProgram& P) {
  L.for_each_gap_state([&](int t, int p) {
    if (L.pair_mode(p) == PairMode::kAvoid)
      P.set_variable_bounds(L.gap_index(p, t), L.pair(p).safe_distance, kInf);
  });
}

}  // namespace disco
