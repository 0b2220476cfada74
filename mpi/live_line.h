// disco — the live progress line of `disco search` on a terminal.
//
// LiveLineSink is the log sink of the disco executable. It passes every log
// message to the stderr sink it wraps; when a status line is set (only on a
// terminal: see run_search's on_status), it keeps that line at the bottom of
// the terminal, cut to the terminal's width: before a message it erases the
// line ("\r" and "erase to end of line"), and the next status (a second later
// at most) draws it below the message. Without a status it writes exactly what
// the wrapped sink writes, so logs piped to a file hold no control characters.
#pragma once

#include <spdlog/sinks/sink.h>

#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

namespace disco {

class LiveLineSink : public spdlog::sinks::sink {
 public:
  explicit LiveLineSink(std::shared_ptr<spdlog::sinks::sink> inner, std::FILE* terminal = stderr);

  void log(const spdlog::details::log_msg& msg) override;
  void flush() override;
  void set_pattern(const std::string& pattern) override;
  void set_formatter(std::unique_ptr<spdlog::formatter> formatter) override;

  // Shows `text` as the status line (replacing the last one); "" removes it.
  void set_status(const std::string& text);

 private:
  void erase_locked();
  void draw_locked();

  std::mutex mutex_;
  std::shared_ptr<spdlog::sinks::sink> inner_;
  std::FILE* terminal_;
  std::string status_;
  bool shown_ = false;
};

// Whether `f` is a terminal (a live line makes sense there only).
bool is_terminal(std::FILE* f);

}  // namespace disco
