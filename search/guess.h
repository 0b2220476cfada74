// disco — initial guesses: a position path for every robot, completed into a point of
// the model.
//
// Every guess of disco is made here. A guess is a set of position paths, one Pose
// (x, y, phi) per robot and state t = 0..N in SI units, made from the robots' straight
// moves (straight_move: from the start pose to the target pose, core/model/bounds.h) by a
// timing along the move and offsets across it; complete_guess() turns paths into a full
// point of the model. The guess kinds of the search's starts (search/start.h) are:
//
//   straight            smoothstep_guess(): every robot on w(tau) = tau^2 (3 - 2 tau),
//                       tau = t / N; straight_guess() (start 0, what `disco solve` runs)
//                       gives a robot too weak for the smoothstep its own timing (below);
//   detour              detour_paths(): conflicting robots pass each other on one side;
//   yield               yield_paths(): robots in a random priority order wait until the
//                       way is clear;
//   perturbed           perturbed_paths(): random lateral and timing perturbations;
//   perturbed feasible  the smoothstep guess, then (step 1b of
//                       search/objective_reduction.h) the feasible point's own paths
//                       re-timed (retimed_paths) and re-solved;
//   given               a trajectory's paths (search/trajectory.h: `--guess FILE`, or the
//                       coarse answer of a coarse-to-fine start), at any horizon.
//
// Obstacles. A robot's move runs along its way around the fixed obstacles
// (way_around_obstacles): the straight segment where it keeps each obstacle's clearance
// (R_i + R_o, + d_s for an avoid pair; core/model/obstacles.h), else the shortest polyline
// through corners kWayMargin times the clearance from the obstacles (8 around a post, 5
// around each end of a wall) whose legs all keep it. Timings and offsets below apply along
// the way as along the straight move. Once no step could cross a wall (core/model/
// swept.h), the doorway's (configs/scenarios/doorway.yaml) first feasibility solve from the
// straight guess through its wall took 897, 126, 1,150 and 1,554 iterations at 20, 30, 40
// and 50 steps; along the way round 287, 176, 89 and 214 (without swept rows, from the
// straight guess: 228, 258, 168, 202). A robot closed in (no way round) and one driven
// along one axis (force_dims 1) keep the straight move; moving obstacles are not avoided.
//
// Paths. Every offset added here vanishes at t = 0 and t = N, and the point at t = N is
// the target pose exactly. A robot with force_dims 1 cannot push sideways: its offsets
// are projected on its force axis (only its timing along the axis changes).
//
// Pushers. Every guess sends each robot with no position target (x and y free) that has a
// contact pair with a moving object (Robot::object whose target moves it) to push the
// nearest such object: the m-th of an object's k pushers heads straight for its contact
// point behind the object (touching it, at angle (m - (k - 1) / 2) pi / 4 from the side
// opposite the object's move) while the object waits, then moves with the object, touching
// it; the share of the horizon spent on the way there is the longest way over (that way +
// the object's move), at most a half. An object without pushers follows its own path as a
// robot would. On scenarios/push_coin_line.yaml this guess took `disco solve` to 1.923142
// (closed form 1.922751) in 737 iterations, where the straight guess (the finger standing
// still) ended at a local optimum 2.378989 after 2,756. Objects left without a pusher (more
// moving objects than pushers) join the queue of a lone pusher, which pushes them one
// after the other (push_the_rest in guess.cpp: to the point straight behind the next
// object, then with it to its target). On scenarios/push_two_coins.yaml the start 0 guess
// with the second coin moving on its own found no feasible point (and neither did six
// starts of a search, 2 ranks); with the queue `disco solve` reached 3.215824 s. An object
// that still has no pusher (every robot of its contact pairs has a position target) is
// taken on the way by the robot with a position target whose way it lengthens least (the
// way to the contact point behind it, its move and the way from there to the robot's
// target, less the robot's straight way), which pushes it as a lone pusher does and then
// goes to its own target (push_the_rest); the first horizon then covers its way
// (pushers_way_time, below). Before, such an object followed its own path as a robot would,
// and start 0 seldom found a feasible point: on 15 random scenes of one coin and 1-3 robots
// that all have targets (`scripts/bench_random --kind objects --count 16 --time-limit 60
// --baseline <disco of 9247f36>`, section `default (partial: ...)` of
// scripts/results/bench_random.md) a certified point on 6, against 13 now; of the 6, 3 ended
// lower by more than 1e-3 now and 2 higher (+12 % and +13 %: one start's local optimum). On
// scenarios/push_coin_and_park.yaml none before, 1.978341 s now (tests: GuessPushers,
// guess.push_and_park). Scenes with a pusher free of a target, and scenes without objects,
// get the same guesses and horizons as before, bit for bit (the 18-start set of bench_starts
// and the four other coin scenes of scenarios/, checked).
//
// Turners. A robot turns only by contact: its force acts at its centre and the floor's only
// torque is a damping (core/model/reachability.h). A robot whose target phi excludes its start
// phi, that no conflict (below) of a contact pair brings into contact (a conflict of an avoid
// pair keeps it apart) and that pushes no object, would follow a
// path that touches nothing, and from such guesses the feasibility solves fail: on
// random_mixed_3_8 (`scripts/bench_random --kind mixed --seed 3`, a robot to turn by 0.958 rad
// whose straight path stays 3.2 m from the other robot's) no start found a feasible point.
// So the guess of a start with StartSpec::meet_turners (start 0, and starts 1, 2, 5, 6, 9, 10,
// ... of a scene with such a robot: search/start.h) moves such a robot i and its partner j (a
// robot with a contact pair with i; of those, the one whose straight path, timed alike,
// comes closest to i's) each half their closest approach's excess over the pair's clearance
// towards the other, with the detour's bump peaking at that approach (meetings(), below):
// they touch there and can rub. A turner whose contact pairs are all with objects (robots
// in avoid pairs, say) meets the closest object the same way, moving the whole excess itself
// (the object keeps its path); one with no contact pair with any disk meets the closest
// fixed contact obstacle the same way (its nearest point to the straight path). The other
// starts keep the paths that touch nothing, whose optima can be lower where the solver finds
// the contact itself. From the straight guess with that meeting random_mixed_3_8 reaches a
// certified point. Scenes without a turner get the guesses they had, bit for bit.
//
// Conflicts. A pair (i, j) conflicts when, on the straight paths (which share the same
// timing, so p_j - p_i = d0 + w (dN - d0) is linear in w), the centre distance drops
// below the pair's clearance R_i + R_j (+ d_s for an avoid pair; core/model/gap.h).
//
// Detour. For every conflicting pair (each on its own side, below), with D = dN - d0 (the relative motion of j seen
// from i) and n = D turned +90 degrees (unit): i is moved by +side B n b(tau), j by -side
// B n b(tau), with B the clearance and b a smooth bump, 0 at tau = 0 and 1, peaking
// (b = 1) at the straight paths' closest approach. So the lateral offset (p_j - p_i) . n
// changes by -2 side B at the peak: side +1 (left) puts each robot on the other's left
// (relative to their relative motion), side -1 (right) on its right. The offsets of the
// two sides are exact mirror images; pairs' offsets add up. Each pair takes its own side
// from the start's pattern (search/start.h: all left, all right, then the mixed ones).
//
// Perturbed. Per robot: a lateral offset p L l(tau) along its path's normal (L = path
// length; a robot that does not move gets p R in x and in y independently, R its
// radius), with l = sum_k a_k sin(k pi tau) / sum |a_k|, k = 1..3, a_k uniform in
// [-1, 1]; and a timing warp s(tau) = tau + p sum_k c_k sin(k pi tau) / (k pi), k = 1..2,
// c_k in [-1, 1], along the path (w(s(tau)) replaces w(tau)), monotone since
// s' >= 1 - 2 p > 0 for p < 0.5. The shape's random numbers come from stream 1 of the
// start's generator (search/start.h).
//
// Yield. Prioritised planning with waits: the robots, in the start's yield_order (its
// enumerated order, search/start.h; with more than kEnumeratedPairs conflicting pairs a
// random order, Fisher-Yates on stream 1), each keep their straight path and smoothstep timing but wait at the start
// for a fraction d of the horizon, then move on w((tau - d) / (1 - d)). Each robot takes
// the smallest d in 0, 0.01, ..., 0.6 for which its centre distance to every robot placed
// before it, over 8 N samples of tau, stays at least `margin` (drawn in [1, 1.5]) times
// the pair's clearance; if none does, the d with the largest smallest distance. So at a
// crossing one robot goes first and the other waits for it, the class of solution a
// straight or detour guess rarely reaches.
//
// Perturbed feasible. The guess is the smoothstep one; the perturbation (step 1b of
// search/objective_reduction.h) takes each robot's path from the feasible point,
// (x, y, phi) at t = 0..N (t = 0 the start), and re-times it: state t of the new path is
// the old path at the continuous step N s(t / N), linearly interpolated between the
// neighbouring states, with s(tau) = tau + p sum_k c_k sin(k pi tau) / (k pi), k = 1..2,
// c_k uniform in [-1, 1] per robot (stream 1), p = perturbation: s(0) = 0, s(1) = 1,
// s' >= 1 - 2 p > 0. The t = N state is the feasible end state exactly (in the target
// box). Robots get different warps, so their relative timing changes too. The rest
// follows from the new positions (complete_guess) for the horizon T_scale times the
// feasible one.
//
// Weak robots. The smoothstep asks for accelerations up to 6 L / T^2 (at both ends). A
// robot whose own acceleration along its move, a_1 = (push - friction) / M
// (core/model/lower_bound.h, MoveLimits), is smaller at the horizon T cannot follow it:
// a robot barely stronger than its floor friction. From such a guess the feasibility
// solve settled on stop-and-go paths (the robot at rest at inner steps, where the
// friction complementarity is biactive and leaving the stop needs a jump of the friction
// to mu M g), local optima the reduction never left: configs/stress/weak_force.yaml
// (F_max = 1.001 mu M g) ended 5.3 % above its optimum. In straight_guess(), at a horizon
// T from the move's minimum time up to sqrt(6 L / a_1), such a robot moves on the timing
// of its own fastest move in the model's steps, stretched to T: the distance after step
// t is the share sum_{k<=t} v_k / sum_{k<=N} v_k of the velocity profile v_k =
// min(a_1 k, a_2 (N - k)), a_2 = (push + friction) / M (v_k = a_1 k without a stop at
// the end); its velocity changes stay within a_1 h and a_2 h whenever T is at least the
// move's minimum time in N steps, and it ends at rest exactly. (The continuous bang-bang
// timing brakes within the last step, which positions at the steps cannot show: from it
// the first feasibility solve failed.) At the default horizon (1.5 times the slowest
// robot's time) the smoothstep is too fast for a robot with push < 2 friction along its
// move: the paper's robots (push 1.52 friction) but none of the other configs/scenarios/
// (tests/test_start.cpp checks). Other kinds keep the smoothstep.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/model/robot_problem.h"
#include "search/objective_reduction.h"
#include "search/start.h"

namespace disco {

// The point of `problem` at horizon `seconds` that follows `paths` (one per robot, N + 1
// poses each; entry t = 0 is not used: the start is a constant of the model and is taken
// exactly): velocities from the kinematics (core/model/kinematics.h), floor friction on
// the vertex most opposed to the motion (core/model/floor_friction.h) at mu M g while
// moving, forces balancing the momentum rows (clipped to their bounds), gaps from the
// positions, contact forces zero, contact gamma = |v_T| (core/model/contact_friction.h).
// phi and omega of a robot that does not turn (core/model/model_plan.h) are its
// constants.
Vector complete_guess(const RobotProblem& problem, const Paths& paths, double seconds);

// A robot's straight move: from its start pose to its target pose.
struct StraightMove {
  Pose from{}, to{};
  double length() const;  // of the (x, y) segment
};
StraightMove straight_move(const Robot& robot);

// A robot's way from its start to its target position, around the fixed obstacles (above).
using Way = std::vector<std::array<double, 2>>;
inline constexpr double kWayMargin = 1.2;
Way way_around_obstacles(const Scene& scene, int robot);

// The time the guesses' way asks of a robot with a position target that pushes objects on
// its way ("Pushers" above): the sum over its legs of each leg's own time from rest to rest
// (straight_move_time of the robot on a way between pushes, pushed_move_time of the object on
// a push; core/model/lower_bound.h), a scale and not a bound; the longest over such robots,
// absent when there is none (or a leg has no such time). feasibility_horizon
// (search/objective_reduction.h) scales the first horizon on it when it is longer than the
// scene's reference time: that reference is each robot's straight move alone, and a robot
// that takes a coin on its way must first reach the coin and then leave it.
std::optional<double> pushers_way_time(const Scene& scene);

// The pairs whose straight paths, timed alike, come closer than their clearance.
struct Conflict {
  int i = 0, j = 0;
  double w = 0.5;             // smoothstep fraction at the closest approach
  double nx = 0.0, ny = 0.0;  // unit normal of the relative motion
  double clearance = 0.0;     // R_i + R_j (+ d_s)
  PairMode mode = PairMode::kAvoid;  // the pair's: crossing in a contact pair, they touch
};
std::vector<Conflict> conflicts(const Scene& scene);

// Turners meet a partner ("Turners" above): robot i must turn and its straight path touches
// nothing, so it and j, its contact partner whose straight path comes closest, are moved
// towards each other along (ux, uy) (from i to j at that closest approach, at the smoothstep
// fraction w), i by shift_i and j by shift_j, which makes them touch there: each half the
// excess when j is a robot, i all of it when j is an object (no force of its own to meet i
// halfway) or when the partner is a fixed contact obstacle (j = -1, `obstacle` its index in
// Scene::obstacles). Two turners that are each other's partner meet once.
struct Meeting {
  int i = 0, j = 0;
  double w = 0.5;
  double ux = 0.0, uy = 0.0;
  double shift_i = 0.0, shift_j = 0.0;
  int obstacle = -1;
};
std::vector<Meeting> meetings(const Scene& scene);

// The guesses, as described above.
// meet_turners: with the turners' meetings ("Turners" above; StartSpec::meet_turners).
Vector smoothstep_guess(const RobotProblem& problem, double seconds, bool meet_turners = false);
Vector straight_guess(const RobotProblem& problem, double seconds, bool meet_turners = false);
// Side +1 (left) or -1 (right) for every conflicting pair.
Paths detour_paths(const Scene& scene, int side);
// Pair k of conflicts(scene) on the right where bit k of `pattern` is set, else on the left
// (pairs beyond 64 on the left).
Paths detour_paths(const Scene& scene, std::uint64_t pattern, bool meet_turners = false);
Paths yield_paths(const Scene& scene, const StartSpec& start);
Paths perturbed_paths(const Scene& scene, const StartSpec& start);
Paths retimed_paths(const RobotProblem& problem, const StartSpec& start, const Vector& feasible);

// The paths of `start`'s guess, at the scene level (no model): the straight paths on the
// smoothstep timing for kStraight and kPerturbedFeasible (a weak robot's own timing aside),
// the kind's own paths otherwise. search/homotopy.h classifies them.
Paths guess_paths(const Scene& scene, const StartSpec& start);

// The initial guess of `start` for horizon `seconds`.
Vector make_guess(const RobotProblem& problem, const StartSpec& start, double seconds);

// kPerturbedFeasible: the perturbation of the feasible point `feasible` (model-unit z):
// its paths re-timed, completed, at T_scale times its horizon. Deterministic in
// (start, feasible).
Perturbation perturb_feasible(const RobotProblem& problem, const StartSpec& start,
                              const Vector& feasible);
// The PerturbFunction for reduce_objective: perturb_feasible for a kPerturbedFeasible
// start, empty (no step 1b) for every other kind and when the scene fixes T_f (objective
// energy). `problem` must outlive the function.
PerturbFunction make_perturbation(const RobotProblem& problem, const StartSpec& start);

}  // namespace disco
