#include "core/model/objective.h"

#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

// Adds J (model units: the model scene's horizon and weight) to row r of P.
void add_terms(const Layout& L, PolynomialProgram& P, int r) {
  const Objective& o = L.model_scene().objective;
  if (o.kind != ObjectiveKind::kEnergy) P.add(r, 1.0, L.horizon());
  if (o.kind == ObjectiveKind::kTime) return;
  const double w = o.kind == ObjectiveKind::kEnergy ? 1.0 : o.energy_weight;
  L.for_each_robot_step([&](int t, int i) {
    if (L.model_scene().robots[i].object) return;
    for (int a = 0; a < 2; ++a) {
      const Affine F = L.force(i, t, a);
      P.add(r, w, L.step(), F, F);  // w h F_a^2
    }
  });
}

}  // namespace

void add_objective(const Layout& L, PolynomialProgram& P) { add_terms(L, P, PolynomialProgram::kObjective); }

int add_objective_row(const Layout& L, PolynomialProgram& P) {
  DISCO_CHECK(L.model_scene().objective.kind != ObjectiveKind::kTime,
              "time is bounded through T_f itself");
  const int r = P.add_row(-kInf, kInf);
  add_terms(L, P, r);
  return r;
}

std::string to_string(ObjectiveKind kind) {
  switch (kind) {
    case ObjectiveKind::kTime: return "time";
    case ObjectiveKind::kEnergy: return "energy";
    case ObjectiveKind::kTimeEnergy: return "time + energy";
  }
  return "?";
}

std::string objective_unit(ObjectiveKind kind) { return kind == ObjectiveKind::kEnergy ? "N^2 s" : "s"; }

double objective_scale(ObjectiveKind kind, const Units& u) {
  return kind == ObjectiveKind::kEnergy ? u.force() * u.force() * u.time : u.time;
}

}  // namespace disco
