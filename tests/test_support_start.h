// disco tests — finding a start of a given kind (search/start.h).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>

#include "search/start.h"

namespace disco::start_test {

// The first start index >= 1 of `kind` (and detour side) for `scene` under
// `seed`, varying the given base settings; a test failure if none of the
// first 50 is.
inline StartSpec first_start_of(const Scene& scene, std::uint64_t seed, GuessKind kind, int side,
                                const ReductionSettings& schedule, const ElasticSettings& elastic) {
  for (int index = 1; index < 50; ++index) {
    StartSpec s = make_start(scene, seed, index, schedule, elastic);
    if (s.guess == kind && s.detour_side == side) return s;
  }
  ADD_FAILURE() << "no start of kind " << to_string(kind) << " side " << side;
  return {};
}

}  // namespace disco::start_test
