#include "search/start.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/util/check.h"
#include "search/guess.h"

// How the starts are made.
//
// Parameters. Start `index` >= 1 draws, in this fixed order, from a
// std::mt19937_64 (fully specified by the standard) seeded with FNV-1a over
// (seed, scene name, index, stream 0): horizon_factor, rate, grow, shrink,
// perturbation, zeta, min_rate, T_scale, margin (the last three were added
// later, after the others, so that those keep their values). Uniform reals are made here
// from the generator's bits (std::uniform_real_distribution is
// implementation-defined), so a start is the same with any standard library.
// Every draw is made whatever the kind, so the kind never shifts the other
// parameters.
//
// Kinds. With a conflicting pair (search/guess.h, conflicts), (index - 1) % 5 = 0: detour left,
// 1: detour right, 2: yield, 3: perturbed, 4: perturbed feasible (detours
// first: on the paper's A3/A4 they reached the best optima, perturbed starts
// rarely did; under a time budget the first starts are the ones that run).
// "Left" and "right" are side patterns: the scene's m-th detour start (m = 2 ((index - 1)
// / 5) + 0 for the left slot, + 1 for the right) takes pattern m of the order all left, all
// right, then the mixed patterns 1, 2, ..., 2^k - 2 (bit p: conflicting pair p on the right),
// cyclically, for k <= kEnumeratedPairs conflicting pairs: so the first 2^k detour starts
// try every way around of the conflicting pairs (start 1 all left and start 2 all right, as
// before patterns). With more pairs, m >= 2 draws its pattern (stream 2).
// Yield starts likewise: the scene's m-th yield start (m = (index - 1) / 5) takes the m-th
// order of yield_order() (who goes first in each conflicting pair), for k <= kEnumeratedPairs;
// with more pairs its order is drawn (search/guess.h).
// Without one (detours and yields would be the straight guess), perturbed and
// perturbed feasible alternate: (index - 1) % 2 = 0: perturbed, 1: perturbed
// feasible.
// The guesses themselves are made in search/guess.h.

namespace disco {
namespace {

// FNV-1a, 64 bits, over an explicit little-endian byte sequence.
class Fnv1a {
 public:
  void byte(std::uint8_t b) {
    h_ ^= b;
    h_ *= 1099511628211ull;
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) byte(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void text(const std::string& s) {
    u64(s.size());
    for (char c : s) byte(static_cast<std::uint8_t>(c));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

}  // namespace

std::mt19937_64 start_generator(std::uint64_t seed, const std::string& scene, int index,
                                std::uint64_t stream) {
  Fnv1a f;
  f.text("disco start");
  f.u64(seed);
  f.text(scene);
  f.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(index)));
  f.u64(stream);
  return std::mt19937_64(f.value());
}

double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& g, double lo, double hi) { return lo + (hi - lo) * uniform01(g); }

std::string to_string(GuessKind kind) {
  switch (kind) {
    case GuessKind::kStraight: return "straight";
    case GuessKind::kPerturbed: return "perturbed";
    case GuessKind::kDetour: return "detour";
    case GuessKind::kPerturbedFeasible: return "perturbed feasible";
    case GuessKind::kYield: return "yield";
    case GuessKind::kGiven: return "given";
  }
  return "unknown";
}

GuessKind guess_kind_from_string(const std::string& text) {
  for (GuessKind k : {GuessKind::kStraight, GuessKind::kPerturbed, GuessKind::kDetour,
                      GuessKind::kPerturbedFeasible, GuessKind::kYield, GuessKind::kGiven})
    if (to_string(k) == text) return k;
  throw std::invalid_argument("unknown guess kind '" + text + "'");
}

// The guess and its parameters, e.g. "detour left".
static std::string guess_text(const StartSpec& s) {
  std::string kind = to_string(s.guess);
  char buf[64];
  if (s.guess == GuessKind::kDetour) {
    if (s.detour_side != 0) {
      kind += s.detour_side > 0 ? " left" : " right";
    } else {  // one letter per conflicting pair
      kind += " ";
      for (int k = 0; k < s.detour_pairs; ++k) kind += (s.detour_pattern >> k & 1u) ? 'R' : 'L';
    }
  } else if (s.guess == GuessKind::kPerturbed) {
    std::snprintf(buf, sizeof buf, " %.2f", s.perturbation);
    kind += buf;
  } else if (s.guess == GuessKind::kPerturbedFeasible) {
    std::snprintf(buf, sizeof buf, " %.2f, T x%.2f", s.perturbation, s.T_scale);
    kind += buf;
  } else if (s.guess == GuessKind::kYield) {
    std::snprintf(buf, sizeof buf, " margin %.2f", s.margin);
    kind += buf;
    if (!s.yield_order.empty()) {
      kind += ", order";
      for (std::size_t q = 0; q < s.yield_order.size(); ++q)
        kind += (q == 0 ? " " : ",") + std::to_string(s.yield_order[q]);
    }
  } else if (s.guess == GuessKind::kGiven) {
    std::snprintf(buf, sizeof buf, " (T_f %.6f s)", s.given.seconds);
    kind += " " + s.given.source + buf;
  }
  if (s.schedule.coarse_fraction > 0.0 && s.guess != GuessKind::kGiven) {
    std::snprintf(buf, sizeof buf, ", coarse %.2f N_t first", s.schedule.coarse_fraction);
    kind += buf;
  }
  return kind;
}

nlohmann::json StartSpec::schedule_json() const {
  return {{"horizon_factor", schedule.horizon_factor}, {"rate", schedule.rate},
          {"grow", schedule.grow},                     {"shrink", schedule.shrink},
          {"min_rate", schedule.min_rate},             {"zeta", elastic.zeta},
          {"minimize_weak", schedule.weak_homotopy ? "homotopy" : "penalty"}};
}

std::string StartSpec::describe() const {
  const std::string kind = guess_text(*this);
  char line[256];
  std::snprintf(line, sizeof line,
                "start %d: %s, horizon x%.2f, rate %.3f, grow %.2f, shrink %.2f, min rate %.4f, "
                "zeta %g",
                index, kind.c_str(), schedule.horizon_factor, schedule.rate, schedule.grow,
                schedule.shrink, schedule.min_rate, elastic.zeta);
  return meet_turners ? std::string(line) + ", turners meet partners" : std::string(line);
}

StartSpec with_guess(StartSpec start, Trajectory trajectory) {
  DISCO_CHECK(!trajectory.empty() && trajectory.seconds > 0.0, "a trajectory with a horizon");
  start.guess = GuessKind::kGiven;
  start.given = std::move(trajectory);
  return start;
}

std::vector<int> yield_order(const Scene& scene, int m) {
  DISCO_CHECK(m >= 0, "yield starts are counted from 0");
  const std::vector<Conflict> cs = conflicts(scene);
  const int k = static_cast<int>(cs.size()), nr = static_cast<int>(scene.robots.size());
  if (k == 0 || k > kEnumeratedPairs) return {};
  // The orders of the patterns 0 .. 2^k - 1 that have one (no cycle of precedences).
  std::vector<std::vector<int>> orders;
  for (std::uint64_t pattern = 0; pattern < (std::uint64_t{1} << k); ++pattern) {
    std::vector<int> before(nr, 0);  // how many robots must go before robot r
    std::vector<std::vector<int>> after(nr);
    for (int p = 0; p < k; ++p) {
      const bool swapped = pattern >> p & 1u;
      const int first = swapped ? cs[p].j : cs[p].i, second = swapped ? cs[p].i : cs[p].j;
      after[first].push_back(second);
      ++before[second];
    }
    std::vector<int> order;  // Kahn's algorithm, the lowest free index first
    std::vector<bool> placed(nr, false);
    for (int n = 0; n < nr; ++n) {
      int next = -1;
      for (int r = 0; r < nr && next < 0; ++r)
        if (!placed[r] && before[r] == 0) next = r;
      if (next < 0) break;  // a cycle: no order gives this pattern
      placed[next] = true;
      order.push_back(next);
      for (int r : after[next]) --before[r];
    }
    if (static_cast<int>(order.size()) == nr) orders.push_back(std::move(order));
  }
  DISCO_CHECK(!orders.empty(), "pattern 0 (each pair's lower index first) is acyclic");
  return orders[static_cast<std::size_t>(m) % orders.size()];
}

StartSpec make_start(const Scene& scene, std::uint64_t seed, int index,
                     const ReductionSettings& base_schedule, const ElasticSettings& base_elastic) {
  DISCO_CHECK(index >= 0, "start indices are >= 0");
  StartSpec s;
  s.index = index;
  s.seed = seed;
  s.schedule = base_schedule;
  s.elastic = base_elastic;
  // Turners meet partners (search/guess.h) in start 0 and in pairs of starts, 1-2, 5-6, ...:
  // both guess kinds of a scene without conflicts, with and without the meeting.
  s.meet_turners = (index == 0 || (index - 1) / 2 % 2 == 0) && !meetings(scene).empty();
  if (index == 0) return s;  // the plain start: straight guess, settings as given

  std::mt19937_64 g = start_generator(seed, scene.name, index, 0);
  s.schedule.horizon_factor = uniform(g, 1.2, 3.0);
  s.schedule.rate = uniform(g, 0.02, 0.2);
  s.schedule.grow = uniform(g, 1.2, 2.0);
  s.schedule.shrink = uniform(g, 0.3, 0.7);
  const double perturbation = uniform(g, 0.05, 0.3);
  static constexpr double kZeta[3] = {1.0, 10.0, 100.0};  // uniform in log10(zeta)
  s.elastic.zeta = kZeta[std::min(2, static_cast<int>(3.0 * uniform01(g)))];
  // Added after the draws above: those keep their values.
  s.schedule.min_rate = uniform(g, 0.005, 0.02);
  const double T_scale = uniform(g, 0.8, 1.0);
  const double margin = uniform(g, 1.0, 1.5);

  enum { kPerturbedSlot, kLeft, kRight, kFeasibleSlot, kYieldSlot } slot;
  const int pairs = static_cast<int>(conflicts(scene).size());
  if (pairs == 0) {
    slot = (index - 1) % 2 == 0 ? kPerturbedSlot : kFeasibleSlot;
  } else {
    static constexpr decltype(slot) kCycle[5] = {kLeft, kRight, kYieldSlot, kPerturbedSlot,
                                                 kFeasibleSlot};
    slot = kCycle[(index - 1) % 5];
  }
  switch (slot) {
    case kLeft:
    case kRight: {
      s.guess = GuessKind::kDetour;
      s.detour_pairs = pairs;
      // The scene's m-th detour start (m = 0, 1, 2, ...): all left, all right, then the
      // mixed patterns, enumerated for up to kEnumeratedPairs conflicting pairs, else drawn.
      const int m = 2 * ((index - 1) / 5) + (slot == kRight ? 1 : 0);
      const std::uint64_t all = pairs >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << pairs) - 1;
      std::uint64_t pattern = 0;
      if (pairs <= kEnumeratedPairs) {
        const int j = m % (1 << pairs);
        pattern = j == 0 ? 0 : j == 1 ? all : static_cast<std::uint64_t>(j - 1);
      } else if (m == 1) {
        pattern = all;
      } else if (m >= 2) {
        std::mt19937_64 bits = start_generator(seed, scene.name, index, 2);
        pattern = bits() & all;
      }
      s.detour_pattern = pattern;
      s.detour_side = pattern == 0 ? +1 : pattern == all ? -1 : 0;
      break;
    }
    case kPerturbedSlot:
      s.guess = GuessKind::kPerturbed;
      s.perturbation = perturbation;
      break;
    case kFeasibleSlot:
      s.guess = GuessKind::kPerturbedFeasible;
      s.perturbation = perturbation;
      s.T_scale = T_scale;
      break;
    case kYieldSlot:
      s.guess = GuessKind::kYield;
      s.margin = margin;
      s.yield_order = yield_order(scene, (index - 1) / 5);
      break;
  }
  return s;
}

}  // namespace disco
