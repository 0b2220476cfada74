// disco — no jump through an obstacle between two states (the paper's Section VI).
//
// The pair rows (core/model/gap.h, core/model/obstacles.h) hold at the N_t states, as the
// paper's do: a disk that moves farther in one step than an obstacle is thick can jump it.
// For every (disk, obstacle) pair and step t = 1..N whose two states both lie in the pair's
// window (t - 1 = 0, the start, always does):
//     (2 R (1 - kSweptMargin) + rho^{t-1} + rho^t)^2 - |d^t|^2 >= 0,
// R = R_i + R_o (R_o a disk obstacle's radius, half a wall's thickness), rho the pair's gap
// (centre distance to the obstacle's centre or centre segment less R), and d^t the disk's
// move p^t - p^{t-1} (a wall), or its move relative to a disk obstacle's centre
// (p^t - q^t) - (p^{t-1} - q^{t-1}) (a fixed post: the move itself; a moving disk: the
// relative move, straight between the states as in swept_distance). Why it forbids a jump: if the straight move from
// p^{t-1} to p^t met the centre segment at q, then |p^t - p^{t-1}| = |p^{t-1} - q| +
// |q - p^t| >= (R + rho^{t-1}) + (R + rho^t), which the row excludes by 2 R kSweptMargin.
// Read the other way: the move is covered by the two disks around its ends whose radii
// are the ends' distances to the wall, and those disks hold no point of the wall. This
// holds through a wall's inside, its ends and the joint of two walls alike, so walls that
// close the only way make a scene infeasible at any N_t. For a disk obstacle the centre
// segment is one point, q: the move may not pass through it, so a disk goes round a post,
// never over it (between the states it can still cut into the post: with both ends at
// distance R the move passes no closer than sqrt(0.19) R ~ 0.44 R to q, which
// swept_gap reports).
//
// What it costs: near a wall a step is at most 2 R (1 - kSweptMargin) + rho^{t-1} + rho^t
// long (sliding along a wall in contact: 1.8 R per step). The row is polynomial (degree
// 2, rho >= 0 or >= d_s keeps the base positive), so its derivatives are exact.
//
// The adaptive plan (core/model/model_plan.h) gives an obstacle pair every state whose
// step before or after can come within reach of the obstacle, so each such step carries
// the row. Far from an obstacle the row is slack for any step shorter than twice the
// distance, and the plan leaves it out where the move provably stays beyond reach: there
// the adaptive model is the full model (every step carries the row) less those rows.
#pragma once

#include "core/model/layout.h"

namespace disco {

// The fraction of the diameter a step near an obstacle gives up, so that a jump is excluded by
// a margin, not only at its limit (where the disk touches the obstacle on both sides).
inline constexpr double kSweptMargin = 0.1;

void add_swept_clearance(Layout& L, PolynomialProgram& P);

}  // namespace disco
