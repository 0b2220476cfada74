// disco — scene file reader. The format and its rules are documented in scene_yaml.h.
#include "core/model/scene_yaml.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/config/yaml_nodes.h"
#include "core/model/gap.h"
#include "core/model/lower_bound.h"
#include "core/model/obstacles.h"
#include "core/model/reachability.h"
#include "core/util/suggest.h"
#include "core/util/errors.h"

namespace disco {
namespace {

using yaml::describe;
using yaml::is_index;
using yaml::kOverrideSource;
using yaml::override_fail;

const std::vector<std::string> kRootKeys = {"scenario", "description", "steps",  "gravity",
                                            "defaults", "robots",      "objects", "obstacles",
                                            "pairs",    "objective"};
// Robot keys that `defaults` may also give, in the order they are read.
const std::vector<std::string> kFieldKeys = {
    "radius", "mass", "inertia", "mu", "damping", "force_max", "force_dims", "force_axis", "K"};
const std::vector<std::string> kRobotKeys = {"name",       "radius",  "mass",      "inertia",
                                             "mu",         "damping", "force_max", "force_dims",
                                             "force_axis", "K",       "start",     "target"};
// What only a robot has: an object (a passive disk) has no force of its own.
const std::vector<std::string> kForceKeys = {"force_max", "force_dims", "force_axis"};
const std::vector<std::string> kStateKeys(kStateNames.begin(), kStateNames.end());
const std::vector<std::string> kPairsKeys = {"mode", "safe_distance", "mu", "overrides"};
const std::vector<std::string> kPairOverrideKeys = {"robots", "mode", "safe_distance", "mu"};
const std::vector<std::string> kObstacleKeys = {"name", "disk", "wall", "mode", "safe_distance", "mu"};
const std::vector<std::string> kDiskObstacleKeys = {"x", "y", "radius", "vx", "vy", "path"};
const std::vector<std::string> kWaypointKeys = {"t", "x", "y"};
const std::vector<std::string> kWallKeys = {"from", "to", "thickness"};
const std::vector<std::string> kObjectiveKeys = {"kind", "horizon", "energy_weight"};
const std::vector<std::string> kObjectiveKinds = {"time", "energy", "time + energy"};

constexpr double kTouchTolerance = 1e-12;  // relative, for the start-overlap checks

std::string show(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// A name from the input, quoted for a message (long ones are cut; see errors.h).
std::string quote(const std::string& name) { return "'" + printable(name, kEchoLimit) + "'"; }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string item(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

// "[0].x" -> ".0.x": an indexed key path written the way --set spells it.
std::string dotted(const std::string& indexed) {
  std::string out;
  for (char c : indexed) {
    if (c == '[')
      out += '.';
    else if (c != ']')
      out += c;
  }
  return out;
}

bool is_name(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

// A node (or a mapping key) that came from an override: its indexed path, its key as
// spelt on the command line, and the KEY of the override that set or created it. Everything
// at or below `path` is reported as "--set".
struct OverrideRecord {
  std::string path;
  std::string key;
  std::string from;
};

// Applies one "KEY=VALUE" override to `root` (a mapping) and records what it touched.
void apply_override(YAML::Node& root, const std::string& assignment,
                    std::vector<OverrideRecord>& records) {
  const yaml::Override o = yaml::parse_override(assignment, "robots.0.mass");
  const std::string& key = o.key;
  const std::vector<std::string>& parts = o.parts;
  const YAML::Node& value = o.value;

  YAML::Node cur = root;
  std::string path;    // indexed, e.g. robots[0].start
  std::string prefix;  // dotted, as on the command line
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string& part = parts[k];
    const bool last = k + 1 == parts.size();
    const std::string here = prefix.empty() ? part : prefix + "." + part;
    const YAML::Node& ccur = cur;
    if (cur.IsMap()) {
      path = child(path, part);
      if (last) {
        cur[part] = value;
        records.push_back({path, key, key});
        return;
      }
      const YAML::Node existing = ccur[part];
      if (!existing.IsDefined() || existing.IsNull()) {
        cur[part] = YAML::Node(YAML::NodeType::Map);
        records.push_back({path, here, key});
      }
      const YAML::Node next = cur[part];
      cur.reset(next);
    } else if (cur.IsSequence()) {
      if (!is_index(part)) {
        override_fail(key, quote(prefix) + " is a sequence: " + quote(part) +
                               " must be an index (0, 1, ...)");
      }
      const std::size_t index = std::stoul(part);
      const std::size_t size = cur.size();
      path = item(path, index);
      if (index > size || (index == size && !last)) {
        override_fail(key, "index " + part + " is out of range: " + quote(prefix) + " has " +
                               std::to_string(size) + " entries");
      }
      if (last) {
        if (index == size)
          cur.push_back(value);
        else
          cur[index] = value;
        records.push_back({path, key, key});
        return;
      }
      const YAML::Node existing = ccur[index];
      if (existing.IsNull()) {
        cur[index] = YAML::Node(YAML::NodeType::Map);
        records.push_back({path, here, key});
      }
      const YAML::Node next = cur[index];
      cur.reset(next);
    } else {
      override_fail(key, quote(prefix) + " is a single value; it has no entry " + quote(part));
    }
    prefix = here;
  }
}

// The document being validated: knows the source and the overrides, and builds messages.
class Doc {
 public:
  Doc(std::string source, std::vector<OverrideRecord> records)
      : source_(std::move(source)), records_(std::move(records)) {}

  // Throws the InputError for `what` at key `path`; `at` is the offending node (or, for a
  // missing key, its parent) and gives the line.
  [[noreturn]] void fail(const YAML::Node& at, const std::string& path,
                         const std::string& what) const {
    const KeyOrigin o = origin(at, path);
    if (o.source == kOverrideSource && o.line == 0)
      throw InputError(located_message(o.source, 0, o.key, what));
    // The overrides that set values below `path` (e.g. robots.1.start.x for a start
    // overlap reported at robots[1].start) are named too, each once.
    std::string below;
    std::vector<std::string> named;
    for (const OverrideRecord& r : records_) {
      if (r.path.size() > path.size() && r.path.compare(0, path.size(), path) == 0 &&
          (r.path[path.size()] == '.' || r.path[path.size()] == '[') &&
          std::find(named.begin(), named.end(), r.from) == named.end()) {
        named.push_back(r.from);
        below += (below.empty() ? "" : ", ") + printable(r.from, kEchoLimit);
      }
    }
    if (!below.empty()) below = " (with --set " + below + ")";
    throw InputError(located_message(source_, o.line, path, what + below));
  }

  // Where the value at key `path` (node `at`, as for fail) was given: the file and line,
  // or "--set" with the override's key when an override set it (or a mapping above it).
  KeyOrigin origin(const YAML::Node& at, const std::string& path) const {
    for (auto it = records_.rbegin(); it != records_.rend(); ++it) {
      const std::string& p = it->path;
      if (path.compare(0, p.size(), p) == 0 &&
          (path.size() == p.size() || path[p.size()] == '.' || path[p.size()] == '['))
        return {kOverrideSource, 0, it->key + dotted(path.substr(p.size()))};
    }
    int line = yaml::line_of(at);
    // An empty value ("mass:") is marked where the next token starts: use its key's line.
    if (const auto it = null_lines_.find(path);
        at.IsDefined() && at.IsNull() && it != null_lines_.end()) {
      line = it->second;
    }
    return {source_, line, path};
  }

  // The entries of mapping `node`, checked: plain unique keys, all in `allowed`. A null
  // node is an empty mapping when `null_ok`.
  std::map<std::string, YAML::Node> mapping(const YAML::Node& node, const std::string& path,
                                            const std::vector<std::string>& allowed,
                                            bool null_ok) const {
    std::map<std::string, YAML::Node> out;
    if (null_ok && node.IsNull()) return out;
    if (!node.IsMap()) fail(node, path, "must be a mapping (got " + describe(node) + ")");
    for (const auto& kv : node) {
      const YAML::Node& k = kv.first;
      if (!k.IsScalar())
        fail(k, path, "mapping keys must be plain names (got " + describe(k) + ")");
      const std::string name = k.Scalar();
      const std::string at = child(path, name);
      bool known = false;
      for (const std::string& a : allowed) known = known || a == name;
      if (!known) fail(k, at, "unknown key (allowed: " + join(allowed) + ")");
      if (out.count(name) != 0) fail(k, at, "duplicate key");
      out.emplace(name, kv.second);
      if (kv.second.IsNull()) null_lines_[at] = k.Mark().line + 1;
    }
    return out;
  }

  double number(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar() || n.Tag() == "!")
      fail(n, path, "must be a number (got " + describe(n) + ")");
    double v = 0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, path, "must be a number (got " + describe(n) + ")");
    }
    if (!std::isfinite(v)) fail(n, path, "must be a finite number (got " + describe(n) + ")");
    return v;
  }

  double positive(const YAML::Node& n, const std::string& path) const {
    const double v = number(n, path);
    if (!(v > 0)) fail(n, path, "must be > 0 (got " + show(v) + ")");
    return v;
  }

  double non_negative(const YAML::Node& n, const std::string& path) const {
    const double v = number(n, path);
    if (v < 0) fail(n, path, "must be >= 0 (got " + show(v) + ")");
    return v;
  }

  int integer(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar() || n.Tag() == "!") {
      fail(n, path, "must be an integer (got " + describe(n) + ")");
    }
    try {
      return n.as<int>();
    } catch (const YAML::Exception&) {
      fail(n, path, "must be an integer (got " + describe(n) + ")");
    }
  }

  std::string text(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) fail(n, path, "must be text (got " + describe(n) + ")");
    return n.Scalar();
  }

  std::string name(const YAML::Node& n, const std::string& path) const {
    const std::string s = text(n, path);
    if (!is_name(s)) {
      fail(n, path,
           "must be a name made of letters, digits, '_', '-' and '.' (got " + describe(n) + ")");
    }
    return s;
  }

  PairMode mode(const YAML::Node& n, const std::string& path) const {
    const std::string s = text(n, path);
    if (s == "avoid") return PairMode::kAvoid;
    if (s == "contact") return PairMode::kContact;
    fail(n, path, "must be 'avoid' or 'contact' (got " + describe(n) + ")");
  }

 private:
  std::string source_;
  std::vector<OverrideRecord> records_;
  mutable std::map<std::string, int> null_lines_;  // key path -> line of its key, for nulls
};

// Where a robot field's value was given: a node and its key path (in the robot itself or
// under `defaults`).
struct Origin {
  YAML::Node node;
  std::string path;
};

struct RobotDraft {
  Robot robot;
  std::map<std::string, Origin> origin;  // the fields given so far
};

bool is_force_key(const std::string& key) {
  return std::find(kForceKeys.begin(), kForceKeys.end(), key) != kForceKeys.end();
}

// The scene file's `robots` and `objects` sequences, indexed as Scene::robots (robots first).
struct DiskNodes {
  YAML::Node robots, objects;
  std::size_t robot_count = 0;
  YAML::Node at(std::size_t i) const { return i < robot_count ? robots[i] : objects[i - robot_count]; }
  std::string path(std::size_t i) const {
    return i < robot_count ? item("robots", i) : item("objects", i - robot_count);
  }
};


void set_field(const Doc& doc, const std::string& key, const YAML::Node& n, const std::string& path,
               RobotDraft& d) {
  Robot& r = d.robot;
  if (key == "radius") {
    r.radius = doc.positive(n, path);
  } else if (key == "mass") {
    r.mass = doc.positive(n, path);
  } else if (key == "inertia") {
    r.inertia = doc.positive(n, path);
  } else if (key == "mu") {
    r.mu = doc.non_negative(n, path);
  } else if (key == "damping") {
    r.damping = doc.non_negative(n, path);
  } else if (key == "force_max") {
    r.force_max = doc.positive(n, path);
  } else if (key == "force_dims") {
    const int dims = doc.integer(n, path);
    if (dims != 1 && dims != 2) {
      doc.fail(n, path, "must be 1 or 2 (got " + std::to_string(dims) + ")");
    }
    r.force_dims = dims;
  } else if (key == "force_axis") {
    if (!n.IsSequence() || n.size() != 2) {
      doc.fail(n, path, "must be a 2-vector [ax, ay] (got " + describe(n) + ")");
    }
    const double ax = doc.number(n[0], item(path, 0));
    const double ay = doc.number(n[1], item(path, 1));
    const double norm = std::hypot(ax, ay);
    if (!(norm > 0)) doc.fail(n, path, "must not be the zero vector");
    r.force_axis = {ax / norm, ay / norm};
  } else if (key == "K") {
    const int k = doc.integer(n, path);
    if (k < 3) doc.fail(n, path, "must be >= 3 (got " + std::to_string(k) + ")");
    r.friction_edges = k;
  }
  d.origin[key] = Origin{n, path};
}

State read_start(const Doc& doc, const YAML::Node& n, const std::string& path) {
  const auto fields = doc.mapping(n, path, kStateKeys, false);
  State s{};
  for (int c = 0; c < kStateSize; ++c) {
    const std::string& key = kStateKeys[c];
    const auto it = fields.find(key);
    if (it == fields.end()) {
      if (c == kX || c == kY) doc.fail(n, child(path, key), "is required but missing");
      continue;
    }
    s[c] = doc.number(it->second, child(path, key));
  }
  return s;
}

StateBox read_target(const Doc& doc, const YAML::Node& n, const std::string& path) {
  const auto fields = doc.mapping(n, path, kStateKeys, true);
  StateBox box;
  for (int c = 0; c < kStateSize; ++c) {
    const auto it = fields.find(kStateKeys[c]);
    if (it == fields.end()) continue;
    const YAML::Node& v = it->second;
    const std::string at = child(path, kStateKeys[c]);
    if (v.IsNull()) continue;
    if (v.IsSequence()) {
      if (v.size() != 2) {
        doc.fail(v, at, "a box must be [lo, hi] (got " + std::to_string(v.size()) + " elements)");
      }
      if (!v[0].IsNull()) box.lower[c] = doc.number(v[0], item(at, 0));
      if (!v[1].IsNull()) box.upper[c] = doc.number(v[1], item(at, 1));
      if (box.lower[c] > box.upper[c]) {
        doc.fail(v, at,
                 "lower bound " + show(box.lower[c]) + " > upper bound " + show(box.upper[c]));
      }
    } else if (v.IsScalar()) {
      box.lower[c] = box.upper[c] = doc.number(v, at);
    } else {
      doc.fail(v, at, "must be a number or a box [lo, hi] (got " + describe(v) + ")");
    }
  }
  return box;
}

// The disks of one section, `robots` or (with `object`) `objects`, appended to `disks`:
// names are unique across both. An object takes the non-force keys of `defaults`; a force
// key written on an object is an error (it has no force of its own).
void read_disks(const Doc& doc, const YAML::Node& seq, const std::string& section, bool object,
                const YAML::Node& defaults, double gravity, std::vector<Robot>& disks) {
  RobotDraft base;
  for (const auto& [key, node] : doc.mapping(defaults, "defaults", kFieldKeys, true)) {
    if (object && is_force_key(key)) continue;
    set_field(doc, key, node, child("defaults", key), base);
  }
  if (object) {
    base.robot.object = true;
    base.robot.force_max = 0.0;
    base.robot.force_dims = 0;
  }
  const std::string what = object ? "objects" : "robots";
  if (object && seq.IsNull()) return;
  if (!seq.IsSequence()) {
    doc.fail(seq, section, "must be a sequence of " + what + " (got " + describe(seq) + ")");
  }
  if (!object && seq.size() == 0) doc.fail(seq, section, "must list at least one robot");

  for (std::size_t i = 0; i < seq.size(); ++i) {
    const YAML::Node node = seq[i];
    const std::string path = item(section, i);
    const auto fields = doc.mapping(node, path, kRobotKeys, false);
    RobotDraft d = base;
    Robot& r = d.robot;

    const auto name_it = fields.find("name");
    if (name_it == fields.end()) doc.fail(node, child(path, "name"), "is required but missing");
    r.name = doc.name(name_it->second, child(path, "name"));
    for (std::size_t k = 0; k < disks.size(); ++k) {
      if (disks[k].name != r.name) continue;
      const std::size_t robots = static_cast<std::size_t>(
          std::count_if(disks.begin(), disks.end(), [](const Robot& x) { return !x.object; }));
      doc.fail(name_it->second, child(path, "name"),
               "duplicate name " + quote(r.name) + " (already used by " +
                   (k < robots ? item("robots", k) : item("objects", k - robots)) + ")");
    }

    for (const std::string& key : kFieldKeys) {
      const auto it = fields.find(key);
      if (it == fields.end()) continue;
      if (object && is_force_key(key)) {
        doc.fail(it->second, child(path, key),
                 "object " + quote(r.name) + " has no force of its own (an object moves only when "
                 "pushed); remove '" + key + "', or list it under 'robots' to drive it");
      }
      set_field(doc, key, it->second, child(path, key), d);
    }
    std::vector<std::string> required = {"radius", "mass", "mu"};
    if (!object) required.push_back("force_max");
    for (const std::string& key : required) {
      if (d.origin.count(key) == 0) {
        doc.fail(node, child(path, key), "is required (here or under 'defaults') but missing");
      }
    }
    if (d.origin.count("inertia") == 0) r.inertia = 0.5 * r.mass * r.radius * r.radius;
    if (d.origin.count("damping") == 0) r.damping = 0.1 * r.radius;

    const auto start_it = fields.find("start");
    if (start_it == fields.end()) doc.fail(node, child(path, "start"), "is required but missing");
    r.start = read_start(doc, start_it->second, child(path, "start"));
    if (const auto it = fields.find("target"); it != fields.end()) {
      r.target = read_target(doc, it->second, child(path, "target"));
    }

    const double resistance = r.mu * r.mass * gravity;
    if (!object && !(r.force_max > resistance)) {
      const Origin& o = d.origin.at("force_max");
      doc.fail(o.node, o.path,
               "robot " + quote(r.name) + " is too weak to move: force_max = " + show(r.force_max) +
                   " N must exceed mu * mass * gravity = " + show(r.mu) + " * " + show(r.mass) +
                   " * " + show(gravity) + " = " + show(resistance) +
                   " N (a disk with no force of its own belongs under 'objects')");
    }
    disks.push_back(r);
  }
}

// The `pairs` defaults (mode, safe_distance, mu) as a Pair.
Pair pair_defaults(const Doc& doc, const YAML::Node& n) {
  const auto fields = doc.mapping(n, "pairs", kPairsKeys, true);
  Pair base;
  base.mode = PairMode::kAvoid;
  base.safe_distance = 0.01;
  base.mu = 0.3;
  if (const auto it = fields.find("mode"); it != fields.end()) {
    base.mode = doc.mode(it->second, "pairs.mode");
  }
  if (const auto it = fields.find("safe_distance"); it != fields.end()) {
    base.safe_distance = doc.non_negative(it->second, "pairs.safe_distance");
  }
  if (const auto it = fields.find("mu"); it != fields.end()) {
    base.mu = doc.non_negative(it->second, "pairs.mu");
  }
  return base;
}

// Scene::pairs from the `pairs` defaults (`base`, pair_defaults) and `pairs.overrides`.
std::vector<Pair> read_pairs(const Doc& doc, const YAML::Node& n, const Pair& base,
                             const std::vector<Robot>& robots) {
  const auto fields = doc.mapping(n, "pairs", kPairsKeys, true);
  const int count = static_cast<int>(robots.size());
  std::vector<Pair> pairs;
  std::map<std::pair<int, int>, std::size_t> slot;  // (i, j) -> index in `pairs`
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      Pair p = base;
      // A pair with an object is a contact pair unless an override says otherwise: an
      // object moves only by contact.
      if (robots[i].object || robots[j].object) p.mode = PairMode::kContact;
      p.i = i;
      p.j = j;
      slot[{i, j}] = pairs.size();
      pairs.push_back(p);
    }
  }

  const auto ov_it = fields.find("overrides");
  if (ov_it == fields.end() || ov_it->second.IsNull()) return pairs;
  const YAML::Node& seq = ov_it->second;
  if (!seq.IsSequence()) {
    doc.fail(seq, "pairs.overrides",
             "must be a sequence of per-pair settings (got " + describe(seq) + ")");
  }
  std::map<std::pair<int, int>, std::string> seen;  // pair -> the override that set it
  for (std::size_t k = 0; k < seq.size(); ++k) {
    const YAML::Node entry = seq[k];
    const std::string path = item("pairs.overrides", k);
    const auto f = doc.mapping(entry, path, kPairOverrideKeys, false);
    const std::string rpath = child(path, "robots");
    const auto r_it = f.find("robots");
    if (r_it == f.end()) doc.fail(entry, rpath, "is required but missing");
    const YAML::Node& names = r_it->second;
    if (!names.IsSequence() || names.size() != 2) {
      doc.fail(names, rpath,
               "must be two robot or object names [a, b] (got " + describe(names) + ")");
    }
    int idx[2];
    for (int e = 0; e < 2; ++e) {
      const std::string nm = doc.text(names[e], item(rpath, e));
      idx[e] = -1;
      for (int r = 0; r < count; ++r) {
        if (robots[r].name == nm) idx[e] = r;
      }
      if (idx[e] < 0) doc.fail(names[e], item(rpath, e), "unknown robot or object name " + quote(nm));
    }
    if (idx[0] == idx[1]) {
      doc.fail(names, rpath,
               "a pair needs two distinct robots or objects (got " + quote(robots[idx[0]].name) + " twice)");
    }
    const std::pair<int, int> key{std::min(idx[0], idx[1]), std::max(idx[0], idx[1])};
    if (const auto s = seen.find(key); s != seen.end()) {
      doc.fail(names, rpath,
               "the pair (" + printable(robots[key.first].name, kEchoLimit) + ", " +
                   printable(robots[key.second].name, kEchoLimit) +
                   ") is already set by " + s->second);
    }
    seen[key] = path;
    Pair& p = pairs[slot.at(key)];
    if (const auto it = f.find("mode"); it != f.end()) {
      p.mode = doc.mode(it->second, child(path, "mode"));
    }
    if (const auto it = f.find("safe_distance"); it != f.end()) {
      p.safe_distance = doc.non_negative(it->second, child(path, "safe_distance"));
    }
    if (const auto it = f.find("mu"); it != f.end()) {
      p.mu = doc.non_negative(it->second, child(path, "mu"));
    }
  }
  return pairs;
}

// [x, y] at `path`.
std::array<double, 2> read_point(const Doc& doc, const YAML::Node& n, const std::string& path) {
  if (!n.IsSequence() || n.size() != 2) doc.fail(n, path, "must be a point [x, y] (got " + describe(n) + ")");
  return {doc.number(n[0], item(path, 0)), doc.number(n[1], item(path, 1))};
}

// A disk obstacle's `path` at `path`: >= 2 waypoints {t, x, y}, t >= 0 and increasing.
std::vector<Waypoint> read_path(const Doc& doc, const YAML::Node& n, const std::string& path) {
  if (!n.IsSequence() || n.size() < 2)
    doc.fail(n, path, "must be a sequence of at least two waypoints {t, x, y} (got " +
                          (n.IsSequence() ? std::to_string(n.size()) : describe(n)) + ")");
  std::vector<Waypoint> out;
  for (std::size_t k = 0; k < n.size(); ++k) {
    const std::string at = item(path, k);
    const auto w = doc.mapping(n[k], at, kWaypointKeys, false);
    for (const char* key : {"t", "x", "y"})
      if (w.count(key) == 0) doc.fail(n[k], child(at, key), "is required but missing");
    Waypoint p;
    p.t = doc.non_negative(w.at("t"), child(at, "t"));
    p.p = {doc.number(w.at("x"), child(at, "x")), doc.number(w.at("y"), child(at, "y"))};
    if (!out.empty() && !(p.t > out.back().t))
      doc.fail(w.at("t"), child(at, "t"),
               "waypoint times must increase (got " + show(p.t) + " after " + show(out.back().t) + ")");
    out.push_back(p);
  }
  return out;
}

// The `obstacles` sequence: Scene::obstacles, and Scene::obstacle_pairs from the `pairs`
// defaults (`base`), each obstacle's own mode / safe_distance / mu, and the rule that a
// pair with an object is a contact pair unless the obstacle names a mode.
void read_obstacles(const Doc& doc, const YAML::Node& seq, const Pair& base, Scene& scene) {
  if (seq.IsNull()) return;
  if (!seq.IsSequence())
    doc.fail(seq, "obstacles", "must be a sequence of obstacles (got " + describe(seq) + ")");
  for (std::size_t k = 0; k < seq.size(); ++k) {
    const YAML::Node node = seq[k];
    const std::string path = item("obstacles", k);
    const auto fields = doc.mapping(node, path, kObstacleKeys, false);
    Obstacle ob;
    const auto name_it = fields.find("name");
    if (name_it == fields.end()) doc.fail(node, child(path, "name"), "is required but missing");
    ob.name = doc.name(name_it->second, child(path, "name"));
    for (const Robot& r : scene.robots)
      if (r.name == ob.name)
        doc.fail(name_it->second, child(path, "name"),
                 "duplicate name " + quote(ob.name) + " (already used by a robot or object)");
    for (const Obstacle& o : scene.obstacles)
      if (o.name == ob.name)
        doc.fail(name_it->second, child(path, "name"),
                 "duplicate name " + quote(ob.name) + " (already used by another obstacle)");
    const auto disk_it = fields.find("disk"), wall_it = fields.find("wall");
    if ((disk_it == fields.end()) == (wall_it == fields.end()))
      doc.fail(node, path, "an obstacle is either a 'disk' or a 'wall': give exactly one of them");
    if (disk_it != fields.end()) {
      const std::string dpath = child(path, "disk");
      const auto d = doc.mapping(disk_it->second, dpath, kDiskObstacleKeys, false);
      ob.shape = ObstacleShape::kDisk;
      if (d.count("radius") == 0) doc.fail(disk_it->second, child(dpath, "radius"), "is required but missing");
      ob.radius = doc.positive(d.at("radius"), child(dpath, "radius"));
      if (const auto path_it = d.find("path"); path_it != d.end()) {
        ob.path = read_path(doc, path_it->second, child(dpath, "path"));
        for (const char* key : {"x", "y", "vx", "vy"})
          if (d.count(key) != 0)
            doc.fail(d.at(key), child(dpath, key),
                     "a disk that follows a path starts at its first waypoint and moves along it: "
                     "give either 'path' or 'x', 'y' (and 'vx', 'vy'), not both");
        ob.from = ob.path.front().p;
      } else {
        for (const char* key : {"x", "y"})
          if (d.count(key) == 0)
            doc.fail(disk_it->second, child(dpath, key), "is required but missing (or give a 'path')");
        ob.from = {doc.number(d.at("x"), child(dpath, "x")), doc.number(d.at("y"), child(dpath, "y"))};
        if (const auto it = d.find("vx"); it != d.end()) ob.velocity[0] = doc.number(it->second, child(dpath, "vx"));
        if (const auto it = d.find("vy"); it != d.end()) ob.velocity[1] = doc.number(it->second, child(dpath, "vy"));
      }
      ob.to = ob.from;
    } else {
      const std::string wpath = child(path, "wall");
      const auto w = doc.mapping(wall_it->second, wpath, kWallKeys, false);
      for (const char* key : {"from", "to"})
        if (w.count(key) == 0) doc.fail(wall_it->second, child(wpath, key), "is required but missing");
      ob.shape = ObstacleShape::kWall;
      ob.from = read_point(doc, w.at("from"), child(wpath, "from"));
      ob.to = read_point(doc, w.at("to"), child(wpath, "to"));
      if (const auto it = w.find("thickness"); it != w.end())
        ob.radius = 0.5 * doc.non_negative(it->second, child(wpath, "thickness"));
      const double length = std::hypot(ob.to[0] - ob.from[0], ob.to[1] - ob.from[1]);
      const double scale = std::max({std::abs(ob.from[0]), std::abs(ob.from[1]), std::abs(ob.to[0]),
                                     std::abs(ob.to[1]), ob.radius});
      if (!(length > 1e-9 * scale))
        doc.fail(w.at("to"), child(wpath, "to"),
                 "a wall needs two distinct ends (got a wall of length " + show(length) +
                     "); for a round post use 'disk'");
    }
    Pair own = base;
    bool own_mode = false;
    if (const auto it = fields.find("mode"); it != fields.end())
      own.mode = doc.mode(it->second, child(path, "mode")), own_mode = true;
    if (const auto it = fields.find("safe_distance"); it != fields.end())
      own.safe_distance = doc.non_negative(it->second, child(path, "safe_distance"));
    if (const auto it = fields.find("mu"); it != fields.end())
      own.mu = doc.non_negative(it->second, child(path, "mu"));
    // A moving obstacle could push (add energy), which the model does not state: its
    // pairs are avoid pairs.
    if (ob.moves()) {
      if (own_mode && own.mode == PairMode::kContact)
        doc.fail(fields.at("mode"), child(path, "mode"),
                 "a moving obstacle cannot be a contact obstacle (it could push, which disco does "
                 "not model): use mode avoid");
      own.mode = PairMode::kAvoid;
      own_mode = true;
    }
    const int j = static_cast<int>(scene.obstacles.size());
    scene.obstacles.push_back(ob);
    for (int i = 0; i < static_cast<int>(scene.robots.size()); ++i) {
      Pair p = own;
      if (!own_mode && scene.robots[i].object) p.mode = PairMode::kContact;
      p.i = i;
      p.j = j;
      scene.obstacle_pairs.push_back(p);
    }
  }
}

// No disk may start inside an obstacle (nor closer than an avoid pair's safe distance).
void check_obstacle_clearance(const Doc& doc, const DiskNodes& nodes, const Scene& scene) {
  for (const Pair& p : scene.obstacle_pairs) {
    const Robot& a = scene.robots[p.i];
    const Obstacle& ob = scene.obstacles[p.j];
    const double dist = obstacle_distance(ob, {a.start[kX], a.start[kY]}, 0.0);
    const std::string what = disk_name(a) + " and obstacle " + quote(ob.name);
    const YAML::Node at = nodes.at(p.i)["start"];
    const std::string path = child(nodes.path(p.i), "start");
    const double touch = a.radius + ob.radius;
    const std::string core = ob.shape == ObstacleShape::kWall ? "centre line" : "centre";
    if (dist < touch * (1 - kTouchTolerance))
      doc.fail(at, path,
               what + " overlap at the start: the centre is " + show(dist) + " from the obstacle's " +
                   core + ", less than R + R_obstacle = " + show(touch));
    const double clear = obstacle_clearance(scene, p);
    if (p.mode == PairMode::kAvoid && dist < clear * (1 - kTouchTolerance))
      doc.fail(at, path,
               what + " (an avoid pair) start too close: the centre is " + show(dist) +
                   " from the obstacle's " + core + ", less than R + R_obstacle + safe_distance = " + show(clear) +
                   " (move it, lower the obstacle's safe_distance or use mode contact)");
  }
}

void check_start_clearance(const Doc& doc, const DiskNodes& nodes, const Scene& scene) {
  for (const Pair& p : scene.pairs) {
    const Robot& a = scene.robots[p.i];
    const Robot& b = scene.robots[p.j];
    const double dist = std::hypot(b.start[kX] - a.start[kX], b.start[kY] - a.start[kY]);
    const double touch = a.radius + b.radius;
    const std::string path = child(nodes.path(p.j), "start");
    const YAML::Node at = nodes.at(p.j)["start"];
    const std::string names = disk_pair_names(a, b);
    if (dist < touch * (1 - kTouchTolerance)) {
      doc.fail(at, path,
               names + " overlap at the start: centre distance " + show(dist) +
                   " < R_i + R_j = " + show(touch));
    }
    const double clear = clearance(scene, p);
    if (p.mode == PairMode::kAvoid && dist < clear * (1 - kTouchTolerance)) {
      doc.fail(at, path,
               names + " (an avoid pair) start too close: centre distance " + show(dist) +
                   " < R_i + R_j + safe_distance = " + show(clear) +
                   " (move them apart, lower safe_distance or use mode contact)");
    }
  }
}

// A scene must ask for something, and nothing it asks for may be out of reach for a reason
// the scene alone shows (core/model/reachability.h).
void check_targets(const Doc& doc, const DiskNodes& nodes, const Scene& scene) {
  if (!has_any_target(scene))
    doc.fail(nodes.robots, "robots",
             nodes.robot_count == scene.robots.size()
                 ? "no robot has a target (every target is missing or unbounded), so there is "
                   "nothing to reach and T_f would be 0; give at least one robot a target"
                 : "no robot or object has a target (every target is missing or unbounded), so "
                   "there is nothing to reach and T_f would be 0; give at least one a target");
  const std::vector<Unreachable> bad = unreachable_targets(scene);
  if (bad.empty()) return;
  const Unreachable& u = bad.front();
  const YAML::Node robot = nodes.at(u.robot);
  const YAML::Node target = robot["target"];
  doc.fail(target.IsDefined() ? target : robot, child(nodes.path(u.robot), "target"),
           "unreachable: " + u.reason);
}

// `objective`: a kind alone ("time"), or a mapping {kind, horizon (energy), energy_weight
// (time + energy)}. Read after the disks: an energy horizon below the scene's lower bound on
// T_f is refused here, since no motion reaches the targets in it.
Objective read_objective(const Doc& doc, const YAML::Node& node, const Scene& scene) {
  const bool map = node.IsMap();
  const auto fields = map ? doc.mapping(node, "objective", kObjectiveKeys, false)
                          : std::map<std::string, YAML::Node>{};
  const auto kind_it = fields.find("kind");
  if (map && kind_it == fields.end()) doc.fail(node, "objective.kind", "is required but missing");
  const YAML::Node kind_node = map ? kind_it->second : node;
  const std::string kind_key = map ? "objective.kind" : "objective";
  std::string word = doc.text(kind_node, kind_key);
  // "time+energy", "time +  energy": one spelling.
  std::string compact;
  for (char c : word)
    if (c != ' ') compact += c;
  if (compact == "time+energy") word = "time + energy";
  Objective o;
  if (word == "time")
    o.kind = ObjectiveKind::kTime;
  else if (word == "energy")
    o.kind = ObjectiveKind::kEnergy;
  else if (word == "time + energy")
    o.kind = ObjectiveKind::kTimeEnergy;
  else
    doc.fail(kind_node, kind_key,
             "unknown objective " + quote(word) + did_you_mean(word, kObjectiveKinds) +
                 " (allowed: 'time', 'energy', 'time + energy')");
  // Each kind takes exactly its own parameter.
  auto param = [&](const std::string& key, bool needed, const std::string& what) -> double {
    const auto it = fields.find(key);
    if (!needed) {
      if (it != fields.end())
        doc.fail(it->second, "objective." + key, "applies to objective " + what + " only, not " + quote(word));
      return 0.0;
    }
    if (it == fields.end())
      doc.fail(node, "objective." + key,
               "is required for objective " + quote(word) + " (write objective: {kind: " + word +
                   ", " + key + ": ...})");
    return doc.positive(it->second, "objective." + key);
  };
  o.horizon = param("horizon", o.kind == ObjectiveKind::kEnergy, "'energy'");
  o.energy_weight = param("energy_weight", o.kind == ObjectiveKind::kTimeEnergy, "'time + energy'");
  if (o.kind == ObjectiveKind::kEnergy) {
    const auto lb = scene_lower_bound(scene);
    if (lb && o.horizon < *lb)
      doc.fail(fields.at("horizon"), "objective.horizon",
               "is below the scene's lower bound on T_f, " + show(*lb) +
                   " s (core/model/lower_bound.h): no motion reaches the targets in " +
                   show(o.horizon) + " s");
  }
  return o;
}

Scene validate(const Doc& doc, const YAML::Node& root, const std::string& source) {
  const auto fields = doc.mapping(root, "", kRootKeys, false);
  auto required = [&](const std::string& key) -> const YAML::Node& {
    const auto it = fields.find(key);
    if (it == fields.end()) doc.fail(root, key, "is required but missing");
    return it->second;
  };
  Scene scene;
  scene.source = source;
  scene.name = doc.name(required("scenario"), "scenario");
  if (const auto it = fields.find("description"); it != fields.end() && !it->second.IsNull()) {
    doc.text(it->second, "description");
  }
  const YAML::Node& steps = required("steps");
  scene.steps = doc.integer(steps, "steps");
  if (scene.steps < 1) {
    doc.fail(steps, "steps", "must be >= 1 (got " + std::to_string(scene.steps) + ")");
  }
  scene.steps_origin = doc.origin(steps, "steps");
  scene.gravity = 9.81;
  if (const auto it = fields.find("gravity"); it != fields.end()) {
    scene.gravity = doc.positive(it->second, "gravity");
  }
  const auto def_it = fields.find("defaults");
  const YAML::Node defaults = def_it == fields.end() ? YAML::Node() : def_it->second;
  DiskNodes nodes;
  nodes.robots = required("robots");
  read_disks(doc, nodes.robots, "robots", false, defaults, scene.gravity, scene.robots);
  nodes.robot_count = scene.robots.size();
  if (const auto it = fields.find("objects"); it != fields.end()) {
    nodes.objects = it->second;
    read_disks(doc, nodes.objects, "objects", true, defaults, scene.gravity, scene.robots);
  }
  const auto pairs_it = fields.find("pairs");
  const YAML::Node pairs = pairs_it == fields.end() ? YAML::Node() : pairs_it->second;
  const Pair base = pair_defaults(doc, pairs);
  scene.pairs = read_pairs(doc, pairs, base, scene.robots);
  YAML::Node obstacles;
  if (const auto it = fields.find("obstacles"); it != fields.end()) {
    obstacles = it->second;
    read_obstacles(doc, obstacles, base, scene);
  }
  check_start_clearance(doc, nodes, scene);
  check_obstacle_clearance(doc, nodes, scene);
  check_targets(doc, nodes, scene);
  if (const auto it = fields.find("objective"); it != fields.end())
    scene.objective = read_objective(doc, it->second, scene);
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides) {
  YAML::Node root = yaml::load(text, source);
  if (!root.IsMap()) {
    const Doc plain(source, {});
    if (root.IsNull()) plain.fail(root, "", "the scene is empty");
    plain.fail(root, "", "a scene must be a YAML mapping (got " + describe(root) + ")");
  }
  std::vector<OverrideRecord> records;
  for (const std::string& o : overrides) apply_override(root, o, records);
  const Doc doc(source, std::move(records));
  try {
    return validate(doc, root, source);
  } catch (const YAML::Exception& e) {
    // Not expected: every access above is checked. Still a user-input problem.
    throw InputError(located_message(source, yaml::line_of(e.mark), "", e.msg));
  }
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(yaml::read_file(path, "scene file"), path, overrides);
}

}  // namespace disco
