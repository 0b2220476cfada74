// disco — yaml-cpp helpers shared by the settings and scene readers. See yaml_nodes.h.
#include "core/config/yaml_nodes.h"

#include <yaml-cpp/depthguard.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/util/errors.h"

namespace disco::yaml {

namespace {

// yaml-cpp's message for `e`, except for nesting deeper than its limit, which it calls a
// "bad file".
std::string reason(const YAML::Exception& e) {
  if (const auto* deep = dynamic_cast<const YAML::DeepRecursion*>(&e)) {
    return "nesting too deep (" + std::to_string(deep->depth()) + " levels)";
  }
  return e.msg;
}

}  // namespace

void override_fail(const std::string& key, const std::string& what) {
  throw InputError(located_message(kOverrideSource, 0, key, what));
}

int line_of(const YAML::Node& n) {
  if (!n.IsDefined()) return 0;
  return line_of(n.Mark());
}

int line_of(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

std::string describe(const YAML::Node& n) {
  if (!n.IsDefined()) return "nothing";
  switch (n.Type()) {
    case YAML::NodeType::Null:
      return "null";
    case YAML::NodeType::Scalar: {
      const std::string text = printable(n.Scalar(), kEchoLimit);
      return n.Tag() == "!" ? "the quoted string \"" + text + "\"" : "'" + text + "'";
    }
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

std::string read_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(located_message(path, 0, "", "cannot open " + what + ": it is a directory"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(located_message(path, 0, "", "cannot open " + what));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(located_message(path, 0, "", "cannot read " + what));
  return text.str();
}

YAML::Node load(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(located_message(source, line_of(e.mark), "", "YAML syntax error: " + reason(e)));
  }
}

Override parse_override(const std::string& assignment, const std::string& example) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos) override_fail(assignment, "expected KEY=VALUE");
  Override o;
  o.key = assignment.substr(0, eq);
  o.text = assignment.substr(eq + 1);
  o.parts = split_dots(o.key);
  for (const std::string& p : o.parts) {
    if (p.empty()) {
      override_fail(o.key, "malformed key (expected a dotted path like " + example + ")");
    }
  }
  try {
    o.value = YAML::Load(o.text);
  } catch (const YAML::Exception& e) {
    override_fail(o.key, "cannot parse the value '" + printable(o.text, kEchoLimit) +
                             "' as YAML: " + reason(e));
  }
  return o;
}

}  // namespace disco::yaml
