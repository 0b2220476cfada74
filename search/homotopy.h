// disco — the homotopy class of a trajectory: which way around each other the robots go.
//
// Starts that end in the same local optimum mostly share its class; the search uses classes
// to say what it has explored (runs.jsonl, the report) and to try unexplored ones first
// (search/task_queue.h, search.defer_seen_classes).
//
// Per pair (i, j) of the scene that comes within reach (its centres come within kReach
// times the pair's clearance, R_i + R_j (+ d_s for an avoid pair; core/model/gap.h), at some
// state of the paths) or goes around each other (a turn of d of at least kTurn, below, at
// any distance: a wide detour still passes on one side). With d(t) = p_j(t) - p_i(t), the
// pair's
//   turn   the total angle d turns through over the paths (the sum of the wrapped angle
//          changes between consecutive states): "ccw" if it is at least kTurn, "cw" if at
//          most -kTurn, "none" between (the robots come near but do not go around each
//          other), "?" if d passes through a centre distance below half the clearance
//          (paths that run through each other, as straight guesses of crossing robots do:
//          the guess does not decide the side);
//   first  at the state of closest approach, the robot farther along its own path (the share
//          of its path length covered), if the shares differ by more than kOrder; none
//          otherwise (a head-on swap passes at the same share);
//   touch  contact pairs only: the centre distance reaches the clearance within kTouch
//          times it (the robots push or rub).
// For crossing paths the turn and the order say the same (who goes first decides which way
// d turns); for a swap only the turn does. The class's key lists the pairs in the scene's
// order, "a/b ccw, a first, touch; b/c cw", and is "" for a scene with no pair within reach.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/scene.h"
#include "search/start.h"

namespace disco {

inline constexpr double kReach = 2.0;    // within reach: centre distance < kReach * clearance
inline constexpr double kTurn = 1.5708;  // rad (90 degrees): a pair went around
inline constexpr double kOrder = 0.1;    // shares of path that make one robot first
inline constexpr double kTouch = 1e-3;   // relative: touching

struct PairClass {
  int i = 0, j = 0;       // robot indices, as in the scene's pair
  std::string turn;       // "ccw", "cw", "none" or "?"
  int first = -1;         // the robot index that passes first; -1: neither
  bool touch = false;
};

struct HomotopyClass {
  std::vector<PairClass> pairs;  // the pairs within reach, in the scene's order
  // Every pair's turn is decided (no "?").
  bool decided() const;
  std::string key(const Scene& scene) const;
  nlohmann::json to_json(const Scene& scene) const;  // {"key", "pairs": [{pair, turn, first, touch}]}
};

// The class of `paths` (one per robot, N + 1 poses, SI) in `scene`.
HomotopyClass homotopy_class(const Scene& scene, const Paths& paths);

}  // namespace disco
