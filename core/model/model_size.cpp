#include "core/model/model_size.h"

#include <fmt/format.h>

#include <array>
#include <new>

#include "core/elastic/elastic_nlp.h"
#include "core/model/robot_problem.h"
#include "core/util/errors.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

// The calibration of the header comment.
constexpr double kProcessBytes = 16.0 * (1 << 20);
constexpr double kBytesPerNonzero = 500.0;
constexpr double kBytesPerStepCoupling = 1.0;  // times s^2 per step

struct Counts {
  double variables = 0, rows = 0, nonzeros = 0;
};

// The elastic NLP's counts of the model with every pair at every step (adaptive or full),
// built at `steps`.
Counts build_counts(Scene scene, bool adaptive, int steps) {
  scene.steps = steps;
  const RobotProblem problem(scene, ModelOptions{adaptive, kInf});
  const ElasticNlp nlp(problem.program(), ElasticFormulation::kLumped, 1.0);
  return {static_cast<double>(nlp.num_variables()), static_cast<double>(nlp.num_constraints()),
          static_cast<double>(nlp.jacobian_pattern().size() + nlp.hessian_pattern().size())};
}

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string memory_text(double bytes) {
  const double gib = bytes / (1024.0 * 1024.0 * 1024.0);
  if (gib >= 1.0) return fmt::format("{:.1f} GiB", gib);
  return fmt::format("{:.0f} MiB", bytes / (1024.0 * 1024.0));
}

std::string ModelSizeEstimate::describe() const {
  return fmt::format(
      "about {} ({:.2g} variables, {:.2g} rows, {:.2g} Jacobian and Hessian nonzeros)",
      memory_text(bytes), variables, rows, nonzeros);
}

ModelSizeEstimate estimate_model_size(const Scene& scene, bool adaptive) {
  ModelSizeEstimate e;
  e.steps = scene.steps;
  const double N = scene.steps;
  Counts c;
  if (scene.steps <= 3) {
    c = build_counts(scene, adaptive, scene.steps);
  } else {  // affine in N_t from 2 on (header)
    const Counts a = build_counts(scene, adaptive, 2), b = build_counts(scene, adaptive, 3);
    auto at = [&](double x2, double x3) { return x2 + (N - 2.0) * (x3 - x2); };
    c = {at(a.variables, b.variables), at(a.rows, b.rows), at(a.nonzeros, b.nonzeros)};
  }
  e.variables = c.variables;
  e.rows = c.rows;
  e.nonzeros = c.nonzeros;
  const double s = (c.variables + c.rows) / N;  // the KKT's size per step
  e.bytes = kProcessBytes + kBytesPerNonzero * c.nonzeros + kBytesPerStepCoupling * s * s * N;
  return e;
}

ModelSizeEstimate check_model_size(const Scene& scene, bool adaptive, const MemoryLimit& limit,
                                   int processes) {
  const ModelSizeEstimate e = estimate_model_size(scene, adaptive);
  const double share = limit.bytes / processes;
  if (e.bytes <= share) return e;
  const KeyOrigin& o = scene.steps_origin;
  // A scene made in code has no origin: its source, without a line.
  const bool known = !o.source.empty();
  const std::string source = known ? o.source : !scene.source.empty() ? scene.source : "scene";
  std::string limit_text =
      fmt::format("{} = {} ({}{}{})", kMemoryLimitKey, memory_text(limit.bytes), limit.where,
                  limit.auto_meaning.empty() ? "" : "; ", limit.auto_meaning);
  if (processes > 1)
    limit_text += fmt::format(
        ", shared by the {} processes of this search on this machine: {} each", processes,
        memory_text(share));
  throw InputError(located_message(
      source, known ? o.line : 0, known ? o.key : "steps",
      fmt::format("the model would need {} at N_t = {} steps of {} and {}, above {}; lower steps "
                  "or raise {}",
                  e.describe(), scene.steps, plural(scene.robots.size(), "robot", "robots"),
                  plural(scene.pairs.size(), "pair", "pairs"), limit_text, kMemoryLimitKey)));
}

std::string out_of_memory_message(const std::string& doing, const Scene& scene, bool adaptive) {
  std::string estimate = "unknown";
  try {
    estimate = estimate_model_size(scene, adaptive).describe();
  } catch (const std::bad_alloc&) {
  }
  return fmt::format("out of memory while {} (N_t = {}; the model's estimate: {}); lower steps, "
                     "free memory, or lower {} so that such a scene is refused before it is built",
                     doing, scene.steps, estimate, kMemoryLimitKey);
}

}  // namespace disco
