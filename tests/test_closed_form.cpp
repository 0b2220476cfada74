// disco solve against theory: one robot moving rest to rest along a straight
// line, and one robot pushing a coin (a passive object) along a line to rest, where the
// continuous minimum time is known in closed form; and the least-effort objectives on the
// straight move. The references are computed here from
// the physics and the scene file's numbers, independently of disco's
// core/model/lower_bound.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/objective.h"
#include "core/model/scene_yaml.h"
#include "core/model/solution.h"
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

// One N_t of a convergence check: the relative error within `tol` at N_t = `at`, and below the
// error at the fewer steps before (`previous`, updated).
void expect_converging(double err, double& previous, int steps, int at, double tol) {
  if (steps == at) {
    EXPECT_LE(err, tol) << "N_t = " << at << " must be within " << 100 * tol << " %";
  }
  EXPECT_LT(err, previous) << "error must shrink as N_t grows (N_t = " << steps << ")";
  previous = err;
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
    expect_converging(err, previous, steps, 100, 1e-3);
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
    expect_converging(err, previous, steps, 50, 5e-3);
  }
}

// The least-effort objectives (core/model/objective.h) on one robot moving D rest to rest
// along x (one_robot_axis: force along x only, so F_y = 0). While it moves forward the floor
// takes mu M g, so F = M a + mu M g, and over a move from rest to rest of length tau
//     int F^2 = M^2 int a^2 + 2 mu M^2 g (v_end - v_start) + (mu M g)^2 tau,
// the middle term 0; int a^2 >= 12 D^2 / tau^3 (the cubic path, a = 6D/tau^2 (1 - 2t/tau)).
// At rest the floor holds it with F = 0. So with T fixed (energy) the best is one move of
// tau = min(T, tau*), tau* = (36 D^2 M^2 / (mu M g)^2)^(1/4), then rest:
//     E* = 12 D^2 M^2 / tau^3 + (mu M g)^2 tau.
// With T free (time + energy, no rest: it would only add time) J(T) = T + w E(T) is least at
//     T*^4 = 36 w D^2 M^2 / (1 + w (mu M g)^2).
// Both hold when the cubic's largest push 6 D M / tau^2 + mu M g is within F_max (asserted).
struct AxisMove {
  double D, M, f, F_max;  // distance, mass, floor friction mu M g, force bound
};
AxisMove axis_move(const Scene& scene) {
  const Robot& r = scene.robots.at(0);
  EXPECT_EQ(r.force_dims, 1);
  return {r.target.lower[kX] - r.start[kX], r.mass, r.mu * r.mass * scene.gravity, r.force_max};
}
double move_energy(const AxisMove& m, double tau) {
  return 12.0 * m.D * m.D * m.M * m.M / std::pow(tau, 3) + m.f * m.f * tau;
}

// E from the solution file's forces alone: sum_t h (Fx^2 + Fy^2).
double energy_of(const nlohmann::json& sol) {
  const double h = sol.at("h").get<double>();
  double E = 0.0;
  for (const auto& r : sol.at("robots")) {
    const auto fx = r.at("Fx").get<std::vector<double>>(), fy = r.at("Fy").get<std::vector<double>>();
    for (std::size_t t = 0; t < fx.size(); ++t) E += h * (fx[t] * fx[t] + fy[t] * fy[t]);
  }
  return E;
}

TEST(ClosedForm, LeastEffortMoveInAFixedTimeRestsAndConverges) {
  const std::string path =
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/one_robot_axis_energy.yaml";
  double previous = INFINITY;
  for (int steps : {25, 50}) {
    const Scene scene = load_scene(path, {"steps=" + std::to_string(steps)});
    ASSERT_EQ(scene.objective.kind, ObjectiveKind::kEnergy);
    const AxisMove m = axis_move(scene);
    const double T = scene.objective.horizon;
    const double tau_star = std::pow(36.0 * m.D * m.D * m.M * m.M / (m.f * m.f), 0.25);
    const double tau = std::min(T, tau_star);
    ASSERT_LE(6.0 * m.D * m.M / (tau * tau) + m.f, m.F_max) << "the cubic move is within the force bound";
    ASSERT_LT(tau, T) << "the scene is meant to show the rest";
    const double exact = move_energy(m, tau);

    const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
    ASSERT_TRUE(run.solved()) << "N_t=" << steps << ": " << to_string(run.info.status);
    EXPECT_LE(run.info.certificate.max_violation, 1e-6);
    EXPECT_LE(run.info.certificate.max_complementarity, 1e-6);
    EXPECT_NEAR(run.T_f(), T, 1e-12 * T) << "T_f is the scene's";
    const nlohmann::json sol = solution_json(*run.problem, run.z, run.info);
    EXPECT_EQ(sol["objective"]["kind"], "energy");
    EXPECT_NEAR(energy_of(sol), run.value(), 1e-9 * run.value()) << "the objective is sum h |F|^2";
    EXPECT_NEAR(sol["objective"]["value"].get<double>(), run.value(), 1e-12 * run.value());
    const double err = std::abs(run.value() - exact) / exact;
    std::printf("one_robot_axis_energy N_t=%d E=%.7f closed form=%.7f rel.error=%.3e\n", steps,
                run.value(), exact, err);
    expect_converging(err, previous, steps, 50, 5e-3);
    // It rests for T - tau: at least that many intervals, less one for the discretisation,
    // end at zero speed (the floor holds it, no push).
    const auto vx = sol["robots"][0]["vx"].get<std::vector<double>>();
    const double h = T / steps;
    int resting = 0;
    for (double v : vx) resting += std::abs(v) < 1e-6 ? 1 : 0;
    EXPECT_GE(resting, static_cast<int>((T - tau) / h) - 1) << "states at rest";
  }
}

TEST(ClosedForm, LeastTimePlusEffortPicksTheBalancedHorizon) {
  const std::string path = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/one_robot_axis.yaml";
  const double w = 0.5;
  const Scene scene = load_scene(
      path, {"steps=50", "objective={kind: time + energy, energy_weight: " + std::to_string(w) + "}"});
  ASSERT_EQ(scene.objective.kind, ObjectiveKind::kTimeEnergy);
  const AxisMove m = axis_move(scene);
  const double T = std::pow(36.0 * w * m.D * m.D * m.M * m.M / (1.0 + w * m.f * m.f), 0.25);
  ASSERT_LE(6.0 * m.D * m.M / (T * T) + m.f, m.F_max) << "the cubic move is within the force bound";
  const double exact = T + w * move_energy(m, T);

  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  ASSERT_TRUE(run.solved()) << to_string(run.info.status);
  const nlohmann::json sol = solution_json(*run.problem, run.z, run.info);
  EXPECT_NEAR(run.value(), run.T_f() + w * energy_of(sol), 1e-9 * run.value());
  const double err = std::abs(run.value() - exact) / exact;
  std::printf("one_robot_axis time + %.2f energy N_t=50 J=%.7f (T_f %.6f) closed form=%.7f (T %.6f) "
              "rel.error=%.3e\n", w, run.value(), run.T_f(), exact, T, err);
  EXPECT_LE(err, 5e-3) << "N_t = 50 must be within 0.5 %";
  EXPECT_NEAR(run.T_f(), T, 0.01 * T) << "the balanced horizon, not the least time 3.075 s";
}

}  // namespace
}  // namespace disco
