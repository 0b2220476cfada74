// disco — what the model minimises (scene file `objective`, core/model/scene.h).
//
//     time          J = T_f                                  (the paper's, Section IV)
//     energy        J = E = sum_i sum_{t<N} h |F_i^t|^2      at T_f fixed to `horizon`
//     time + energy J = T_f + w E
// with h = T_f / N and F_i^t robot i's control force over interval t (objects have none).
// E is the squared-force effort of the controls (N^2 s), the paper's "other objectives"
// (Section VI: "can be optimized by just changing the model objective"). Every term is a
// polynomial of degree <= 3 (h F_x F_x), so derivatives stay exact.
//
// The objective reduction bounds J (J <= (1 - r) J_best, search/objective_reduction.h):
// for time that is the bound on the unknown T_f; otherwise a constraint row carrying the
// same polynomial (add_objective_row), whose bounds RobotProblem sets.
#pragma once

#include <string>

#include "core/model/layout.h"
#include "core/model/units.h"

namespace disco {

// Adds J (model units) to the objective of P.
void add_objective(const Layout& L, PolynomialProgram& P);
// A row lo <= J <= hi (free until bounded), for objectives other than time; its index.
int add_objective_row(const Layout& L, PolynomialProgram& P);

// "time", "energy", "time + energy": the scene file's words.
std::string to_string(ObjectiveKind kind);
// The unit of J in SI: "s" (time, time + energy) or "N^2 s" (energy).
std::string objective_unit(ObjectiveKind kind);
// J's SI value per model-unit value: the time unit, or force^2 x time for energy.
double objective_scale(ObjectiveKind kind, const Units& u);

}  // namespace disco
