// disco — one start of the multi-start search: an initial guess, an
// objective-reduction schedule and elastic-mode settings, generated
// deterministically from (scene, seed, start index).
//
// Start 0 of every scene is the plain one: the straight-line guess with the
// settings file's schedule (exactly what `disco solve` runs). Later starts
// cycle through the guess kinds and draw their parameters from a generator
// seeded by (seed, scene name, index), so the same (scene, seed, index) gives
// the same start on any rank, in any run.
//
// The guess of each kind is made in search/guess.h (make_guess). A kPerturbedFeasible
// start runs the feasibility phase from the smoothstep guess, then re-solves it once
// from a perturbation of the feasible point (reduce_objective's PerturbFunction, step 1b
// in objective_reduction.h); the reduction continues from that point if it is
// certified, else from the feasible point itself.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/elastic/elastic_solver.h"
#include "core/model/robot_problem.h"
#include "search/objective_reduction.h"

namespace disco {

enum class GuessKind {
  kStraight,   // smoothstep straight lines; a robot too weak for the smoothstep moves on
               // its own bang-bang timing (search/guess.h, straight_guess)
  kPerturbed,  // straight lines with random lateral and along-path perturbations
  kDetour,     // robots whose straight paths cross pass each other on one side
  kPerturbedFeasible,  // straight lines, then the feasible point re-timed and re-solved
  kYield,      // straight lines; in a random priority order, robots wait until the way is clear
  kGiven,      // a given trajectory (StartSpec::given): `--guess FILE`, or the coarse answer of
               // a coarse-to-fine start (search/solve_scene.h)
};
// "straight", "perturbed", "detour", "perturbed feasible", "yield", "given"
std::string to_string(GuessKind kind);
// The kind named by `text` (as to_string gives it); std::invalid_argument otherwise.
GuessKind guess_kind_from_string(const std::string& text);

// paths[i][t]: the pose of robot i at state t = 0..N, SI units (metres, radians).
using Paths = std::vector<std::vector<Pose>>;

// A trajectory to start from (search/trajectory.h): the robots' paths at the scene's N steps
// and the horizon they were found at.
struct Trajectory {
  Paths paths;
  double seconds = 0.0;  // its T_f, s
  std::string source;    // where it came from, for messages: the file, or "coarse N_t = 20"
  bool empty() const { return paths.empty(); }
};

struct StartSpec {
  int index = 0;
  std::uint64_t seed = 0;
  GuessKind guess = GuessKind::kStraight;
  int detour_side = 0;            // kDetour: +1 every pair left, -1 every pair right, 0 mixed
  std::uint64_t detour_pattern = 0;  // kDetour: bit k set: conflicting pair k on the right
                                     // (search/guess.h, detour_paths)
  int detour_pairs = 0;              // kDetour: the scene's conflicting pairs
  double perturbation = 0.0;      // kPerturbed: relative amplitude; kPerturbedFeasible: of the warp
  double T_scale = 1.0;           // kPerturbedFeasible: re-solve horizon / feasible horizon
  double margin = 1.0;            // kYield: clearance multiple kept from higher-priority robots
  std::vector<int> yield_order;   // kYield: the robots, highest priority first (empty: drawn at
                                  // random from stream 1, search/guess.h)
  bool meet_turners = false;      // a robot that must turn and touches nothing meets a partner
                                  // in the guess (search/guess.h, "Turners"): set by make_start
                                  // where the scene has such a robot
  Trajectory given;               // kGiven: the trajectory; the first feasibility horizon is
                                  // (1 + feasibility.guess_slack) times its T_f
  ReductionSettings schedule;     // feasibility horizon factor, reduction rate, grow, shrink, ...
  ElasticSettings elastic;        // zeta, formulation, ...
  std::string describe() const;   // one line, for runs.jsonl and reports
  // {horizon_factor, rate, grow, shrink, min_rate, zeta}: the schedule that varies by start;
  // minimize_weak: `penalty` or `homotopy` (schedule.weak_homotopy).
  nlohmann::json schedule_json() const;
};

// `start` with its guess replaced by `trajectory` (kind kGiven); its schedule stays.
StartSpec with_guess(StartSpec start, Trajectory trajectory);

// Detour starts enumerate every side pattern of a scene with at most this many conflicting
// pairs (2^k patterns: all left, all right, then the mixed ones); with more, the mixed
// patterns are drawn (stream 2 of the start's generator).
inline constexpr int kEnumeratedPairs = 3;

// The priority order of the scene's m-th yield start (m = 0, 1, ...), for a scene with at
// most kEnumeratedPairs conflicting pairs: who goes first in each conflicting pair, pattern
// by pattern (bit p set: the second robot of pair p first) as detour starts take their
// sides, skipping the patterns no order can give (a cycle), cyclically; robots ordered by
// those precedences, ties to the lower index. Empty with more pairs (the order is drawn) or
// none.
std::vector<int> yield_order(const Scene& scene, int m);

// The start `index` for `scene` under `seed`, varying the given base settings.
StartSpec make_start(const Scene& scene, std::uint64_t seed, int index,
                     const ReductionSettings& base_schedule, const ElasticSettings& base_elastic);

// The generator of start `index` of `scene` under `seed`: a std::mt19937_64 (fully
// specified by the standard) seeded with FNV-1a over (seed, scene name, index, stream).
// Stream 0 draws the start's parameters (make_start), stream 1 the shape of its guess
// (search/guess.h).
std::mt19937_64 start_generator(std::uint64_t seed, const std::string& scene, int index,
                                std::uint64_t stream);
// Uniform in [0, 1) from the generator's top 53 bits, and in [lo, hi): made here, not by
// std::uniform_real_distribution (implementation-defined), so a start is the same with any
// standard library.
double uniform01(std::mt19937_64& g);
double uniform(std::mt19937_64& g, double lo, double hi);

}  // namespace disco
