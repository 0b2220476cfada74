// disco solve against theory: one robot moving rest to rest along a straight
// line, where the continuous minimum time is known in closed form. The
// reference is computed here from the physics (bang-bang: full force to the
// switching point, full reverse force to stop), independently of disco's
// core/model/lower_bound.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "search/solve_scene.h"

namespace disco {
namespace {

// T for distance d, push F along the move, friction mu M g, mass M.
double bang_bang_time(double d, double F, double mu, double M, double g) {
  const double a1 = (F - mu * M * g) / M;  // speeding up: friction against
  const double a2 = (F + mu * M * g) / M;  // braking: friction helps
  // d = v^2 / (2 a1) + v^2 / (2 a2)
  const double v = std::sqrt(2.0 * d / (1.0 / a1 + 1.0 / a2));
  return v / a1 + v / a2;
}

struct Case {
  const char* file;
  double distance, push;  // from the scene file: 10 m along x (D_ef 1); 8*sqrt(2) m diagonal (D_ef 2)
};

double solve_time(const Case& c, int steps, double* certificate_violation = nullptr,
                  double* certificate_complementarity = nullptr) {
  const std::string path = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + c.file;
  const Scene scene = load_scene(path, {"steps=" + std::to_string(steps)});
  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  EXPECT_TRUE(run.solved()) << c.file << " N_t=" << steps << ": " << to_string(run.info.status);
  if (certificate_violation) *certificate_violation = run.info.certificate.max_violation;
  if (certificate_complementarity)
    *certificate_complementarity = run.info.certificate.max_complementarity;
  return run.T_f();
}

const Case kAxis{"one_robot_axis.yaml", 10.0, 5.0};
const Case kDiagonal{"one_robot_diagonal.yaml", 8.0 * std::sqrt(2.0), 5.0 * std::sqrt(2.0)};

void check_convergence(const Case& c) {
  const double exact = bang_bang_time(c.distance, c.push, 0.2, 1.0, 9.81);
  double previous = INFINITY;
  for (int steps : {25, 50, 100, 200}) {
    double viol = 0, compl_ = 0;
    const double T = solve_time(c, steps, &viol, &compl_);
    const double err = std::abs(T - exact) / exact;
    std::printf("%s N_t=%d T_f=%.7f closed form=%.7f rel.error=%.3e\n", c.file, steps, T, exact,
                err);
    EXPECT_LE(viol, 1e-6);
    EXPECT_LE(compl_, 1e-6);
    if (steps == 100) {
      EXPECT_LE(err, 1e-3) << "N_t = 100 must be within 0.1 %";
    }
    EXPECT_LT(err, previous) << "error must shrink as N_t grows (N_t = " << steps << ")";
    previous = err;
  }
}

TEST(ClosedForm, AxisMoveWithOneForceAxisConverges) { check_convergence(kAxis); }
TEST(ClosedForm, DiagonalMoveWithTwoForceAxesConverges) { check_convergence(kDiagonal); }

}  // namespace
}  // namespace disco
