// disco — the multi-start search (`disco search`): every rank's part of it.
//
// Rank 0 prepares the output directory (search/run_manifest.h: the manifest, --resume,
// --force), owns the Coordinator (search/coordinator.h: the task queue, the record,
// best.json, progress) and works too: with P ranks a coordinator thread on rank 0 answers
// the workers (ranks 1..P-1) over the Transport (search/transport.h) while rank 0's main
// thread runs tasks, so P ranks use P cores. Each task is one start (search/run_start.h)
// of one scene; its solution file gets the search's provenance.
//
// SIGINT or SIGTERM (mpirun turns Ctrl-C into SIGTERM for every rank): no start is
// handed out any more, every solve in flight stops at its next Ipopt iteration and its
// start is recorded as interrupted, with its best so far; rank 0 writes best.json, logs
// "interrupted (SIGINT): K of N starts kept in DIR/runs.jsonl, L lost (...); continue with
// --resume" and the search returns 128 + the signal (130 for SIGINT, 143 for SIGTERM), as
// a shell reports a process a signal ended. A second signal ends the process at once (the
// default action). Open MPI's mpirun sends SIGCONT, then SIGTERM and SIGKILL 1 s apart
// (odls_base_sigkill_timeout, search/README.md): what finished is on disk before then (every
// line is fsync'ed as it is written).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "search/transport.h"

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
  // --deterministic: search.share_incumbent = false (each start runs alone: the same runs and
  // best for any number of ranks, and on --resume).
  bool deterministic = false;
  // --guess FILE (repeatable): solution files; start 0 of each one's scene starts from it
  // (attach_guesses, search/search_plan.h).
  std::vector<std::string> guesses;
  // Rank 0: called about once a second with the live status line (starts done,
  // elapsed, ETA, best T_f, starts running) and with "" at the end. Unset: none.
  std::function<void(const std::string&)> on_status;
};

class Coordinator;  // search/coordinator.h

// Rank 0's side of the transport (run by run_search on a second thread of rank 0): answers
// every worker (ranks 1..size-1) until each has been told to stop, passes on the running
// starts' progress and sends the coordinator's incumbent messages as they arise. It polls
// (a blocking probe would spin a core in Open MPI, the core of rank 0's own worker).
void serve_workers(Coordinator& coordinator, Transport& transport);

// Runs the search on every rank of `transport`. Returns the process exit status (0: every
// scene has a certified solution; 3: some scene has none; 2: bad input, reported on rank
// 0; 130 / 143: interrupted by SIGINT / SIGTERM, what finished is kept).
int run_search(const SearchOptions& options, Transport& transport);

}  // namespace disco
