// disco solve against theory: one robot moving rest to rest along a straight
// line, and one robot pushing a coin (a passive object) along a line to rest, where the
// continuous minimum time is known in closed form. The references are computed here from
// the physics and the scene file's numbers, independently of disco's
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

// A finger (robot 0: force along x only) starts touching a coin (object 1), both at rest;
// the coin must end at rest D further along x, the finger anywhere. Fastest: push together
// with full force, a1 = (F - mu_r M_r g - mu_c M_c g) / (M_r + M_c), then release: the coin
// slides to a stop at a2 = mu_c g (the finger can only push, never hold it back), so
// T = v / a1 + v / a2 with v = sqrt(2 D a1 a2 / (a1 + a2)).
TEST(ClosedForm, PushingACoinToRestConverges) {
  const std::string path = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/push_coin_line.yaml";
  double previous = INFINITY;
  for (int steps : {25, 50}) {
    const Scene scene = load_scene(path, {"steps=" + std::to_string(steps)});
    ASSERT_EQ(scene.robots.size(), 2u);
    const Robot& r = scene.robots[0];
    const Robot& c = scene.robots[1];
    ASSERT_TRUE(c.object && !r.object);
    ASSERT_EQ(r.force_dims, 1);
    ASSERT_EQ(r.force_axis[0], 1.0);
    ASSERT_EQ(c.target.lower[kX], c.target.upper[kX]);
    ASSERT_DOUBLE_EQ(c.start[kX] - r.start[kX], r.radius + c.radius) << "touching at the start";
    const double g = scene.gravity, D = c.target.lower[kX] - c.start[kX];
    const double a1 = (r.force_max - r.mu * r.mass * g - c.mu * c.mass * g) / (r.mass + c.mass);
    const double a2 = c.mu * g;
    const double v = std::sqrt(2.0 * D * a1 * a2 / (a1 + a2));
    const double exact = v / a1 + v / a2;

    const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
    ASSERT_TRUE(run.solved()) << "N_t=" << steps << ": " << to_string(run.info.status);
    EXPECT_LE(run.info.certificate.max_violation, 1e-6);
    EXPECT_LE(run.info.certificate.max_complementarity, 1e-6);
    const double err = std::abs(run.T_f() - exact) / exact;
    std::printf("push_coin_line N_t=%d T_f=%.7f closed form=%.7f rel.error=%.3e\n", steps,
                run.T_f(), exact, err);
    if (steps == 50) EXPECT_LE(err, 5e-3) << "N_t = 50 must be within 0.5 %";
    EXPECT_LT(err, previous) << "error must shrink as N_t grows (N_t = " << steps << ")";
    previous = err;
  }
}

}  // namespace
}  // namespace disco
