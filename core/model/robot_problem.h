// disco — the whole robot model of a scene: Appendix A as a PolynomialProgram.
//
//     minimize T_f (or J)  subject to  kinematics, dynamics, floor friction, gap,
//     nonpenetration, contact friction, avoidance, bounds
// (one unit each in core/model/, in that order), built in model units
// (core/model/units.h). Pass a subset of families to build part of the model
// (derivative tests check each family alone; dynamics is always included,
// since the force families add their impulses to its rows).
//
// The objective is the scene's (core/model/objective.h): T_f by default. The
// horizon T_f is an unknown with bounds: fix_horizon() pins it (the
// feasibility phase), limit_horizon() bounds it above (objective reduction
// of time), never above the largest horizon T_max of the ModelOptions; with
// objective energy it stays at the scene's horizon. The adaptive
// model (core/model/model_plan.h) builds only what a scene needs up to T_max;
// set_horizon_max() rebuilds it for another T_max. All times given to or
// returned by this class are in seconds (SI). The initial guesses of the
// solves are made in search/guess.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/model/model_plan.h"
#include "core/model/layout.h"
#include "core/model/scene.h"
#include "core/model/units.h"
#include "core/nlp/polynomial_program.h"

namespace disco {

enum class Family {
  kKinematics,
  kDynamics,
  kFloorFriction,
  kGap,
  kNonpenetration,
  kContactFriction,
  kAvoidance,
  kSweptClearance,
  kBounds,
};
const std::vector<Family>& all_families();

struct ModelSize {
  int variables = 0, constraints = 0, complementarity_pairs = 0;
};

class RobotProblem {
 public:
  explicit RobotProblem(const Scene& scene, const std::vector<Family>& families = all_families(),
                        const ModelOptions& options = {});
  RobotProblem(const Scene& scene, const ModelOptions& options)
      : RobotProblem(scene, all_families(), options) {}

  PolynomialProgram& program() { return program_; }
  const PolynomialProgram& program() const { return program_; }
  const Layout& layout() const { return *layout_; }
  const Units& units() const { return units_; }
  const Scene& scene() const { return scene_; }  // SI
  ModelSize size() const;
  const ModelOptions& options() const { return options_; }
  const ModelPlan& plan() const { return plan_; }

  // Rebuilds the model for T_f <= max_seconds, if that changes it. Every point
  // of the model before (and any reference to program() or layout() data) is
  // then invalid: call it only between solves that share no point.
  void set_horizon_max(double max_seconds);  // (objective energy: always its horizon)
  void fix_horizon(double seconds);        // T_f = seconds (<= T_max)
  void limit_horizon(double max_seconds);  // T_f in [minimum, min(max_seconds, T_max)]
  double horizon(const ConstVectorRef& z) const;  // T_f of a point, seconds

  // The objective J (core/model/objective.h) and the bounds the objective reduction puts
  // on it, in SI (seconds, or N^2 s for energy). For time these are the horizon's bounds.
  ObjectiveKind objective_kind() const;
  double objective(const ConstVectorRef& z) const;  // J of a point
  // J <= value, or J = value (`fixed`); T_f stays free (fixed for energy).
  void bound_objective(double value, bool fixed);
  // J free: T_f free up to T_max, or fixed at the scene's horizon for energy (the model
  // itself; how it is built).
  void free_objective();
  // True when T_f is the scene's, not an unknown of the search (objective energy).
  bool horizon_is_fixed() const { return objective_kind() == ObjectiveKind::kEnergy; }
  // A value J never goes below on this model: for time (and time + energy) the larger of
  // the lower bound and the model's smallest horizon; 0 for energy.
  double objective_floor() const;
  // The largest T_f (s) of any point with a smaller J than a point at horizon T: T itself for
  // time; for time + energy T (1 + w sum_i Fbar_i^2), since J <= T + w T sum_i Fbar_i^2 at T
  // (|F_i| <= Fbar_i) and T_f <= J; for energy the scene's horizon. The model a reduction
  // from a feasible point at T needs (set_horizon_max).
  double horizon_reach(double T) const;
  std::optional<double> lower_bound() const;      // seconds (core/model/lower_bound.h)
  std::optional<double> reference_time() const;   // seconds: a scale, not a bound

  // The point of `to` (the same scene, another plan: e.g. the full model) that
  // the point z of this model describes. Unknowns both have are copied; those
  // only `to` has take the values the plan proves (core/model/model_plan.h):
  // gaps from the centres, contact forces and friction multipliers 0, contact
  // gamma = |v_T| (core/model/contact_friction.h), phi = phi^0 and omega = 0. Certifying the result on
  // `to` checks the adaptive model's answer on the full model.
  Vector transfer(const Vector& z, const RobotProblem& to) const;

  // Where a point breaks the model, for an infeasible result: per robot (or pair) and
  // family, the largest violation of its rows (model units: the certificate's), and of the
  // bounds on its state at T_f ("target"), largest first, those above `tolerance` only.
  struct Violation {
    std::string owner;   // "robot 'a'" or "pair ('a', 'b')"
    std::string family;  // "dynamics", "kinematics", "gap", "target", ...
    double amount = 0.0;
  };
  std::vector<Violation> violations(const Vector& z, double tolerance) const;

 private:
  void build();

  Scene scene_;
  Units units_;
  std::vector<Family> families_;
  ModelOptions options_;
  ModelPlan plan_;
  PolynomialProgram program_;
  std::optional<Layout> layout_;  // set by build()
  int objective_row_ = -1;        // the row of J for objectives other than time
};

}  // namespace disco
