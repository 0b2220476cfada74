// disco — a mathematical program with complementarity constraints (MPCC).
//
//     minimize    f(z)
//     subject to  c_lo <= c(z) <= c_hi,   z_lo <= z <= z_hi,
//                 0 <= G_i(z)  _|_  H_i(z) >= 0,       i = 1..p
//
// i.e. G_i >= 0, H_i >= 0 and G_i * H_i = 0 for every pair. Each side of a pair
// is either a variable z_k or a constraint row c_r(z) of the underlying Nlp (so
// it inherits the Nlp's exact first and second derivatives). A row used as a
// side usually has free bounds; bounds it does have still apply. The sides'
// own nonnegativity is implied by the pair and need not be in the bounds.
//
// This layer knows nothing about robots: anything that can state its problem
// this way can be solved by the elastic mode (core/elastic/elastic_solver.h).
#pragma once

#include <vector>

#include "core/nlp/nlp.h"

namespace disco {

struct ComplementaritySide {
  enum class Kind { kVariable, kRow };
  Kind kind = Kind::kVariable;
  int index = 0;  // variable index or constraint-row index

  static ComplementaritySide variable(int k) { return {Kind::kVariable, k}; }
  static ComplementaritySide row(int r) { return {Kind::kRow, r}; }
};

struct ComplementarityPair {
  ComplementaritySide g, h;
};

class Mpcc : public Nlp {
 public:
  const std::vector<ComplementarityPair>& complementarity_pairs() const { return pairs_; }
  int num_complementarity_pairs() const { return static_cast<int>(pairs_.size()); }

 protected:
  std::vector<ComplementarityPair> pairs_;
};

// The value of a side at z, given c(z).
inline double side_value(const ComplementaritySide& s, const ConstVectorRef& z,
                         const ConstVectorRef& c) {
  return s.kind == ComplementaritySide::Kind::kVariable ? z[s.index] : c[s.index];
}

}  // namespace disco
