// disco — errors a user can cause.
//
// InputError is thrown for anything wrong in what the user gave: a scene file,
// a settings file, a command-line option. Its message always names where the
// problem is: "FILE:LINE: key 'robots[1].mass': must be positive (got -1)".
#pragma once

#include <stdexcept>
#include <string>

namespace disco {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Builds the standard message "SOURCE:LINE: key 'KEY': WHAT". LINE is 1-based;
// a LINE of 0 is left out (e.g. for a key given on the command line).
inline std::string located_message(const std::string& source, int line,
                                   const std::string& key, const std::string& what) {
  std::string out = source;
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + key + "': ";
  out += what;
  return out;
}

}  // namespace disco
