// disco — small yaml-cpp helpers shared by the two YAML readers: the settings file
// (core/config/settings.cpp) and the scene file (core/model/scene_yaml.cpp).
//
// Everything here that fails throws InputError with the standard located message
// (core/util/errors.h), so both readers word the same problem the same way.
//
//   kOverrideSource   the source named in messages about a "--set KEY=VALUE" override.
//   override_fail     throws InputError "--set: key 'KEY': WHAT".
//   line_of(node)     the 1-based line where a node starts; 0 if it is undefined or unmarked.
//   line_of(mark)     the 1-based line of a mark (e.g. a YAML::Exception's); 0 if null.
//   describe          what a node holds, for the "(got ...)" part of messages: "nothing",
//                     "null", "'text'", "the quoted string \"text\"", "a sequence" or
//                     "a mapping"; text is cut after kEchoLimit bytes (errors.h, printable).
//   split_dots        "a.b.0" -> {"a", "b", "0"}; empty parts are kept ("a..b", ".a").
//   is_index          true for 1 to 9 decimal digits: a usable sequence index.
//   read_file         the whole text of the file at `path`; InputError if it is a directory
//                     or cannot be opened or read ("cannot open settings file", ...).
//   load              parses one YAML document; InputError "YAML syntax error: ..." with its
//                     line if the text is not valid YAML.
//   parse_override    splits "KEY=VALUE" into the key, its dotted parts and the value parsed
//                     as YAML; InputError (as an override) if there is no '=', a part of the
//                     key is empty, or the value is not valid YAML.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace disco::yaml {

inline constexpr const char* kOverrideSource = "--set";

[[noreturn]] void override_fail(const std::string& key, const std::string& what);

int line_of(const YAML::Node& n);
int line_of(const YAML::Mark& mark);

std::string describe(const YAML::Node& n);

std::vector<std::string> split_dots(const std::string& key);

bool is_index(const std::string& s);

// `what` names the kind of file in messages, e.g. "settings file" or "scene file".
std::string read_file(const std::string& path, const std::string& what);

// `source` names the text in messages (usually its file path).
YAML::Node load(const std::string& text, const std::string& source);

// One "KEY=VALUE" override as given to --set.
struct Override {
  std::string key;                 // KEY, as given
  std::string text;                // VALUE, as given
  std::vector<std::string> parts;  // KEY split at its dots; none empty
  YAML::Node value;                // VALUE parsed as YAML (null for an empty VALUE)
};

// `example` is a well-formed key shown in the message for a malformed one.
Override parse_override(const std::string& assignment, const std::string& example);

}  // namespace disco::yaml
