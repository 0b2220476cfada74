#include "core/model/avoidance.h"

#include "core/util/numbers.h"

namespace disco {

void add_avoidance(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.scene();
  for (int p = 0; p < static_cast<int>(s.pairs.size()); ++p) {
    if (s.pairs[p].mode != PairMode::kAvoid) continue;
    for (int t = 1; t <= L.steps(); ++t)
      P.set_variable_bounds(L.gap_index(p, t), s.pairs[p].safe_distance, kInf);
  }
}

}  // namespace disco
