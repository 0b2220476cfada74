#include "core/model/avoidance.h"

#include "core/util/numbers.h"

namespace disco {

void add_avoidance(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.model_scene();
  L.for_each_gap_state([&](int t, int p) {
    if (s.pairs[p].mode == PairMode::kAvoid)
      P.set_variable_bounds(L.gap_index(p, t), s.pairs[p].safe_distance, kInf);
  });
}

}  // namespace disco
