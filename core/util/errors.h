// disco — errors a user can cause.
//
// InputError is thrown for anything wrong in what the user gave: a scene file,
// a settings file, a command-line option. Its message always names where the
// problem is: "FILE:LINE: key 'robots[1].mass': must be positive (got -1)".
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace disco {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The longest echo of user text (a value, a name) in a message, in bytes.
inline constexpr std::size_t kEchoLimit = 80;

// `text` fit for a one-line message: control bytes (below 0x20, and 0x7f) become escapes
// (\n, \t, \r, \xNN), and where that is longer than `max` bytes it is cut there (not inside
// a UTF-8 character), followed by "... (N bytes)" with N the length of `text`. Bytes from
// 0x80 up pass through.
inline std::string printable(const std::string& text, std::size_t max = std::string::npos) {
  std::string out;
  std::size_t k = 0;
  for (; k < text.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(text[k]);
    char piece[4] = {static_cast<char>(c), 0, 0, 0};
    std::size_t length = 1;
    if (c == '\n' || c == '\t' || c == '\r') {
      piece[0] = '\\';
      piece[1] = c == '\n' ? 'n' : c == '\t' ? 't' : 'r';
      length = 2;
    } else if (c < 0x20 || c == 0x7f) {
      const char* hex = "0123456789abcdef";
      piece[0] = '\\';
      piece[1] = 'x';
      piece[2] = hex[c >> 4];
      piece[3] = hex[c & 15];
      length = 4;
    }
    if (out.size() + length > max) break;
    out.append(piece, length);
  }
  if (k == text.size()) return out;
  // Back to the start of a UTF-8 character (its bytes, all >= 0x80, were copied one to one).
  auto byte = [&](std::size_t at) { return static_cast<unsigned char>(text[at]); };
  for (; k > 0 && (byte(k) & 0xC0) == 0x80 && byte(k - 1) >= 0x80; --k) out.pop_back();
  return out + "... (" + std::to_string(text.size()) + " bytes)";
}

// Builds the standard message "SOURCE:LINE: key 'KEY': WHAT". LINE is 1-based;
// a LINE of 0 is left out (e.g. for a key given on the command line). The message is one
// line: control bytes anywhere are escaped, and KEY is cut after 2 * kEchoLimit bytes
// (see printable).
inline std::string located_message(const std::string& source, int line,
                                   const std::string& key, const std::string& what) {
  std::string out = printable(source);
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + printable(key, 2 * kEchoLimit) + "': ";
  out += printable(what);
  return out;
}

}  // namespace disco
