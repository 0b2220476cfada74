// Same scene, same settings -> the same answer, bit for bit, solve after solve.
//
// Guards the MUMPS ordering choice in configs/disco.yaml: with
// mumps_pivot_order 7 (automatic) MUMPS may order the KKT matrix with SCOTCH
// or METIS, which use pseudo-random numbers, and on this contact scene two
// solves in one process then differed at roundoff from Ipopt iteration 39 on
// (59 vs 58 iterations, different points). Multi-start search relies on
// reproducible runs (same seed, same best T_f for 1 and 2 ranks).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "search/solve_scene.h"

namespace disco {
namespace {

TEST(Determinism, RepeatedContactSolvesAreBitwiseIdentical) {
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("reduction.max_solves=0");  // the feasibility phase suffices
  const Scene scene = load_scene(
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/three_robots_contact.yaml");
  const SceneSolve first = solve_scene(scene, settings);
  ASSERT_TRUE(first.solved());
  for (int k = 1; k <= 2; ++k) {
    const SceneSolve again = solve_scene(scene, settings);
    ASSERT_TRUE(again.solved());
    EXPECT_EQ(again.info.iterations, first.info.iterations) << "repeat " << k;
    ASSERT_EQ(again.z.size(), first.z.size());
    EXPECT_EQ(std::memcmp(again.z.data(), first.z.data(), sizeof(double) * first.z.size()), 0)
        << "repeat " << k << " differs";
  }
}

}  // namespace
}  // namespace disco
