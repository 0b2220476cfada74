#include "core/util/clock.h"

#include <cmath>

#include "core/util/check.h"

namespace disco {
namespace {

WallTime wall_time;
std::atomic<TimeSource*> source{&wall_time};

}  // namespace

Clock::time_point Clock::now() { return time_point(source.load()->now()); }

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Clock::time_point after(Clock::time_point t0, double seconds) {
  return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

void clock_iteration() { source.load()->on_iteration(); }

Clock::duration WallTime::now() const {
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::steady_clock::now().time_since_epoch());
}

IterationTime::IterationTime(double seconds_per_iteration)
    : per_iteration_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(seconds_per_iteration))) {
  DISCO_CHECK(std::isfinite(seconds_per_iteration) && per_iteration_.count() > 0,
              "a simulated clock advances by a positive time per iteration");
}

Clock::duration IterationTime::now() const { return per_iteration_ * ticks_.load(); }

void IterationTime::on_iteration() { ticks_.fetch_add(1); }

ScopedTimeSource::ScopedTimeSource(TimeSource& s) : previous_(source.exchange(&s)) {}

ScopedTimeSource::~ScopedTimeSource() { source.store(previous_); }

Stopwatch::Stopwatch() { restart(); }

void Stopwatch::restart() { t0_ = std::chrono::steady_clock::now(); }

double Stopwatch::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

std::unique_ptr<TimeSource> make_time_source(const ClockSettings& settings) {
  if (settings.kind == ClockKind::kIterations)
    return std::make_unique<IterationTime>(settings.seconds_per_iteration);
  return std::make_unique<WallTime>();
}

std::time_t calendar_now() { return std::time(nullptr); }

}  // namespace disco
