// disco — solver settings. See settings.h.
#include "core/config/settings.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "core/util/errors.h"

namespace disco {
namespace {

const char* const kOverrideSource = "--set";

[[noreturn]] void override_fail(const std::string& key, const std::string& what) {
  throw InputError(located_message(kOverrideSource, 0, key, what));
}

int line_of(const YAML::Node& n) {
  if (!n.IsDefined()) return 0;
  const YAML::Mark mark = n.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

std::string describe(const YAML::Node& n) {
  if (!n.IsDefined()) return "nothing";
  switch (n.Type()) {
    case YAML::NodeType::Null:
      return "null";
    case YAML::NodeType::Scalar:
      return n.Tag() == "!" ? "the quoted string \"" + n.Scalar() + "\"" : "'" + n.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a sequence";
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "nothing";
  }
}

std::vector<std::string> split_dots(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t dot = key.find('.', begin);
    parts.push_back(key.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  return parts;
}

bool is_index(const std::string& s) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// The child of `n` named `part` (a key of a mapping or an index of a sequence), or an
// undefined node.
YAML::Node child_of(const YAML::Node& n, const std::string& part) {
  if (n.IsMap()) return n[part];
  if (n.IsSequence() && is_index(part)) {
    const std::size_t index = std::stoul(part);
    if (index < n.size()) return n[index];
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

// Rejects non-scalar or repeated mapping keys anywhere below `n` (yaml-cpp keeps both).
void check_keys(const YAML::Node& n, const std::string& path, const std::string& source) {
  if (n.IsMap()) {
    std::set<std::string> seen;
    for (const auto& kv : n) {
      const YAML::Node& k = kv.first;
      if (!k.IsScalar()) {
        throw InputError(
            located_message(source, line_of(k), path, "mapping keys must be plain names"));
      }
      const std::string at = path.empty() ? k.Scalar() : path + "." + k.Scalar();
      if (!seen.insert(k.Scalar()).second) {
        throw InputError(located_message(source, line_of(k), at, "duplicate key"));
      }
      check_keys(kv.second, at, source);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) {
      check_keys(n[i], path + "." + std::to_string(i), source);
    }
  }
}

}  // namespace

struct Settings::Impl {
  YAML::Node root{YAML::NodeType::Map};
  std::string source;
  std::set<std::string> overridden;  // keys set by apply_override

  // The node at dotted `key`, or an undefined node. `deepest` receives the deepest existing
  // ancestor (for the line of "missing" messages).
  YAML::Node find(const std::string& key, YAML::Node* deepest = nullptr) const {
    YAML::Node cur = root;
    for (const std::string& part : split_dots(key)) {
      const YAML::Node next = child_of(cur, part);
      if (!next.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
      cur.reset(next);
      if (deepest != nullptr) deepest->reset(cur);
    }
    return cur;
  }

  [[noreturn]] void fail(const std::string& key, const YAML::Node& at,
                         const std::string& what) const {
    if (overridden.count(key) != 0)
      throw InputError(located_message(kOverrideSource, 0, key, what));
    throw InputError(located_message(source, line_of(at), key, what));
  }

  // The scalar at `key`, as a node; InputError if missing or not a scalar.
  YAML::Node scalar(const std::string& key, const char* kind) const {
    YAML::Node deepest;
    const YAML::Node n = find(key, &deepest);
    if (!n.IsDefined()) {
      throw InputError(
          located_message(source, line_of(deepest), key, "is missing from the settings"));
    }
    if (!n.IsScalar()) fail(key, n, std::string("must be ") + kind + " (got " + describe(n) + ")");
    return n;
  }
};

Settings::Settings() : impl_(std::make_unique<Impl>()) {}
Settings::~Settings() = default;
Settings::Settings(Settings&&) noexcept = default;
Settings& Settings::operator=(Settings&&) noexcept = default;

Settings::Settings(const Settings& other) : impl_(std::make_unique<Impl>(*other.impl_)) {
  impl_->root.reset(YAML::Clone(other.impl_->root));  // never operator=: it aliases
}

Settings& Settings::operator=(const Settings& other) {
  if (this != &other) {
    auto copy = std::make_unique<Impl>(*other.impl_);
    copy->root.reset(YAML::Clone(other.impl_->root));
    impl_ = std::move(copy);
  }
  return *this;
}

Settings Settings::load(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(located_message(path, 0, "", "cannot open settings file: it is a directory"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(located_message(path, 0, "", "cannot open settings file"));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(located_message(path, 0, "", "cannot read settings file"));
  return parse(text.str(), path);
}

Settings Settings::parse(const std::string& text, const std::string& source) {
  Settings s;
  s.impl_->source = source;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const int line = e.mark.is_null() ? 0 : e.mark.line + 1;
    throw InputError(located_message(source, line, "", "YAML syntax error: " + e.msg));
  }
  if (root.IsNull()) return s;  // an empty file: no settings
  if (!root.IsMap()) {
    throw InputError(
        located_message(source, line_of(root), "",
                        "a settings file must be a YAML mapping (got " + describe(root) + ")"));
  }
  check_keys(root, "", source);
  s.impl_->root.reset(root);
  return s;
}

void Settings::apply_override(const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos) override_fail(assignment, "expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  const std::vector<std::string> parts = split_dots(key);
  for (const std::string& p : parts) {
    if (p.empty()) override_fail(key, "malformed key (expected a dotted path like elastic.zeta)");
  }
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    override_fail(key, "cannot parse the value '" + text + "' as YAML: " + e.msg);
  }
  if (value.IsNull()) override_fail(key, "needs a value (got '" + text + "')");
  if (!value.IsScalar())
    override_fail(key, "the value must be a single scalar (got " + describe(value) + ")");

  const bool ipopt = parts.size() == 2 && parts[0] == "ipopt";
  YAML::Node& root = impl_->root;
  if (ipopt) {
    const YAML::Node& croot = root;
    const YAML::Node section = croot["ipopt"];
    if (!section.IsDefined() || section.IsNull()) root["ipopt"] = YAML::Node(YAML::NodeType::Map);
    const YAML::Node now = croot["ipopt"];
    if (!now.IsMap()) override_fail(key, "'ipopt' in " + impl_->source + " is not a mapping");
  }
  YAML::Node parent = root;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
    const YAML::Node next = child_of(parent, parts[k]);
    if (!next.IsDefined()) {
      override_fail(key,
                    "no such setting in " + impl_->source + " (only ipopt.* options may be new)");
    }
    parent.reset(next);
  }
  const std::string& last = parts.back();
  const YAML::Node existing = child_of(parent, last);
  if (!existing.IsDefined() && !ipopt) {
    override_fail(key,
                  "no such setting in " + impl_->source + " (only ipopt.* options may be new)");
  }
  if (existing.IsDefined() && (existing.IsMap() || existing.IsSequence())) {
    override_fail(key, "is a section, not a single setting");
  }
  if (parent.IsMap()) {
    parent[last] = value;
  } else if (parent.IsSequence()) {
    parent[static_cast<std::size_t>(std::stoul(last))] = value;
  } else {
    override_fail(key, "no such setting in " + impl_->source);
  }
  impl_->overridden.insert(key);
}

double Settings::number(const std::string& key) const {
  const YAML::Node n = impl_->scalar(key, "a number");
  const std::string what = "must be a number (got " + describe(n) + ")";
  if (n.Tag() == "!") impl_->fail(key, n, what);
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    impl_->fail(key, n, what);
  }
  if (std::isnan(v)) impl_->fail(key, n, "must be a number, not NaN");
  return v;
}

int Settings::integer(const std::string& key) const {
  const YAML::Node n = impl_->scalar(key, "an integer");
  const std::string what = "must be an integer (got " + describe(n) + ")";
  if (n.Tag() == "!") impl_->fail(key, n, what);
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    impl_->fail(key, n, what);
  }
}

bool Settings::boolean(const std::string& key) const {
  const YAML::Node n = impl_->scalar(key, "true or false");
  const std::string what = "must be true or false (got " + describe(n) + ")";
  if (n.Tag() == "!") impl_->fail(key, n, what);
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    impl_->fail(key, n, what);
  }
}

std::string Settings::text(const std::string& key) const {
  return impl_->scalar(key, "text").Scalar();
}

std::vector<Settings::Entry> Settings::section(const std::string& key) const {
  YAML::Node deepest;
  const YAML::Node n = impl_->find(key, &deepest);
  if (!n.IsDefined()) {
    throw InputError(located_message(impl_->source, line_of(deepest), key,
                                     "section is missing from the settings"));
  }
  std::vector<Entry> out;
  if (n.IsNull()) return out;
  if (!n.IsMap()) impl_->fail(key, n, "must be a section (a mapping; got " + describe(n) + ")");
  for (const auto& kv : n) {
    const std::string name = kv.first.Scalar();
    const std::string full = key + "." + name;
    const YAML::Node& v = kv.second;
    if (!v.IsScalar()) impl_->fail(full, v, "must be a single value (got " + describe(v) + ")");
    const bool over = impl_->overridden.count(full) != 0;
    out.push_back(Entry{name, v.Scalar(), over ? 0 : line_of(v)});
  }
  return out;
}

const std::string& Settings::source() const { return impl_->source; }

std::string Settings::where(const std::string& key) const {
  if (impl_->overridden.count(key) != 0) return kOverrideSource;
  const YAML::Node n = impl_->find(key);
  const int line = line_of(n);
  if (line == 0) return impl_->source;
  return impl_->source + ":" + std::to_string(line);
}

void split_overrides(const std::vector<std::string>& sets, std::vector<std::string>& scene,
                     std::vector<std::string>& settings) {
  static const std::string kScenePrefix = "scene.";
  for (const std::string& s : sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos) override_fail(s, "expected KEY=VALUE");
    if (eq == 0) override_fail(s, "empty key (expected KEY=VALUE)");
    if (s.compare(0, kScenePrefix.size(), kScenePrefix) == 0) {
      scene.push_back(s.substr(kScenePrefix.size()));
    } else {
      settings.push_back(s);
    }
  }
}

}  // namespace disco
