// disco — the multi-start search over MPI ranks (`disco search`).
//
// Tasks are (scene, start) pairs, larger scenes first. Rank 0 owns the task
// list and the output directory; tasks are handed out dynamically (starts
// differ in cost by 10x and more):
//   * one rank: the process runs every task itself;
//   * P ranks: a coordinator thread on rank 0 answers the workers (ranks
//     1..P-1) and rank 0's main thread works too, so P ranks use P cores.
//     Workers call MPI only between solves (MUMPS's fake MPI; see
//     mpi/CMakeLists.txt), and only rank 0's coordinator thread calls MPI
//     while rank 0 works (MPI_THREAD_SERIALIZED).
//
// Output (DIR = --out):
//   DIR/manifest.json     what the run is (search/run_manifest.h): version, scene files and
//                         their SHA-256, overrides, seed, settings; written first. Without
//                         --resume a non-empty DIR is refused unless --force;
//   DIR/runs.jsonl        one line per start that ended, written and flushed as
//                         it arrives (search/run_start.h, StartOutcome): also a
//                         start cut short by a time limit (status time_limit) or
//                         an interrupt (interrupted), with its best point so far;
//   DIR/best.json         per scene: best certified T_f, its start, starts run
//                         and solved, time to first feasible and to best (from
//                         the hand-out of the scene's first start);
//                         whether the time limit cut the search short;
//   DIR/best/SCENE.json   the full solution of the best start (core/model/solution.h).
// --resume refuses a DIR whose manifest does not match the command (naming each
// difference), reads runs.jsonl, skips the starts it holds a final outcome for,
// runs again the starts cut short (unless their own start_time_limit cut them and
// is unchanged), and rebuilds the best from the latest line of every start (a best
// start's solution file is kept from the earlier run). Deterministic starts
// (search/start.h) make a resumed search end with the runs and best of one run
// without interruption.
//
// SIGINT or SIGTERM (mpirun turns Ctrl-C into SIGTERM for every rank): no start is
// handed out any more, every solve in flight stops at its next Ipopt iteration and
// its start is recorded as interrupted, with its best so far; rank 0 writes
// best.json, logs "interrupted (SIGINT): K of N starts kept in DIR/runs.jsonl, L
// lost (...); continue with --resume" and the search returns 128 + the signal
// (130 for SIGINT, 143 for SIGTERM), as a shell reports a process a signal ended.
// A second signal ends the process at once (the default action). Open MPI's mpirun
// kills the ranks 1 s after its SIGTERM (odls_base_sigkill_timeout): what finished
// is on disk before then (every line is fsync'ed as it is written).
// The best of a scene is the smallest certified T_f, ties to the lower start
// index, so the outcome does not depend on which rank ran what.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace disco {

struct SearchOptions {
  std::vector<std::string> configs;
  std::string settings;            // settings file
  std::vector<std::string> sets;   // --set KEY=VALUE (scene.* or settings)
  int starts = 0;                  // > 0 replaces every scene's starts
  std::uint64_t seed = 1;
  double time_limit = 0.0;         // s for the whole search; 0 = none
  std::string out = "runs/search";
  bool resume = false;
  bool force = false;  // replace what DIR holds (search/run_manifest.h)
  // Rank 0: called about once a second with the live status line (starts done,
  // elapsed, ETA, best T_f, starts running) and with "" at the end. Unset: none.
  std::function<void(const std::string&)> on_status;
};

// Runs the search; call between MPI_Init_thread and MPI_Finalize on every
// rank. Returns the process exit status (0: every scene has a certified
// solution; 3: some scene has none; 2: bad input, reported on rank 0;
// 130 / 143: interrupted by SIGINT / SIGTERM, what finished is kept).
int run_search(const SearchOptions& options);

}  // namespace disco
