// disco — the command-line tool.
//
//   disco solve SCENE.yaml [--out DIR] [--start N [--seed S]] [--guess FILE] [--threads N]
//               [--settings FILE] [--set KEY=VALUE ...] [--model-only] [--quiet | --verbose]
//   disco search CONFIG... [--starts N] [--seed S] [--time-limit SEC] [--out DIR]
//                [--resume | --force] [--deterministic] [--guess FILE ...] [--threads N]
//                [--settings FILE]
//                [--set KEY=VALUE ...] [--quiet | --verbose]            (search/run_search.h)
//   disco --version
//
// Options and the file arguments may come in any order; each --set takes one KEY=VALUE
// (repeat it for more).
//
// Logs go to stderr and results to files; nothing is written to stdout except
// --help. On a terminal, `search` keeps a live status line below its log
// (mpi/live_line.h). --quiet keeps warnings and errors only; --verbose adds every Ipopt
// solve inside an elastic-mode solve and, under search, every start's solve log.
//
// Finds a feasible point at a large fixed T_f, then runs the paper's inexact
// objective reduction from it (search/objective_reduction.h), logging one line
// per elastic-mode solve to stderr, and writes DIR/solution.json (schema:
// core/model/solution.h and core/README.md). The file is written whatever the
// outcome, with the status telling what happened.
//
// Exit status (also in --help, kExitCodes): 0 a certified solution was written (search:
// for every scene); 3 the run ended without one (status infeasible, failed or
// elastic_not_tight, still written); 2 bad input or usage (the message names the file,
// line and key), a scene whose model would exceed model.memory_limit included
// (core/model/model_size.h); 1 an internal error, or out of memory all the same (the
// message says so, with the model's estimate); 130 / 143 interrupted by SIGINT / SIGTERM
// (what finished is written; see search/run_search.h). A second signal ends disco at once.
#include <mpi.h>
#include <omp.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/model_size.h"
#include "core/model/objective.h"
#include "core/model/scene_yaml.h"
#include "core/util/clock.h"
#include "core/util/deterministic_heap.h"
#include "core/util/errors.h"
#include "core/util/interrupt.h"
#include "core/util/provenance.h"
#include "core/util/suggest.h"
#include "core/ipopt/ipopt_solver.h"
#include "mpi/live_line.h"
#include "mpi/mpi_transport.h"
#include "search/reduction_phases.h"
#include "search/run_search.h"
#include "search/solve_scene.h"
#include "search/start.h"
#include "search/trajectory.h"

namespace {

using namespace disco;
using json = nlohmann::json;

constexpr const char* kExitCodes =
    "Exit status: 0 certified solution(s) written (search: for every scene); 3 finished "
    "without a certified solution (for some scene); 2 bad input or usage (a model above "
    "model.memory_limit too); 1 internal error or out of memory; "
    "130 / 143 interrupted by SIGINT / SIGTERM (finished work kept; search: continue with "
    "--resume).";

// SIGINT and SIGTERM request a clean stop (core/util/interrupt.h); SA_RESETHAND makes a
// second signal end the process at once.
void on_signal(int signal) { request_interrupt(signal); }
void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}
int interrupted_exit_code() { return 128 + (interrupt_signal() > 0 ? interrupt_signal() : SIGINT); }

// The first word must be a command: name an unknown one, with the closest command.
// Returns the usage error to print, or "" when the command line starts well.
std::string unknown_command(int argc, char** argv, const CLI::App& app) {
  if (argc < 2 || argv[1][0] == '-') return "";
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return "";
  return "unknown command '" + printable(word, kEchoLimit) + "'" + did_you_mean(word, names) +
         "; the commands are solve and search (disco --help)";
}

// One thread unless asked: evaluation is a small share of a solve, and
// parallelism across starts comes from MPI ranks (ranks x threads <= cores).
void set_threads(int threads) {
  if (threads > 0) {
    omp_set_num_threads(threads);
  } else if (std::getenv("OMP_NUM_THREADS") == nullptr) {
    omp_set_num_threads(1);
  }
}

struct Verbosity {
  bool quiet = false;
  bool verbose = false;
  // The log level of a process; under search only rank 0 reports progress.
  spdlog::level::level_enum level(bool reporting) const {
    if (quiet) return spdlog::level::warn;
    if (verbose) return spdlog::level::debug;
    return reporting ? spdlog::level::info : spdlog::level::warn;
  }
  void add_flags(CLI::App* cmd) {
    auto* q = cmd->add_flag("-q,--quiet", quiet, "Log warnings and errors only");
    cmd->add_flag("-v,--verbose", verbose,
                  "Log every Ipopt solve too (and, under search, every start's solve log)")
        ->excludes(q);
  }
};

// `disco search`: MPI is initialised here and only here.
int run_search_command(SearchOptions o, int threads, const Verbosity& verbosity,
                       const std::shared_ptr<LiveLineSink>& sink, int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  MpiTransport transport;
  const int rank = transport.rank(), size = transport.size();
  int code = 0;
  if (size > 1 && provided < MPI_THREAD_SERIALIZED) {
    if (rank == 0) spdlog::error("error: the MPI library does not provide MPI_THREAD_SERIALIZED");
    code = 1;
  } else {
    spdlog::set_level(verbosity.level(rank == 0));
    // Every rank logs under --verbose: say which.
    if (verbosity.verbose && size > 1) spdlog::set_pattern(fmt::format("%^[rank {}] %v%$", rank));
    // The live status line: rank 0, on a terminal, unless --quiet.
    if (rank == 0 && !verbosity.quiet && is_terminal(stderr))
      o.on_status = [sink](const std::string& text) { sink->set_status(text); };
    set_threads(threads);
    install_signal_handlers();
    try {
      code = run_search(o, transport);
    } catch (const InputError& e) {
      if (rank == 0) spdlog::error("error: {}", e.what());
      code = 2;
    } catch (const std::bad_alloc&) {  // a start's own runs out in run_start (status error)
      spdlog::error("error: out of memory on rank {}", rank);
      code = 1;
    } catch (const std::exception& e) {
      spdlog::error("internal error on rank {}: {}", rank, e.what());
      code = 1;
    }
    // An error on one rank must not leave the others waiting for messages
    // (e.g. rank 0 cannot write --out while the workers wait for tasks).
    const bool interrupted = code == interrupted_exit_code() && interrupt_requested();
    if (code != 0 && code != 3 && !interrupted && size > 1) MPI_Abort(MPI_COMM_WORLD, code);
  }
  MPI_Finalize();
  return code;
}

struct SolveOptions {
  std::string scene;
  std::string out;
  std::string settings = default_settings_path();
  int threads = 0;
  int start = 0;
  std::uint64_t seed = 1;
  std::vector<std::string> sets;
  std::string guess;  // --guess FILE
  bool model_only = false;
};

// "T_f = 2.332261 s", or "energy = 3.51234 N^2 s (T_f = 4.000000 s)".
std::string value_text(const SceneSolve& run) {
  const ObjectiveKind kind = run.problem->objective_kind();
  if (kind == ObjectiveKind::kTime) return fmt::format("T_f = {:.6f} s", run.T_f());
  return fmt::format("{} = {:.6g} {} (T_f = {:.6f} s)", to_string(kind), run.value(),
                     objective_unit(kind), run.T_f());
}

// disco solve, once the scene passed the size check.
int solve_checked(const SolveOptions& o, const Settings& settings, const Scene& scene,
                  const std::vector<std::string>& scene_sets, const std::string& out_dir,
                  const ModelSizeEstimate& estimate, const Trajectory& guess) {
  {
    RobotProblem preview(scene, model_options(settings));
    const double T_max = preview.horizon_reach(feasibility_horizon(preview, reduction_settings(settings)));
    preview.set_horizon_max(T_max);
    const auto size = preview.size();
    const auto objects = std::count_if(scene.robots.begin(), scene.robots.end(),
                                       [](const Robot& r) { return r.object; });
    spdlog::info("scene {} ({}): {} robots{}{}, {} pairs, N_t = {}", scene.name, scene.source,
                 scene.robots.size() - objects, objects ? fmt::format(", {} objects", objects) : "",
                 scene.obstacles.empty() ? "" : fmt::format(", {} obstacles", scene.obstacles.size()),
                 scene.pairs.size() + scene.obstacle_pairs.size(), scene.steps);
    const Objective& obj = scene.objective;
    spdlog::info("model{}: {} variables, {} constraints, {} complementarity pairs "
                 "({}); {} threads",
                 preview.options().adaptive ? " (adaptive)" : "", size.variables, size.constraints,
                 size.complementarity_pairs,
                 preview.horizon_is_fixed() ? fmt::format("T_f = {:.4g} s", T_max)
                                            : fmt::format("T_f <= {:.4g} s", T_max),
                 omp_get_max_threads());
    if (obj.kind != ObjectiveKind::kTime)
      spdlog::info("objective: {} ({})", to_string(obj.kind),
                   obj.kind == ObjectiveKind::kEnergy
                       ? fmt::format("sum of h |F|^2 over robots and steps, N^2 s, at T_f = {:.6g} s",
                                     obj.horizon)
                       : fmt::format("T_f + {:.6g} * sum of h |F|^2, s", obj.energy_weight));
    const ModelPlan& plan = preview.plan();
    spdlog::info("  pairs within reach at {} of {} pair-states; {} of {} disks turn",
                 plan.pair_states(),
                 static_cast<int>(scene.pairs.size() + scene.obstacle_pairs.size()) * scene.steps,
                 plan.turning_robots(), static_cast<int>(scene.robots.size()));
    spdlog::info("  memory of a solve: {}; {} = {}", estimate.describe(), kMemoryLimitKey,
                 memory_text(memory_limit(settings).bytes));
    if (const auto lb = preview.lower_bound(); lb && std::isfinite(*lb)) {
      spdlog::info("lower bound (robots without contact partners, each alone): {:.6f} s", *lb);
    } else {
      spdlog::info("lower bound: none (every robot can be pushed, or has no closed form)");
    }
  }
  // Every option is checked before anything runs, --model-only too.
  elastic_settings(settings);
  IpoptSolver check(ipopt_settings(settings));
  if (o.model_only) return 0;
  std::filesystem::create_directories(out_dir);
  StartSpec start =
      make_start(scene, o.seed, o.start, reduction_settings(settings), elastic_settings(settings));
  if (!guess.empty()) {
    start = with_guess(start, guess);
    spdlog::info("guess: {} (T_f {:.6f} s), resampled to N_t = {}; first horizon {:.6f} s",
                 o.guess, start.given.seconds, scene.steps,
                 (1.0 + start.schedule.guess_slack) * start.given.seconds);
  }
  if (o.start != 0) {
    spdlog::info("seed {}, {}", o.seed, start.describe());
  } else {
    spdlog::debug("{}", start.describe());
  }
  const ObjectiveKind kind = scene.objective.kind;
  spdlog::info("{}", solve_log_header(kind));
  int count = 0;
  auto on_solve = [&](const SolveRecord& r) { spdlog::info("{}", solve_log_line(++count, r, kind)); };

  install_signal_handlers();
  const SceneSolve run = solve_scene(scene, settings, start, 0.0, on_solve);
  spdlog::info("  {}", stop_line(run.result.stop, start.schedule));
  const std::string path = out_dir + "/solution.json";
  json doc = solution_json(*run.problem, run.z, run.info);
  doc["provenance"] =
      provenance_json({"solve", o.scene, scene_sets, o.sets, o.seed, o.start, o.guess}, settings);
  write_json_file(path, doc);
  if (interrupt_requested()) {
    spdlog::warn("interrupted: the solve stopped early; {} holds its best point so far{}", path,
                 run.solved() ? fmt::format(" ({}, certified)", value_text(run))
                              : " (none: status " + to_string(run.info.status) + ")");
    return interrupted_exit_code();
  }
  // The model holds at the states: say so where a disk passed through an obstacle between them.
  for (const auto& p : doc["obstacle_pairs"]) {
    if (!p["swept_gap"].is_array()) continue;
    const auto& g = p["swept_gap"];
    const auto worst = std::min_element(g.begin(), g.end());
    const double R = run.problem->scene().robots[p["i"].get<int>()].radius;
    if (worst == g.end() || *worst >= -1e-6 * R) continue;
    const auto k = std::distance(g.begin(), worst);
    spdlog::warn("{} '{}' passes through obstacle '{}' between states {} and {} (overlap {:.3g} m): "
                 "the model holds at the N_t states only; raise steps",
                 run.problem->scene().robots[p["i"].get<int>()].object ? "object" : "robot",
                 p["robot_i"].get<std::string>(), p["obstacle"].get<std::string>(), k, k + 1, -worst->get<double>());
  }
  const auto lb = run.problem->lower_bound();
  if (run.solved()) {
    // The lower bound is on T_f: its gap is a measure for objective time only.
    spdlog::info("solved: {}{}; certificate: violation {:.1e}, complementarity {:.1e}",
                 value_text(run),
                 kind == ObjectiveKind::kTime && lb && *lb > 0 && std::isfinite(*lb)
                     ? fmt::format(" ({:+.3f} % from the lower bound)", 100.0 * (run.T_f() - *lb) / *lb)
                     : std::string(),
                 run.info.certificate.max_violation, run.info.certificate.max_complementarity);
  } else {
    const std::string where = violations_text(run.info.violations);
    spdlog::warn("no certified solution: status {}{}", to_string(run.info.status), where.empty() ? "" : "; " + where);
  }
  spdlog::info("KKT: {} factorisations, {} of them by MUMPS for disco's LDLᵀ, {} by its pivoting "
               "LDLᵀ for the other, {} pivot threshold raises (kkt.solver); {} analyses ordered "
               "by nested dissection (kkt.ldlt.ordering); {} polish solves started again by "
               "kkt.polish_rescue",
               run.info.kkt_factorisations, run.info.kkt_fallbacks, run.info.kkt_to_pivoted,
               run.info.kkt_threshold_raises, run.info.kkt_nested_dissection,
               run.info.kkt_polish_rescues);
  spdlog::info("{} NLP solves, {} iterations, {:.3f} s; wrote {}", run.info.nlp_solves,
               run.info.iterations, run.info.wall_s, path);
  return run.solved() ? 0 : 3;
}

int run_solve(const SolveOptions& o) {
  std::vector<std::string> scene_sets, settings_sets;
  split_overrides(o.sets, scene_sets, settings_sets);
  Settings settings = Settings::load(o.settings);
  for (const auto& s : settings_sets) settings.apply_override(s);
  const Scene scene = load_scene(o.scene, scene_sets);
  // The solve's time (reduction.time_limit, the seconds it reports) is read on this clock.
  const std::unique_ptr<TimeSource> time_source = make_time_source(clock_settings(settings));
  const ScopedTimeSource clock(*time_source);
  const Trajectory guess = o.guess.empty() ? Trajectory{} : read_guess_file(o.guess, scene);
  set_threads(o.threads);
  const std::string out_dir = o.out.empty() ? "out/" + scene.name : o.out;
  // Refuse a model too big for model.memory_limit before building any (--model-only too).
  const bool adaptive = model_options(settings).adaptive;
  const ModelSizeEstimate estimate = check_model_size(scene, adaptive, memory_limit(settings));
  try {
    return solve_checked(o, settings, scene, scene_sets, out_dir, estimate, guess);
  } catch (const std::bad_alloc&) {
    spdlog::error("error: {}", out_of_memory_message("solving " + o.scene, scene, adaptive));
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Before anything allocates: Ipopt 3.11.9 can read a never-set value from fresh heap memory
  // (core/util/deterministic_heap.h); this makes that value the same in every process.
  disco::make_heap_deterministic();
  auto sink = std::make_shared<LiveLineSink>(
      std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("disco", sink));
  spdlog::set_pattern("%^%v%$");

  CLI::App app{"disco: minimum-time control of disk robots with friction (elastic-mode MPCC)"};
  app.require_subcommand(1);
  app.footer(kExitCodes);
  app.set_version_flag("--version", disco_version(), "Print disco's version and git commit, and exit");
  SolveOptions solve;
  Verbosity solve_verbosity, search_verbosity;
  auto* cmd = app.add_subcommand("solve", "Solve one scene from one start (objective reduction)");
  cmd->add_option("scene", solve.scene, "Scene file (YAML)")->required();
  cmd->add_option("--out", solve.out, "Output directory")->default_str("out/SCENARIO");
  cmd->add_option("--start", solve.start,
                  "Run this start of a search (search/start.h) instead of start 0, e.g. to see the "
                  "log of the start that gave a search's best")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--seed", solve.seed, "Seed of the start generator (with --start; as for search)");
  cmd->add_option("--guess", solve.guess,
                  "Start from this trajectory: a solution.json or best/SCENE.json of the same "
                  "robots (any N_t; resampled to the scene's, first solved at "
                  "(1 + feasibility.guess_slack) times its T_f)");
  cmd->add_flag("--model-only", solve.model_only,
                "Print the model's size (at start 0's feasibility horizon) and exit without solving");
  cmd->add_option("--threads", solve.threads, "OpenMP threads (default: OMP_NUM_THREADS, else 1)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--settings", solve.settings, "Solver settings file")
      ->capture_default_str();
  cmd->add_option("--set", solve.sets,
                  "Override KEY=VALUE: a settings key (elastic.zeta_max=1e8, ipopt.tol=1e-10) "
                  "or a scene key prefixed with 'scene.' (scene.steps=50); repeat for more")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  solve_verbosity.add_flags(cmd);
  SearchOptions search;
  search.settings = default_settings_path();
  int search_threads = 0;
  auto* scmd = app.add_subcommand(
      "search", "Multi-start search over MPI ranks (run under mpirun, or as one process)");
  scmd->add_option("configs", search.configs, "Scene or benchmark files (YAML)")->required();
  scmd->add_option("--starts", search.starts, "Starts per scene (replaces the files' counts)")
      ->check(CLI::PositiveNumber)
      ->default_str("the benchmark file's, 1 for a scene file");
  scmd->add_option("--seed", search.seed, "Seed of the start generator")->capture_default_str();
  scmd->add_option("--time-limit", search.time_limit, "Seconds for the whole search (0: none)")
      ->check(CLI::NonNegativeNumber);
  scmd->add_option("--out", search.out, "Output directory")->capture_default_str();
  auto* resume = scmd->add_flag(
      "--resume", search.resume,
      "Continue the run in OUT: skip the starts OUT/runs.jsonl holds, run again those cut short "
      "(refused if OUT/manifest.json differs from this command)");
  scmd->add_flag("--force", search.force,
                 "Replace the run OUT holds (without --resume, a non-empty OUT is refused)")
      ->excludes(resume);
  scmd->add_flag("--deterministic", search.deterministic,
                 "Each start runs alone (search.share_incumbent=false): the same runs and best "
                 "for any number of ranks, and on --resume");
  scmd->add_option("--guess", search.guesses,
                   "A solution file (solution.json, best/SCENE.json) for start 0 of the scene it "
                   "names (of the only scene, whatever its name); repeat for more scenes")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  scmd->add_option("--threads", search_threads, "OpenMP threads per rank (default 1)")
      ->check(CLI::PositiveNumber);
  scmd->add_option("--settings", search.settings, "Solver settings file")->capture_default_str();
  scmd->add_option("--set", search.sets, "Override KEY=VALUE (as for solve); repeat for more")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  search_verbosity.add_flags(scmd);
  if (const std::string error = unknown_command(argc, argv, app); !error.empty()) {
    spdlog::error("error: {}", error);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (scmd->parsed())
    return run_search_command(search, search_threads, search_verbosity, sink, argc, argv);
  spdlog::set_level(solve_verbosity.level(true));
  try {
    if (cmd->parsed()) return run_solve(solve);
  } catch (const InputError& e) {
    spdlog::error("error: {}", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    spdlog::error("error: out of memory");
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("internal error: {}", e.what());
    return 1;
  }
  return 0;
}
