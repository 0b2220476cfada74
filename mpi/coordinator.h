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
//   DIR/runs.jsonl        one line per finished start, written and flushed as
//                         it arrives (search/run_start.h, StartOutcome);
//   DIR/best.json         per scene: best certified T_f, its start, starts run
//                         and solved, time to first feasible and to best (from
//                         the hand-out of the scene's first start);
//                         whether the time limit cut the search short;
//   DIR/best/SCENE.json   the full solution of the best start (core/model/solution.h).
// --resume reads runs.jsonl, skips the starts it holds and rebuilds the best
// from them (a best start's solution file is kept from the earlier run).
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
  // Rank 0: called about once a second with the live status line (starts done,
  // elapsed, ETA, best T_f, starts running) and with "" at the end. Unset: none.
  std::function<void(const std::string&)> on_status;
};

// Runs the search; call between MPI_Init_thread and MPI_Finalize on every
// rank. Returns the process exit status (0: every scene has a certified
// solution; 3: some scene has none; 2: bad input, reported on rank 0).
int run_search(const SearchOptions& options);

}  // namespace disco
