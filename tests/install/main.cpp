// An outside program on an installed disco: states MacMPEC's gauvin (Gauvin & Savard 1992)
//   min x^2 + (y - 10)^2,  0 <= x <= 15,
//   0 <= 4 (x + 2y - 30) + u  _|_  y >= 0,
//   0 <= 20 - x - y           _|_  u >= 0
// (y minimises (x + 2y - 30)^2 over 0 <= y <= 20 - x; literature optimum f* = 20 at
// (2, 14, 0)), solves it with disco's elastic mode and the installed settings file's Ipopt
// options and elastic parameters, and checks the answer against a reference computed here,
// independently of disco: a scan over x with the lower level in closed form.
// Exit 0 if the solution matches, 1 if not.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/nlp/polynomial_program.h"

namespace {

using disco::Affine;
using Side = disco::ComplementaritySide;

double lower_level(double x) { return std::clamp((30 - x) / 2, 0.0, 20 - x); }
double upper_objective(double x) {
  const double y = lower_level(x);
  return x * x + (y - 10) * (y - 10);
}

}  // namespace

int main() {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  disco::PolynomialProgram p;
  const int x = p.add_variable(0.0, 15.0, 7.5), y = p.add_variable(0.0, kInf, 0.0),
            u = p.add_variable(0.0, kInf, 1.0);
  const int fy = p.add_row(-kInf, kInf), fu = p.add_row(-kInf, kInf);
  p.add(fy, 4.0, Affine::variable(x) + 2.0 * Affine::variable(y) - Affine(30.0));
  p.add(fy, 1.0, Affine::variable(u));
  p.add(fu, 1.0, Affine(20.0) - Affine::variable(x) - Affine::variable(y));
  p.add(disco::PolynomialProgram::kObjective, 1.0, Affine::variable(x), Affine::variable(x));
  p.add(disco::PolynomialProgram::kObjective, 1.0, Affine::variable(y) - Affine(10.0),
        Affine::variable(y) - Affine(10.0));
  p.add_pair(Side::row(fy), Side::variable(y));
  p.add_pair(Side::row(fu), Side::variable(u));
  p.finalize();

  const disco::Settings settings = disco::Settings::load(DISCO_SETTINGS);
  disco::IpoptSolver ipopt(disco::ipopt_settings(settings));
  const disco::ElasticSolver solver(ipopt, disco::elastic_settings(settings));
  const disco::MpccResult r = solver.solve(p, p.initial_point());

  // The reference: the best of a grid of step 1e-5 on [0, 15] (the error in f is below
  // f''/2 * (5e-6)^2 ~ 1e-10 here).
  double x_ref = 0.0, f_ref = kInf;
  for (int k = 0; k <= 1500000; ++k) {
    const double xv = 1e-5 * k;
    if (const double f = upper_objective(xv); f < f_ref) {
      f_ref = f;
      x_ref = xv;
    }
  }
  const double y_ref = lower_level(x_ref);
  // 20 - x - y > 0 there, so its pair forces u = 0.
  const double u_ref = 20 - x_ref - y_ref > 0 ? 0.0 : std::nan("");
  // The solution's own feasibility, evaluated here (not disco's certificate).
  const double zx = r.z[x], zy = r.z[y], zu = r.z[u];
  const double side_y = 4 * (zx + 2 * zy - 30) + zu, side_u = 20 - zx - zy;
  const double violation = std::max({0.0, -side_y, -zy, -side_u, -zu, -zx, zx - 15});
  const double complementarity = std::max(std::abs(std::min(side_y, zy)), std::abs(std::min(side_u, zu)));
  const double f = zx * zx + (zy - 10) * (zy - 10);
  std::printf("disco: status %s, f = %.9f at (x, y, u) = (%.7f, %.7f, %.7f); violation %.1e, "
              "complementarity %.1e\nreference: f = %.9f at (x, y, u) = (%.5f, %.5f, %.5f)\n",
              disco::to_string(r.status).c_str(), f, zx, zy, zu, violation, complementarity,
              f_ref, x_ref, y_ref, u_ref);
  const bool ok = r.solved() && violation <= 1e-6 && complementarity <= 1e-6 &&
                  std::abs(f - f_ref) <= 1e-6 && std::abs(zx - x_ref) <= 1e-4 &&
                  std::abs(zy - y_ref) <= 1e-4 && std::abs(zu - u_ref) <= 1e-4;
  std::printf("%s\n", ok ? "match" : "MISMATCH");
  return ok ? 0 : 1;
}
