// Factorisation and solve of dumped KKT matrices by MUMPS and by disco's LDLᵀ (a benchmark, not a
// test: scripts/bench_kkt runs it on the corpus it dumps and writes the table; issue 33).
//
//   bench_kkt FILE.kkt... [--repeat R] [--settings FILE] [--set KEY=VALUE ...] | --version
//
// FILE: a KKT matrix written by `disco solve --set kkt.dump.every=N` (the format:
// core/ipopt/kkt_solver.h). Per file, on the machine's clock (Stopwatch), medians over R runs
// (default 7):
//   - mumps: sequential MUMPS through dmumps_c, set up as Ipopt 3.11.9's MumpsSolverInterface
//     sets it up (sym 2, par 1, no output, ICNTL(13) 1, no refinement: ICNTL(10) 0, and the
//     ipopt.mumps_* options of the settings file, else Ipopt's defaults); analysis (job 1) once,
//     factorisation (job 2) and solve (job 3) timed. Inertia: INFOG(12); INFO(1) < 0 is a failure
//     (−10: singular).
//   - mumps_check: MUMPS once more, untimed, with the AMD ordering (ICNTL(7) 0) and a pivot
//     threshold of 0.01: where its inertia differs from mumps's, roundoff decides the inertia
//     (scripts/bench_kkt then calls MUMPS's ambiguous).
//   - ldlt: disco's SparseLdlt (core/linalg/sparse_ldlt.h) with the kkt.ldlt settings; analyse()
//     once, factor() and solve() (which refines) timed. Inertia: negative(); status "unstable"
//     when its growth() is above kkt.ldlt.growth_limit (disco gives that matrix to MUMPS);
//     smallest_eigenvalue and certified: the inertia certificate (kkt.ldlt.certificate), which
//     disco asks for when the inertia is not the one Ipopt wants (uncertified: to MUMPS).
//   - ldlt and pivoted also report their analysis, timed once: analyse_ms, and the ordering it
//     chose (kkt.ldlt.ordering): ordering "amd" or "nested_dissection", amd_flops and
//     nested_dissection_flops (null when not computed).
// Each solve's x is checked here, the same way for both: the normwise backward error
// ‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞) against the file's right-hand side b (null when x is not finite).
//
// Output (stdout), JSON lines: first {"settings", "repeat", "mumps": its options, "ldlt": its
// settings}, then one object per file: file, n, nnz, dual_from, check_inertia, expected_negative,
// and per solver factor_ms, solve_ms, negative, backward_error and what else the solver tells.
// Exit status 2 for bad arguments, settings or files (the message names the file).
#include <dmumps_c.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/ipopt/kkt_solver.h"  // the file format
#include "core/linalg/pivoted_ldlt.h"
#include "core/linalg/sparse_ldlt.h"
#include "core/util/clock.h"
#include "core/util/errors.h"
#include "core/util/provenance.h"

using namespace disco;
using nlohmann::json;

namespace {

struct KktFile {
  int n = 0, nnz = 0, dual_from = 0, expected_negative = 0;
  bool check_inertia = false;
  std::vector<int> ia, ja;
  std::vector<double> values, rhs;
};

template <class T>
void read(std::ifstream& in, T* data, size_t count, const std::string& path) {
  if (!in.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(sizeof(T) * count)))
    throw InputError(path + ": truncated KKT file");
}

KktFile read_kkt(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  char magic[8];
  read(in, magic, 8, path);
  if (std::memcmp(magic, kKktFileMagic, 8) != 0) throw InputError(path + ": not a KKT file");
  int32_t head[6];  // version, n, nnz, dual_from, check_inertia, expected_negative
  read(in, head, 6, path);
  if (head[0] != kKktFileVersion)
    throw InputError(path + ": KKT file version " + std::to_string(head[0]) + ", expected " +
                     std::to_string(kKktFileVersion));
  KktFile k;
  k.n = head[1], k.nnz = head[2], k.dual_from = head[3];
  k.check_inertia = head[4] != 0, k.expected_negative = head[5];
  if (k.n <= 0 || k.nnz <= 0 || k.dual_from < 0 || k.dual_from > k.n)
    throw InputError(path + ": bad sizes (n " + std::to_string(k.n) + ", nnz " +
                     std::to_string(k.nnz) + ", dual_from " + std::to_string(k.dual_from) + ")");
  k.ia.resize(k.nnz), k.ja.resize(k.nnz), k.values.resize(k.nnz), k.rhs.resize(k.n);
  read(in, k.ia.data(), k.nnz, path);
  read(in, k.ja.data(), k.nnz, path);
  read(in, k.values.data(), k.nnz, path);
  read(in, k.rhs.data(), k.n, path);
  for (int t = 0; t < k.nnz; ++t)
    if (k.ia[t] < 1 || k.ia[t] > k.n || k.ja[t] < 1 || k.ja[t] > k.n)
      throw InputError(path + ": triplet " + std::to_string(t) + " outside 1.." +
                       std::to_string(k.n));
  if (in.peek() != std::ifstream::traits_type::eof())
    throw InputError(path + ": bytes after the rhs");
  return k;
}

// The matrix of a file with its repeats summed, one entry per (i ≤ j), to check solutions with.
struct Symmetric {
  std::vector<int> row, col;  // 0-based, row ≤ col
  std::vector<double> value;
  double norm = 0.0;  // ‖A‖∞
};

Symmetric merged(const KktFile& k) {
  auto key = [&](int t) {
    const int64_t i = std::min(k.ia[t], k.ja[t]) - 1, j = std::max(k.ia[t], k.ja[t]) - 1;
    return i * k.n + j;
  };
  std::vector<int> order(k.nnz);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  Symmetric a;
  for (size_t s = 0; s < order.size(); ++s) {
    const int t = order[s];
    if (s > 0 && key(t) == key(order[s - 1])) {
      a.value.back() += k.values[t];
      continue;
    }
    a.row.push_back(static_cast<int>(key(t) / k.n));
    a.col.push_back(static_cast<int>(key(t) % k.n));
    a.value.push_back(k.values[t]);
  }
  std::vector<double> sums(k.n, 0.0);
  for (size_t e = 0; e < a.value.size(); ++e) {
    sums[a.row[e]] += std::abs(a.value[e]);
    if (a.row[e] != a.col[e]) sums[a.col[e]] += std::abs(a.value[e]);
  }
  a.norm = *std::max_element(sums.begin(), sums.end());
  return a;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// ‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞); null when x is not finite.
json backward_error(const Symmetric& a, const std::vector<double>& b,
                    const std::vector<double>& x) {
  if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) return nullptr;
  std::vector<double> r = b;
  for (size_t e = 0; e < a.value.size(); ++e) {
    r[a.row[e]] -= a.value[e] * x[a.col[e]];
    if (a.row[e] != a.col[e]) r[a.col[e]] -= a.value[e] * x[a.row[e]];
  }
  return max_abs(r) / (a.norm * max_abs(x) + max_abs(b));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

// Milliseconds of `step` (run `repeat` times, `before` untimed ahead of each): the median.
template <class Before, class Step>
double median_ms(int repeat, Before before, Step step) {
  std::vector<double> ms;
  for (int r = 0; r < repeat; ++r) {
    before();
    const Stopwatch watch;
    step();
    ms.push_back(1e3 * watch.seconds());
  }
  return median(ms);
}

// Ipopt 3.11.9's MUMPS options (IpMumpsSolverInterface.cpp) as the settings file gives them to
// Ipopt, with Ipopt's defaults for those it leaves out.
struct MumpsOptions {
  double pivtol = 1e-6;       // mumps_pivtol: CNTL(1)
  int mem_percent = 1000;     // mumps_mem_percent: ICNTL(14)
  int permuting_scaling = 7;  // mumps_permuting_scaling: ICNTL(6)
  int pivot_order = 7;        // mumps_pivot_order: ICNTL(7)
  int scaling = 77;           // mumps_scaling: ICNTL(8)
};

MumpsOptions mumps_options(const Settings& settings) {
  MumpsOptions o;
  for (const auto& e : settings.section("ipopt")) {
    const std::string key = "ipopt." + e.name;
    if (e.name == "mumps_pivtol") o.pivtol = settings.number(key);
    if (e.name == "mumps_mem_percent") o.mem_percent = settings.integer(key);
    if (e.name == "mumps_permuting_scaling") o.permuting_scaling = settings.integer(key);
    if (e.name == "mumps_pivot_order") o.pivot_order = settings.integer(key);
    if (e.name == "mumps_scaling") o.scaling = settings.integer(key);
  }
  return o;
}

constexpr int kMumpsCommWorld = -987654;  // USE_COMM_WORLD of MUMPS's Fortran interface

json run_mumps(const KktFile& k, const Symmetric& a, const MumpsOptions& o, int repeat) {
  auto m = std::make_unique<DMUMPS_STRUC_C>();
  m->job = -1, m->par = 1, m->sym = 2, m->comm_fortran = kMumpsCommWorld;
  dmumps_c(m.get());
  // No output: Ipopt silences ICNTL(2..4) and leaves MUMPS's error messages on (ICNTL(1) 6), which
  // would land among the JSON lines; nothing else depends on them.
  m->icntl[0] = m->icntl[1] = m->icntl[2] = m->icntl[3] = 0;
  std::vector<double> values = k.values;
  std::vector<int> ia = k.ia, ja = k.ja;
  m->n = k.n, m->nz = k.nnz, m->irn = ia.data(), m->jcn = ja.data(), m->a = values.data();
  m->icntl[5] = o.permuting_scaling, m->icntl[6] = o.pivot_order, m->icntl[7] = o.scaling;
  m->icntl[9] = 0;  // no iterative refinement
  m->icntl[12] = 1, m->icntl[13] = o.mem_percent;
  m->cntl[0] = o.pivtol;
  json out;
  m->job = 1;
  dmumps_c(m.get());
  if (m->info[0] >= 0) {
    out["factor_ms"] = median_ms(
        repeat, [] {},
        [&] {
          m->job = 2;
          dmumps_c(m.get());
          // Ipopt doubles ICNTL(14) and factorises again while MUMPS runs out of working space.
          for (int attempt = 0; attempt < 20 && (m->info[0] == -8 || m->info[0] == -9); ++attempt) {
            m->icntl[13] *= 2;
            dmumps_c(m.get());
          }
        });
  }
  out["info1"] = m->info[0];
  if (m->info[0] >= 0) {
    out["negative"] = m->infog[11];
    out["flops"] = m->rinfog[2];
    out["factor_entries"] = m->infog[8];  // INFOG(9): real entries of the factors
    std::vector<double> x;
    out["solve_ms"] = median_ms(
        repeat, [&] { x = k.rhs; },
        [&] {
          m->rhs = x.data();
          m->job = 3;
          dmumps_c(m.get());
        });
    out["solve_info1"] = m->info[0];
    out["backward_error"] = backward_error(a, k.rhs, x);
    // ‖A‖∞ ‖x‖∞ / ‖b‖∞, a lower bound on A's condition number: huge where A is numerically
    // singular (and its inertia decided by roundoff).
    const double nb = max_abs(k.rhs);
    out["growth"] = nb > 0 && std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })
                        ? json(a.norm * max_abs(x) / nb)
                        : json(nullptr);
  }
  m->job = -2;
  dmumps_c(m.get());
  return out;
}

// The solve of one of disco's LDLT solvers, timed (x reset to the rhs before each run), its
// reported and measured backward errors and refinement steps into `out`.
template <class Solver>
void solve_timed(const KktFile& k, const Symmetric& a, Solver& ldlt, int repeat, json& out) {
  std::vector<double> x;
  double reported = 0.0;
  out["solve_ms"] = median_ms(
      repeat, [&] { x = k.rhs; }, [&] { reported = ldlt.solve(x.data()); });
  out["reported_error"] = std::isfinite(reported) ? json(reported) : json(nullptr);
  out["refinement_steps"] = ldlt.last_refinement_steps();
  out["backward_error"] = backward_error(a, k.rhs, x);
}

// The analysis of one of disco's LDLT solvers, timed once: its time and the ordering it chose
// (kkt.ldlt.ordering) with the multiply-adds of each ordering it judged.
template <class Solver>
json analyse_timed(const KktFile& k, const LdltSettings& settings, Solver& ldlt) {
  const Stopwatch clock;
  ldlt.analyse(k.n, k.nnz, k.ia.data(), k.ja.data(), 1, k.dual_from, settings.ordering);
  json out;
  out["analyse_ms"] = clock.seconds() * 1e3;
  const FillReducingOrder& o = ldlt.ordering();
  out["ordering"] = o.ordering == Ordering::kAmd ? "amd" : "nested_dissection";
  out["amd_flops"] = o.amd_flops;
  out["nested_dissection_flops"] =
      o.nested_dissection_flops >= 0 ? json(o.nested_dissection_flops) : json(nullptr);
  return out;
}

json run_ldlt(const KktFile& k, const Symmetric& a, const LdltSettings& settings, int repeat) {
  SparseLdlt ldlt;
  json out = analyse_timed(k, settings, ldlt);
  SparseLdlt::Factorised status = SparseLdlt::Factorised::kDone;
  out["factor_ms"] = median_ms(
      repeat, [] {}, [&] { status = ldlt.factor(k.values.data(), settings); });
  const bool factors = status == SparseLdlt::Factorised::kDone ||
                       status == SparseLdlt::Factorised::kUnstable;
  out["finite"] = factors;
  out["status"] = status == SparseLdlt::Factorised::kDone        ? "done"
                  : status == SparseLdlt::Factorised::kUnstable ? "unstable"
                  : status == SparseLdlt::Factorised::kEmptyRow ? "empty_row"
                                                                 : "not_finite";
  out["empty_rows"] = ldlt.empty_rows();
  if (!factors) return out;
  out["negative"] = ldlt.negative();
  out["perturbed"] = ldlt.perturbed();
  out["regularised"] = ldlt.regularised();
  out["growth"] = ldlt.growth();
  out["factor_entries"] = ldlt.factor_entries();
  out["flops"] = ldlt.flops();
  out["regularisation_norm"] = ldlt.regularisation_norm();
  if (settings.certificate_iterations > 0)
    out["smallest_eigenvalue"] = ldlt.smallest_eigenvalue(settings.certificate_iterations);
  out["certified"] = ldlt.inertia_certified();
  solve_timed(k, a, ldlt, repeat, out);
  return out;
}

json run_pivoted(const KktFile& k, const Symmetric& a, const LdltSettings& settings,
                int repeat) {
  PivotedLdlt ldlt;
  json out = analyse_timed(k, settings, ldlt);
  PivotedLdlt::Factorised status = PivotedLdlt::Factorised::kDone;
  out["factor_ms"] = median_ms(
      repeat, [] {},
      [&] { status = ldlt.factor(k.values.data(), settings, settings.pivot_threshold); });
  const bool factors = status == PivotedLdlt::Factorised::kDone;
  out["finite"] = status != PivotedLdlt::Factorised::kNotFinite;
  out["status"] = status == PivotedLdlt::Factorised::kDone        ? "done"
                  : status == PivotedLdlt::Factorised::kSingular ? "singular"
                  : status == PivotedLdlt::Factorised::kEmptyRow ? "empty_row"
                                                                  : "not_finite";
  out["empty_rows"] = ldlt.empty_rows();
  out["supernodes"] = ldlt.supernodes();
  out["postponed"] = ldlt.postponed();
  out["flops"] = ldlt.flops();
  if (!factors) return out;
  out["negative"] = ldlt.negative();
  out["delayed"] = ldlt.delayed();
  out["two_by_two"] = ldlt.two_by_two();
  out["forced"] = ldlt.forced();
  out["factor_entries"] = ldlt.factor_entries();
  solve_timed(k, a, ldlt, repeat, out);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Factorisation and solve of dumped KKT matrices by MUMPS and by disco's LDLT "
      "(tests/bench_kkt.cpp says how): one JSON line per file on stdout."};
  std::vector<std::string> files, sets;
  int repeat = 7;
  std::string settings_path = default_settings_path();
  app.add_option("files", files, "KKT matrix files (disco solve --set kkt.dump.every=N)")
      ->required();
  app.add_option("--repeat", repeat,
                 "timed factorisations and solves per solver; the median is shown")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--settings", settings_path, "the settings file (kkt.ldlt, ipopt.mumps_*)")
      ->capture_default_str();
  app.add_option("--set", sets, "KEY=VALUE: a settings override");
  app.set_version_flag("--version", disco_version(),
                       "Print disco's version and git commit, and exit");
  CLI11_PARSE(app, argc, argv);
  try {
    Settings settings = Settings::load(settings_path);
    for (const auto& s : sets) settings.apply_override(s);
    const LdltSettings ldlt = ldlt_settings(settings);
    const MumpsOptions mumps = mumps_options(settings);
    // The same matrix by MUMPS again, another ordering (AMD) and a stricter threshold for its
    // pivots: on a matrix whose inertia is determined by its values (not by roundoff), any
    // ordering and pivot sequence give the same one (Sylvester's law of inertia).
    MumpsOptions check = mumps;
    check.pivot_order = 0;
    check.pivtol = 1e-2;
    const json head = {{"settings", settings.source()},
                       {"repeat", repeat},
                       {"mumps",
                        {{"pivtol", mumps.pivtol},
                         {"mem_percent", mumps.mem_percent},
                         {"permuting_scaling", mumps.permuting_scaling},
                         {"pivot_order", mumps.pivot_order},
                         {"scaling", mumps.scaling}}},
                       {"mumps_check", {{"pivtol", check.pivtol}, {"pivot_order", check.pivot_order}}},
                       {"ldlt",
                        {{"scaling_sweeps", ldlt.scaling_sweeps},
                         {"regularisation", ldlt.regularisation},
                         {"residual_tolerance", ldlt.residual_tolerance},
                         {"refinement_steps", ldlt.refinement_steps},
                         {"growth_limit", ldlt.growth_limit},
                         {"certificate_iterations", ldlt.certificate_iterations},
                         {"certificate_margin", ldlt.certificate_margin}}}};
    std::printf("%s\n", head.dump().c_str());
    for (const auto& path : files) {
      const KktFile k = read_kkt(path);
      const Symmetric a = merged(k);
      const json row = {{"file", path},
                        {"n", k.n},
                        {"nnz", k.nnz},
                        {"dual_from", k.dual_from},
                        {"check_inertia", k.check_inertia},
                        {"expected_negative", k.expected_negative},
                        {"mumps", run_mumps(k, a, mumps, repeat)},
                        {"mumps_check", run_mumps(k, a, check, 1)},
                        {"ldlt", run_ldlt(k, a, ldlt, repeat)},
                        {"pivoted", run_pivoted(k, a, ldlt, repeat)}};
      std::printf("%s\n", row.dump().c_str());
      std::fflush(stdout);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_kkt: %s\n", e.what());
    return 2;
  }
  return 0;
}
