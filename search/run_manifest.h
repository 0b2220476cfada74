// disco — the manifest of a search's output directory (DIR/manifest.json), and the rules
// for writing into a directory that already holds a run.
//
// The manifest says what the run is: disco's version, the CONFIG files (path, SHA-256),
// every scene (name, file, SHA-256 of the file's bytes, the scene overrides applied, its
// --guess file and SHA-256 or null), the
// --set list, the seed, --starts, --time-limit, the settings (file, SHA-256 of
// Settings::canonical_text(), and every value). `invocations` lists each command that wrote
// into the directory (version, UTC time, resumed or not, starts, time limit).
//
//   {"format": "disco-search-manifest", "format_version": 1, "mode": "search",
//    "version": "0.1.0 (git …)", "configs": [{"file", "sha256"}],
//    "scenes": [{"name", "file", "sha256", "overrides": [...], "starts", "guess"}],
//    "overrides": [...], "seed": 7, "starts": 0, "time_limit": 0,
//    "settings": {"file", "sha256", "values": {"elastic.zeta": "10", ...}},
//    "invocations": [{"version", "utc", "resume", "starts", "time_limit"}]}
//
// What must match to resume (manifest_differences): the scenes (names, file contents,
// overrides, --guess file contents), the seed and every settings value. The starts per
// scene and the time limits may change: start k is the same start whatever the count
// (search/start.h), so a resume may add starts or run without the limit that cut the earlier run short. A different
// disco version is allowed with a warning (the manifest keeps both).
//
// Output directory rules (prepare_out_dir):
//   fresh (no --resume): DIR must be missing or empty, else an InputError that lists what
//       it holds and says to use --resume, --force or another --out;
//   --force: disco's own files in DIR (manifest.json, runs.jsonl, best.json, best/, report/)
//       are removed first; nothing else is touched;
//   --resume: DIR's manifest must match (else an InputError listing every difference); a
//       missing or empty DIR starts afresh; a DIR with runs but no manifest (an older disco)
//       is refused.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "search/search_plan.h"

namespace disco {

struct ManifestInputs {
  std::vector<std::string> configs;    // the CONFIG files as given
  std::vector<std::string> overrides;  // --set, as given
  std::uint64_t seed = 1;
  int starts = 0;            // --starts (0: the files' counts)
  double time_limit = 0.0;   // --time-limit (0: none)
  bool resume = false;
};

nlohmann::json search_manifest(const SearchPlan& plan, const Settings& settings,
                               const ManifestInputs& inputs);

// Why `now` cannot resume `earlier`, one line per difference ("seed: 7 there, 8 here");
// empty when it can.
std::vector<std::string> manifest_differences(const nlohmann::json& earlier,
                                              const nlohmann::json& now);

enum class OutDirMode { kFresh, kResume, kForce };

// Applies the rules above and writes DIR/manifest.json (on resume: the earlier manifest
// with this invocation appended). Returns the number of invocations before this one that
// wrote into DIR (0: a fresh run). InputError naming DIR (and, on a mismatch, each
// difference) otherwise.
int prepare_out_dir(const std::string& dir, OutDirMode mode, const nlohmann::json& manifest);

}  // namespace disco
