// disco — solver settings, read from a YAML file (configs/disco.yaml; installed as
// share/disco/configs/disco.yaml, see default_settings_path) and command-line overrides.
//
// The settings file is one YAML mapping of sections ("ipopt:", "elastic:", ...). Code asks
// for values by dotted key ("elastic.zeta_max") with the accessor of the expected type; a
// missing key or a value of the wrong type is an InputError that names the file, the line
// and the key (or "--set" and the key, when the value came from an override).
//
// Typing rules: number() takes any plain YAML number, including .inf / -.inf, but not .nan
// nor a quoted string; integer() takes only integers ("2.5" and "1e3" are rejected);
// boolean() takes YAML booleans (true/false, yes/no, on/off); text() takes any scalar.
//
// Overrides: "KEY=VALUE" with VALUE parsed as a YAML scalar. KEY must name an existing value
// (not a section) of the loaded document; keys "ipopt.NAME" may also be new, because Ipopt
// checks its own options. Duplicate keys in the file are rejected on load.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace disco {

class Settings {
 public:
  // An empty document with no source: every lookup fails. Useful only as a placeholder.
  Settings();
  ~Settings();
  Settings(const Settings& other);  // deep copy: overriding a copy leaves the original alone
  Settings& operator=(const Settings& other);
  Settings(Settings&&) noexcept;
  Settings& operator=(Settings&&) noexcept;

  // Reads the settings file at `path`. InputError if it cannot be opened, is not valid YAML,
  // is not a mapping or repeats a key (for default_settings_path(), below, if it is not
  // there: the message says where disco looks and to pass --settings FILE).
  static Settings load(const std::string& path);
  // Same, from text in memory; `source` names it in messages.
  static Settings parse(const std::string& text, const std::string& source);

  // Applies "a.b.c=value" (see the file comment). InputError naming "--set" and the key if
  // the assignment is malformed, the key does not exist (outside "ipopt."), names a section,
  // or the value is not a single YAML scalar.
  void apply_override(const std::string& assignment);

  // The value at dotted `key`. InputError if it is missing or has the wrong type; the
  // message gives the source, the line and the key.
  double number(const std::string& key) const;
  int integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string text(const std::string& key) const;

  // One scalar entry of a mapping section. `line` is the 1-based line in the file, or 0 when
  // the entry was set by an override.
  struct Entry {
    std::string name, value;
    int line;
  };
  // The scalar entries of mapping section `key`, in file order (entries added by overrides
  // come last), e.g. the "ipopt" options to hand to Ipopt. An empty (null) section gives no
  // entries. InputError if the section is missing, is not a mapping, or holds a non-scalar.
  std::vector<Entry> section(const std::string& key) const;

  // The file (or `source` given to parse()).
  const std::string& source() const;

  // The settings in effect (the file's values after every override): every scalar as
  // (dotted key, text as written), sorted by key; null values read "~".
  std::vector<std::pair<std::string, std::string>> values() const;
  // values() as "KEY: VALUE" lines: equal texts mean equal settings, whatever the file's
  // layout, order and comments. Its SHA-256 is the settings hash of run manifests and
  // solution files.
  std::string canonical_text() const;

  // Where `key` was defined, for messages made by other code: "FILE:LINE", or "--set" when
  // an override set it. For a key that does not exist, just "FILE".
  std::string where(const std::string& key) const;

 private:
  std::string no_such_setting(const std::string& key) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The settings file read when none is given (--settings): PREFIX/share/disco/configs/disco.yaml,
// PREFIX being the directory above the one holding the running executable (found through
// /proc/self/exe). So PREFIX/bin/disco reads PREFIX/share/disco/configs/disco.yaml (the
// install's copy of configs/disco.yaml), and in a build tree BUILD/mpi/disco and the test
// binaries in BUILD/tests read BUILD/share/disco/configs/disco.yaml, a link to the source's
// configs/disco.yaml that CMake makes when it configures (so edits need no rebuild). No
// source path is compiled in (the relative path comes from CMake: DISCO_SETTINGS_FILE).
// Settings::load of this path, when nothing is there, is an InputError that names the path
// and says to pass --settings FILE.
std::string default_settings_path();

// Splits command-line "--set" assignments: entries starting with "scene." go to `scene`
// with that prefix removed (for load_scene), all others to `settings` (for
// Settings::apply_override), keeping their order. Appends to both outputs. InputError
// naming "--set" for an entry without '=' or with an empty key.
void split_overrides(const std::vector<std::string>& sets, std::vector<std::string>& scene,
                     std::vector<std::string>& settings);

}  // namespace disco
