// libFuzzer target for the scene parser (core/model/scene_yaml.h); run by scripts/fuzz_scene.
//
// Input: the scene text, optionally followed by a line "#--set" and override lines:
//
//   scenario: a              <- scene text (everything before the marker line)
//   ...
//   #--set                   <- marker (a YAML comment, so a plain scene stays a scene)
//   robots.0.mass=2          <- one "KEY=VALUE" override per line, at most kMaxOverrides;
//   steps=[1, 2              <-   later lines are ignored
//
// The bytes go to parse_scene(text, "fuzz.yaml", overrides). Findings (abort(), so libFuzzer
// saves the input): a crash or sanitizer report, an exception other than InputError, an
// unclear InputError message, or a parsed Scene that breaks an invariant of core/model/scene.h.
//
// A message is clear when:
//   * it starts with "fuzz.yaml: ", "fuzz.yaml:LINE: " with 1 <= LINE <= the text's line
//     count + 1, or "--set: " (core/util/errors.h, located_message);
//   * it is one line of printable text: no byte below 0x20 and no 0x7f (echoed input must
//     be escaped; bytes >= 0x80, e.g. UTF-8, may pass through);
//   * it is at most kMaxMessage bytes long, whatever the input (long echoes are cut).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <set>
#include <string>
#include <vector>

#include "core/model/scene_yaml.h"
#include "core/util/errors.h"

namespace {

constexpr const char* kSource = "fuzz.yaml";
constexpr const char* kMarker = "\n#--set\n";
constexpr std::size_t kMaxOverrides = 4;
constexpr std::size_t kMaxMessage = 1000;

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "scene_fuzz: %s: %s\n", what, detail.c_str());
  std::abort();
}

void require(bool ok, const char* what, const std::string& detail = "") {
  if (!ok) finding(what, detail);
}

// 1-based line count of `text` (a last line without '\n' counts).
std::size_t line_count(const std::string& text) {
  std::size_t lines = 1;
  for (char c : text) lines += c == '\n';
  return lines;
}

void check_message(const std::string& msg, const std::string& text) {
  require(!msg.empty(), "empty message");
  require(msg.size() <= kMaxMessage, "message too long",
          std::to_string(msg.size()) + " bytes: " + msg);
  for (unsigned char c : msg) {
    require(c >= 0x20 && c != 0x7f, "control byte in message", msg);
  }
  const std::string set = "--set: ";
  if (msg.compare(0, set.size(), set) == 0) return;
  const std::string src = std::string(kSource) + ":";
  require(msg.compare(0, src.size(), src) == 0, "message does not start with the source", msg);
  std::size_t at = src.size();
  if (msg[at] == ' ') return;  // no line
  std::size_t line = 0;
  while (at < msg.size() && msg[at] >= '0' && msg[at] <= '9' && line < 1000000000) {
    line = line * 10 + static_cast<std::size_t>(msg[at++] - '0');
  }
  require(msg.compare(at, 2, ": ") == 0, "malformed location", msg);
  require(line >= 1 && line <= line_count(text) + 1, "line out of range", msg);
}

bool finite(double v) { return std::isfinite(v); }

// The invariants written beside the fields of core/model/scene.h.
void check_scene(const disco::Scene& s) {
  using disco::kStateSize;
  require(s.source == kSource, "Scene::source", s.source);
  require(!s.name.empty(), "empty scenario name");
  require(s.steps >= 1, "steps < 1");
  require(finite(s.gravity) && s.gravity > 0, "gravity");
  require(!s.robots.empty(), "no robots");
  std::set<std::string> names;
  for (const disco::Robot& r : s.robots) {
    require(names.insert(r.name).second, "duplicate robot name", r.name);
    require(finite(r.radius) && r.radius > 0, "radius", r.name);
    require(finite(r.mass) && r.mass > 0, "mass", r.name);
    require(finite(r.inertia) && r.inertia > 0, "inertia", r.name);
    require(finite(r.mu) && r.mu >= 0, "mu", r.name);
    require(finite(r.damping) && r.damping >= 0, "damping", r.name);
    require(finite(r.force_max) && r.force_max > r.mu * r.mass * s.gravity, "force_max", r.name);
    require(r.force_dims == 1 || r.force_dims == 2, "force_dims", r.name);
    const double norm = std::hypot(r.force_axis[0], r.force_axis[1]);
    require(std::fabs(norm - 1) < 1e-12, "force_axis not a unit vector", r.name);
    require(r.friction_edges >= 3, "K < 3", r.name);
    for (int c = 0; c < kStateSize; ++c) {
      require(finite(r.start[c]), "start not finite", r.name);
      const double lo = r.target.lower[c], hi = r.target.upper[c];
      require(lo <= hi && lo < disco::kInf && hi > -disco::kInf, "target box", r.name);
    }
  }
  const std::size_t n = s.robots.size();
  require(s.pairs.size() == n * (n - 1) / 2, "pair count");
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j, ++k) {
      const disco::Pair& p = s.pairs[k];
      require(p.i == static_cast<int>(i) && p.j == static_cast<int>(j), "pair order");
      require(p.mode == disco::PairMode::kAvoid || p.mode == disco::PairMode::kContact, "mode");
      require(finite(p.safe_distance) && p.safe_distance >= 0, "safe_distance");
      require(finite(p.mu) && p.mu >= 0, "pair mu");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::string text = input;
  std::vector<std::string> overrides;
  if (const std::size_t marker = input.find(kMarker); marker != std::string::npos) {
    text = input.substr(0, marker + 1);
    std::size_t begin = marker + std::string(kMarker).size();
    while (begin <= input.size() && overrides.size() < kMaxOverrides) {
      const std::size_t end = input.find('\n', begin);
      overrides.push_back(input.substr(begin, end == std::string::npos ? end : end - begin));
      if (end == std::string::npos) break;
      begin = end + 1;
    }
  }
  try {
    check_scene(disco::parse_scene(text, kSource, overrides));
  } catch (const disco::InputError& e) {
    check_message(e.what(), text);
  } catch (const std::exception& e) {
    finding("exception other than InputError", e.what());
  }
  return 0;
}
