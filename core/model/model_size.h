// disco — how big a scene's model is and how much memory a solve of it needs, known before
// anything is built; and the guard that refuses a scene too big for the machine
// (model.memory_limit in configs/disco.yaml, read by core/config/solver_settings.h, memory_limit).
//
// Counts. Every constraint family states what holds at one step (core/model/layout.h), so
// a model with every pair at every step (the full model, and the adaptive model with an
// unbounded horizon: core/model/model_plan.h) has counts affine in N_t from N_t = 2 on. The
// counts of the two models at N_t = 2 and 3 (a few hundred unknowns each, built in well under
// a millisecond) give them exactly at any N_t, in O(robots + pairs), whatever N_t is.
// Counted: the elastic NLP handed to Ipopt (core/elastic/elastic_nlp.h, lumped: one slack
// per row side, eps and its row): variables n, rows m and the nonzeros nz of its Jacobian
// and Hessian (lower triangle).
//
// Which model. A solve builds the adaptive model for an unbounded horizon
// (RobotProblem's constructor), rebuilds it at each feasibility horizon
// (RobotProblem::set_horizon_max) and solves that, and builds the full model once to
// certify the answer (search/solve_scene.cpp). Each adaptive model is a part of the
// unbounded one, so the unbounded one's counts bound every model solved; the full model is
// only built, never solved: building takes about half of what solving the same model
// does (--model-only against a solve, below), and its counts are at most 1.1 times the
// unbounded adaptive model's. With model.adaptive false the full model is the one solved
// and counted.
//
// Memory. The peak resident memory of a solve is estimated as
//     bytes = 16 MiB + 500 B * nz + 1 B * s^2 * N_t,     s = (n + m) / N_t:
// the process itself (disco and its libraries: 13.4 MiB measured); per nonzero, disco's
// program (its monomials and the contributions of every derivative entry,
// core/nlp/polynomial_program.h), the elastic NLP's copies, Ipopt's KKT matrix and its
// iteration vectors, MUMPS's analysis and factor at light coupling; and the fill-in of
// MUMPS's factor, which grows with the square of what one step couples (s, the KKT's size
// per step: 60 for one robot, 1600 for twelve robots all in contact).
//
// Calibration: peak RSS (/usr/bin/time -f %M) on the 2-core 24 GiB machine, of
//   disco solve SCENE --set scene.steps=N --set ipopt.max_iter=5 --out DIR
// (every elastic-mode solve capped at 5 Ipopt iterations: the factorisations, not the
// iterations, make the peak). nz and s are those of the estimate (unbounded adaptive model).
//   scene                  N_t      nz     s   measured   estimate  ratio
//   one_robot_axis        2000   392 k    60   156 MiB    210 MiB   1.34
//   one_robot_axis       10000  1960 k    60   675 MiB    985 MiB   1.46
//   steps_1000            1000   196 k    60    86 MiB    113 MiB   1.32
//   two_robots_swap_avoid  500   204 k   124    82 MiB    121 MiB   1.46
//   two_robots_swap_avoid 1000   408 k   124   148 MiB    225 MiB   1.52
//   three_robots_contact   200   189 k   231    78 MiB    117 MiB   1.49
//   three_robots_contact   500   474 k   231   176 MiB    267 MiB   1.52
//   twelve_robots          100   185 k   564    85 MiB    134 MiB   1.59
//   twelve_robots          300   554 k   564   198 MiB    371 MiB   1.88
//   K_64                   300   218 k   205    91 MiB    132 MiB   1.44
//   paper B2               300   284 k   231   127 MiB    167 MiB   1.31
//   forced_contact         300   158 k   140    75 MiB     97 MiB   1.30
//   paper A4               300   158 k   180    85 MiB    101 MiB   1.18
//   A4, all pairs contact  100   279 k   570   141 MiB    180 MiB   1.28
//   A4, all pairs contact  300   838 k   570   372 MiB    509 MiB   1.37
//   12 robots crossing,     50   456 k  1572   292 MiB    351 MiB   1.20
//     all pairs contact
// Whole solves (no cap) peaked at 85 MiB (steps_1000; capped 86), 85 MiB (twelve_robots,
// N_t = 100; capped 85) and 91 MiB (three_robots_contact, N_t = 200, stopped after 390 s;
// capped 78): 500 B rather than the 450 B the capped runs ask for keeps that last one at
// 1.28. Without the s^2 term the 12-robot contact scene would be estimated at 0.99 of its
// capped peak. --model-only (building only) peaked at 42 MiB for one_robot_axis at N_t =
// 1000 and 1.38 GiB at 50000 (0.4 and 0.3 of the estimate of a solve).
#pragma once

#include <string>

#include "core/model/scene.h"

namespace disco {

struct ModelSizeEstimate {
  int steps = 0;
  // Of the elastic NLP of the largest model a solve builds (doubles: N_t may be 2^31 - 1).
  double variables = 0, rows = 0, nonzeros = 0;
  double bytes = 0;  // peak memory of a solve
  // "about 3.9 GiB (2.2e+06 variables, 2.1e+06 rows, 1.1e+07 Jacobian and Hessian nonzeros)"
  std::string describe() const;
};

// The estimate for `scene` (SI units, as read) with model.adaptive = `adaptive`. Builds
// nothing larger than the model at N_t = 3.
ModelSizeEstimate estimate_model_size(const Scene& scene, bool adaptive);

// The memory a model may take (model.memory_limit), and where it was set, for messages.
struct MemoryLimit {
  double bytes = 0;   // > 0
  std::string where;  // "FILE:LINE" of the setting, or "--set"
  std::string auto_meaning;  // for `auto`: "auto = half of the machine's 23.5 GiB"; else ""
};
inline constexpr const char* kMemoryLimitKey = "model.memory_limit";

// Estimates the model of `scene` and throws InputError if it exceeds limit.bytes /
// processes (the processes of one search on this machine share the limit). The message
// names where the scene's `steps` was given (file and line, or --set), the estimate, N_t,
// the limit and where it was set. Returns the estimate.
ModelSizeEstimate check_model_size(const Scene& scene, bool adaptive, const MemoryLimit& limit,
                                   int processes = 1);

// The message for a std::bad_alloc caught while `doing` something with `scene`:
// "out of memory while DOING; the model's estimate was about ... (model.memory_limit ...)".
std::string out_of_memory_message(const std::string& doing, const Scene& scene, bool adaptive);

// "3.9 GiB" (one decimal), "512 MiB" below 1 GiB.
std::string memory_text(double bytes);

}  // namespace disco
