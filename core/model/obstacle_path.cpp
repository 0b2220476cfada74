#include "core/model/obstacle_path.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <memory>

#include "core/util/check.h"

namespace disco {

PathCoordinate::PathCoordinate(const std::vector<Waypoint>& w, int axis) {
  const int n = static_cast<int>(w.size()) - 1;
  DISCO_CHECK(n >= 1, "a path has at least two waypoints");
  for (int k = 0; k < n; ++k) DISCO_CHECK(w[k + 1].t > w[k].t, "waypoint times increase");
  // Second derivatives M_k at the knots: the clamped spline's tridiagonal system (slope 0 at
  // both ends). It is symmetric and strictly diagonally dominant, hence positive definite:
  // a sparse Cholesky solves it in O(n), so a path sampled at thousands of waypoints costs
  // no more than its length.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  auto h = [&](int k) { return w[k + 1].t - w[k].t; };
  auto slope = [&](int k) { return (w[k + 1].p[axis] - w[k].p[axis]) / h(k); };
  for (int k = 0; k <= n; ++k) {
    const double left = k > 0 ? h(k - 1) : 0.0, right = k < n ? h(k) : 0.0;
    entries.emplace_back(k, k, 2.0 * (left + right));
    if (k > 0) entries.emplace_back(k, k - 1, left);
    if (k < n) entries.emplace_back(k, k + 1, right);
    b[k] = 6.0 * ((k < n ? slope(k) : 0.0) - (k > 0 ? slope(k - 1) : 0.0));
  }
  Eigen::SparseMatrix<double> A(n + 1, n + 1);
  A.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(A);
  DISCO_CHECK(factor.info() == Eigen::Success, "the clamped spline's system is positive definite");
  const Eigen::VectorXd M = factor.solve(b);
  for (int k = 0; k < n; ++k) {
    t_.push_back(w[k].t);
    c_.push_back({w[k].p[axis], slope(k) - h(k) * (2.0 * M[k] + M[k + 1]) / 6.0, 0.5 * M[k],
                  (M[k + 1] - M[k]) / (6.0 * h(k))});
  }
  t_.push_back(w[n].t);
  c_.push_back({w[n].p[axis], 0.0, 0.0, 0.0});  // at rest after the last waypoint
}

std::array<double, 3> PathCoordinate::eval(double tau) const {
  if (tau <= t_.front()) return {c_.front()[0], 0.0, 0.0};  // waits at the first waypoint
  // The piece whose knot is the last one <= tau (the rest piece after t_n).
  const int k = static_cast<int>(std::upper_bound(t_.begin(), t_.end(), tau) - t_.begin()) - 1;
  const auto& c = c_[k];
  const double s = tau - t_[k];
  return {c[0] + s * (c[1] + s * (c[2] + s * c[3])), c[1] + s * (2.0 * c[2] + 3.0 * s * c[3]),
          2.0 * c[2] + 6.0 * s * c[3]};
}

std::array<double, 2> PathCoordinate::range(double tau0, double tau1) const {
  double lo = eval(tau0)[0], hi = lo;
  auto take = [&](double tau) {
    if (tau < tau0 || tau > tau1) return;
    const double v = eval(tau)[0];
    lo = std::min(lo, v), hi = std::max(hi, v);
  };
  take(tau1);
  for (std::size_t k = 0; k < t_.size(); ++k) {
    take(t_[k]);
    if (k + 1 == t_.size()) break;
    // Turning points of piece k: c1 + 2 c2 s + 3 c3 s^2 = 0 with 0 < s < t_{k+1} - t_k.
    const auto& c = c_[k];
    const double a = 3.0 * c[3], bb = 2.0 * c[2], cc = c[1], len = t_[k + 1] - t_[k];
    std::vector<double> roots;
    if (a == 0.0) {
      if (bb != 0.0) roots.push_back(-cc / bb);
    } else if (const double disc = bb * bb - 4.0 * a * cc; disc >= 0.0) {
      roots.push_back((-bb + std::sqrt(disc)) / (2.0 * a));
      roots.push_back((-bb - std::sqrt(disc)) / (2.0 * a));
    }
    for (double s : roots)
      if (s > 0.0 && s < len) take(t_[k] + s);
  }
  return {lo, hi};
}

std::array<double, 2> path_point(const std::vector<Waypoint>& waypoints, double tau) {
  return {PathCoordinate(waypoints, 0).eval(tau)[0], PathCoordinate(waypoints, 1).eval(tau)[0]};
}

void add_obstacle_path(Layout& L, PolynomialProgram& P) {
  for (int p = 0; p < L.num_pairs(); ++p) {
    if (!L.follows_path(p)) continue;
    const int tag = L.pair_row_tag("gap", p);
    for (int a = 0; a < 2; ++a) {
      const auto Q = std::make_shared<const PathCoordinate>(L.obstacle(p).path, a);
      for (int t = 1; t <= L.steps(); ++t) {
        const int k = L.path_point_index(p, t, a);
        if (k < 0) continue;
        const int r = P.add_row(0.0, 0.0, tag);
        P.add(r, 1.0, Affine::variable(k));
        P.add_function(r, -1.0, Q, L.horizon_index(), static_cast<double>(t) / L.steps());
      }
    }
  }
}

void complete_obstacle_paths(const Layout& L, VectorRef z) {
  const double t_f = z[L.horizon_index()];
  for (int p = 0; p < L.num_pairs(); ++p) {
    if (!L.follows_path(p)) continue;
    for (int t = 1; t <= L.steps(); ++t) {
      if (L.path_point_index(p, t, 0) < 0) continue;
      const auto q = path_point(L.obstacle(p).path, t * t_f / L.steps());
      for (int a = 0; a < 2; ++a) z[L.path_point_index(p, t, a)] = q[a];
    }
  }
}

}  // namespace disco
