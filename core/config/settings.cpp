// disco — solver settings. See settings.h.
#include "core/config/settings.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <set>
#include <system_error>
#include <utility>

#include "core/config/yaml_nodes.h"
#include "core/util/errors.h"
#include "core/util/suggest.h"

namespace disco {
namespace {

using yaml::describe;
using yaml::is_index;
using yaml::kOverrideSource;
using yaml::line_of;
using yaml::override_fail;
using yaml::split_dots;

// The default settings file's path below the prefix (core/CMakeLists.txt).
constexpr const char* kDefaultSettingsFile = DISCO_DEFAULT_SETTINGS;

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

  // The scalar at `key` converted to T; InputError "must be KIND (got ...)" if missing, not
  // a scalar, a quoted string, or not convertible. `node` (if given) receives the scalar.
  template <typename T>
  T typed(const std::string& key, const char* kind, YAML::Node* node = nullptr) const {
    const YAML::Node n = scalar(key, kind);
    if (node != nullptr) node->reset(n);
    const std::string what = std::string("must be ") + kind + " (got " + describe(n) + ")";
    if (n.Tag() == "!") fail(key, n, what);
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(key, n, what);
    }
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
  if (path == default_settings_path() && !std::filesystem::exists(path, ec)) {
    throw InputError(located_message(
        path, 0, "",
        std::string("no settings file here: without --settings, disco reads ") +
            kDefaultSettingsFile +
            " under its prefix (the directory above the one holding the executable; a build "
            "tree gets it when CMake configures it); pass --settings FILE"));
  }
  return parse(yaml::read_file(path, "settings file"), path);
}

Settings Settings::parse(const std::string& text, const std::string& source) {
  Settings s;
  s.impl_->source = source;
  const YAML::Node root = yaml::load(text, source);
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

// "no such setting in FILE ...", with the settings keys close to `key`, or, for a key
// outside every settings section, the hint that scene keys take the prefix "scene.".
std::string Settings::no_such_setting(const std::string& key) const {
  std::vector<std::string> keys;
  for (const auto& [k, v] : values()) keys.push_back(k);
  std::string hint = did_you_mean(key, keys);
  const std::string first = key.substr(0, key.find('.'));
  if (hint.empty() && !child_of(impl_->root, first).IsDefined())
    hint = " (" + first + " is not a settings section; a scene key takes the prefix 'scene.': scene." +
           key + ")";
  return "no such setting in " + impl_->source + hint + "; only ipopt.* options may be new";
}

void Settings::apply_override(const std::string& assignment) {
  const yaml::Override o = yaml::parse_override(assignment, "elastic.zeta");
  const std::string& key = o.key;
  const std::string& text = o.text;
  const std::vector<std::string>& parts = o.parts;
  const YAML::Node& value = o.value;
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
    if (!next.IsDefined()) override_fail(key, no_such_setting(key));
    parent.reset(next);
  }
  const std::string& last = parts.back();
  const YAML::Node existing = child_of(parent, last);
  if (!existing.IsDefined() && !ipopt) override_fail(key, no_such_setting(key));
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
  YAML::Node n;
  const double v = impl_->typed<double>(key, "a number", &n);
  if (std::isnan(v)) impl_->fail(key, n, "must be a number, not NaN");
  return v;
}

int Settings::integer(const std::string& key) const {
  return impl_->typed<int>(key, "an integer");
}

bool Settings::boolean(const std::string& key) const {
  return impl_->typed<bool>(key, "true or false");
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

std::vector<std::pair<std::string, std::string>> Settings::values() const {
  std::vector<std::pair<std::string, std::string>> out;
  auto walk = [&](auto& self, const YAML::Node& node, const std::string& key) -> void {
    if (node.IsMap()) {
      for (const auto& kv : node)
        self(self, kv.second, (key.empty() ? "" : key + ".") + kv.first.as<std::string>());
    } else if (node.IsSequence()) {
      for (std::size_t k = 0; k < node.size(); ++k)
        self(self, node[k], key + "[" + std::to_string(k) + "]");
    } else {
      out.emplace_back(key, node.IsScalar() ? node.Scalar() : std::string("~"));
    }
  };
  walk(walk, impl_->root, "");
  std::sort(out.begin(), out.end());
  return out;
}

std::string Settings::canonical_text() const {
  std::string text;
  for (const auto& [key, value] : values()) text += key + ": " + value + "\n";
  return text;
}

std::string Settings::where(const std::string& key) const {
  if (impl_->overridden.count(key) != 0) return kOverrideSource;
  const YAML::Node n = impl_->find(key);
  const int line = line_of(n);
  if (line == 0) return impl_->source;
  return impl_->source + ":" + std::to_string(line);
}

std::string default_settings_path() {
  static const std::string path = [] {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    // Unreadable (no /proc): a path that cannot exist, naming how it was looked for.
    if (ec) return std::string("/proc/self/exe/../../") + kDefaultSettingsFile;
    return (exe.parent_path().parent_path() / kDefaultSettingsFile).string();
  }();
  return path;
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
