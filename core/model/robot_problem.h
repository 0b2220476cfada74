// disco — the whole robot model of a scene: Appendix A as a PolynomialProgram.
//
//     minimize T_f  subject to  kinematics, dynamics, floor friction, gap,
//     nonpenetration, contact friction, avoidance, bounds
// (one unit each in core/model/, in that order), built in model units
// (core/model/units.h). Pass a subset of families to build part of the model
// (derivative tests check each family alone; dynamics is always included,
// since the force families add their impulses to its rows).
//
// The horizon T_f is an unknown with bounds: fix_horizon() pins it (the
// feasibility phase), limit_horizon() bounds it above (objective reduction).
// All times given to or returned by this class are in seconds (SI).
#pragma once

#include <array>
#include <optional>
#include <vector>

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
  kBounds,
};
const std::vector<Family>& all_families();

struct ModelSize {
  int variables = 0, constraints = 0, complementarity_pairs = 0;
};

class RobotProblem {
 public:
  explicit RobotProblem(const Scene& scene, const std::vector<Family>& families = all_families());

  PolynomialProgram& program() { return program_; }
  const PolynomialProgram& program() const { return program_; }
  const Layout& layout() const { return layout_; }
  const Units& units() const { return units_; }
  const Scene& scene() const { return scene_; }  // SI
  ModelSize size() const;

  void fix_horizon(double seconds);
  void limit_horizon(double max_seconds);  // T_f in [minimum, max_seconds]
  double horizon(const ConstVectorRef& z) const;  // T_f of a point, seconds
  std::optional<double> lower_bound() const;      // seconds (core/model/lower_bound.h)
  std::optional<double> reference_time() const;   // seconds: a scale, not a bound

  // The straight-line guess for horizon T: smoothstep positions from the start
  // to the nearest target point, velocities consistent with the kinematics,
  // friction opposing the motion, forces balancing the momentum rows (clipped
  // to their bounds), gaps from the positions, contact forces zero.
  Vector straight_line_guess(double seconds) const;
  // The same completion for given position paths: xyphi[i][t] = (x, y, phi)
  // of robot i at t = 0..N, in SI units (metres, radians). Entry t = 0 is not
  // used: the start state is a constant of the model and is taken exactly.
  // Everything else (velocities, friction, forces, gaps) follows the paths as
  // in straight_line_guess, which is this with smoothstep paths.
  Vector guess_from_paths(const std::vector<std::vector<std::array<double, 3>>>& xyphi,
                          double seconds) const;

 private:
  Scene scene_;
  Units units_;
  PolynomialProgram program_;
  Layout layout_;
};

}  // namespace disco
