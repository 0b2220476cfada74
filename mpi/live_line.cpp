#include "mpi/live_line.h"

#include <sys/ioctl.h>
#include <unistd.h>

namespace disco {
namespace {

constexpr const char* kErase = "\r\x1b[K";  // to column 0, erase to the end of the line

// The terminal's width in columns (80 if it does not say).
std::size_t columns(std::FILE* f) {
  winsize w{};
  if (ioctl(fileno(f), TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

}  // namespace

bool is_terminal(std::FILE* f) { return isatty(fileno(f)) == 1; }

LiveLineSink::LiveLineSink(std::shared_ptr<spdlog::sinks::sink> inner, std::FILE* terminal)
    : inner_(std::move(inner)), terminal_(terminal) {}

void LiveLineSink::log(const spdlog::details::log_msg& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  erase_locked();
  inner_->log(msg);
  inner_->flush();
  // The line is drawn again by the next set_status (within a second): redrawn
  // here it would show the state from before the message.
}

void LiveLineSink::flush() {
  std::lock_guard<std::mutex> lock(mutex_);
  inner_->flush();
  std::fflush(terminal_);
}

void LiveLineSink::set_pattern(const std::string& pattern) {
  std::lock_guard<std::mutex> lock(mutex_);
  inner_->set_pattern(pattern);
}

void LiveLineSink::set_formatter(std::unique_ptr<spdlog::formatter> formatter) {
  std::lock_guard<std::mutex> lock(mutex_);
  inner_->set_formatter(std::move(formatter));
}

void LiveLineSink::set_status(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  erase_locked();
  status_ = text;
  draw_locked();
}

void LiveLineSink::erase_locked() {
  if (!shown_) return;
  std::fputs(kErase, terminal_);
  shown_ = false;
}

void LiveLineSink::draw_locked() {
  if (status_.empty()) return;
  // One column short of the width: a full line would wrap on some terminals.
  const std::size_t width = columns(terminal_) - 1;
  std::fputs(status_.size() > width ? status_.substr(0, width).c_str() : status_.c_str(),
             terminal_);
  std::fflush(terminal_);
  shown_ = true;
}

}  // namespace disco
