// disco — a disk obstacle that follows waypoints given in advance (the paper's Section VI,
// "moving obstacles"; Obstacle::path, core/model/scene.h).
//
// The path. Through the waypoints (t_k, P_k), k = 0..n (n >= 1, t_k increasing), each
// coordinate is the clamped cubic spline with zero slope at t_0 and t_n: it passes every
// waypoint, is twice continuously differentiable between t_0 and t_n, and starts and ends at
// rest. Before t_0 the obstacle waits at P_0, after t_n it stays at P_n, so the path is
// continuously differentiable everywhere; its second derivative jumps at t_0 and t_n only.
// (A spline through the points, not straight legs: straight legs have kinks, and at a kink
// the velocity, hence the Jacobian, jumps.)
//
// Its rows. With T_f free, state t is at tau = t T_f / N, so the obstacle's centre there
// is Q(t T_f / N), a piecewise cubic in the unknown T_f, not a polynomial. Each pair with
// a path obstacle gets, at each of its gap states t (its window, core/model/model_plan.h),
// two unknowns q^t = (q_x^t, q_y^t) defined by
//     q_a^t - Q_a((t / N) T_f) = 0,          a = x, y,
// a function term of PolynomialProgram (core/nlp/polynomial_program.h) whose derivatives
//     d/dT_f = -(t / N) Q_a',      d2/dT_f2 = -(t / N)^2 Q_a''
// are exact: Q's own, per piece. The pair's other rows (gap, avoid) use q^t like any
// disk's centre, so they stay polynomial. At t = 0 the centre is the constant Q(0).
// The derivative tests (tests/test_model_derivatives.cpp) cover these rows, near the
// waypoints too; tests/test_obstacle_path.cpp covers the spline itself.
//
// A moving obstacle could push, which the model does not state, so its pairs are avoid
// pairs (core/model/scene_yaml.cpp).
#pragma once

#include <array>
#include <vector>

#include "core/model/layout.h"
#include "core/model/scene.h"
#include "core/nlp/polynomial_program.h"

namespace disco {

// One coordinate (axis 0: x, 1: y) of the path through `waypoints`, as a function of
// time: value, first and second derivative (the spline above, exact to roundoff).
class PathCoordinate : public UnivariateFunction {
 public:
  PathCoordinate(const std::vector<Waypoint>& waypoints, int axis);
  std::array<double, 3> eval(double tau) const override;
  // The least and greatest value over [tau0, tau1] (exact: ends, waypoints inside, and the
  // turning points of each cubic piece).
  std::array<double, 2> range(double tau0, double tau1) const;

 private:
  std::vector<double> t_;                   // knots
  std::vector<std::array<double, 4>> c_;    // piece k: sum_j c_j (tau - t_k)^j
};

// The path's point at time tau.
std::array<double, 2> path_point(const std::vector<Waypoint>& waypoints, double tau);

// The rows q^t = Q(t T_f / N) of every pair with a path obstacle at its gap states (the
// gap family builds them).
void add_obstacle_path(Layout& L, PolynomialProgram& P);

// Sets every pair's q^t in z to the path at the T_f in z (for guesses and transfers).
void complete_obstacle_paths(const Layout& L, VectorRef z);

}  // namespace disco
