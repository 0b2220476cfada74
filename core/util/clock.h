// disco — the one clock disco reads time from.
//
// Every time disco acts on (a solve's deadline, a start's budget, a search's --time-limit, the
// salvage's pace, the seconds in runs.jsonl and the solve log, the progress line) is read
// through Clock::now(). Clock is a std::chrono clock (steady) whose readings come from the
// process's TimeSource:
//   - WallTime (the default): the machine's steady clock.
//   - IterationTime: a simulated clock that advances by a fixed amount at every Ipopt
//     iteration report and at nothing else, so a time limit is an iteration budget and where
//     it cuts is the same on any machine, at any load (`clock.kind: iterations` in
//     configs/disco.yaml; the tests that assert where a limit falls).
// Ipopt reports each iteration (core/ipopt/ipopt_solver.cpp, the intermediate callback:
// iteration 0, the starting point, then one per iteration) through clock_iteration() before it
// checks the solve's deadline. Ipopt's own max_cpu_time is refused (core/ipopt/ipopt_solver.cpp):
// every limit is on this clock.
//
// The source is process-wide: install another with ScopedTimeSource (tests, `disco solve`
// and `disco search` per clock_settings). Reading and reporting are thread-safe (rank 0's
// coordinator thread reads while its worker reports); install a source while no solve runs.
//
// Two readings stay on the machine's own clocks whatever the source: a Stopwatch (benchmarks
// that measure the machine itself) and calendar_now() (dates in manifests).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <memory>

namespace disco {

struct Clock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<Clock>;
  static constexpr bool is_steady = true;
  static time_point now();  // the installed source's reading
};

// A point on disco's clock by which something must end.
using Deadline = Clock::time_point;

// Seconds on disco's clock from t0 until now.
double seconds_since(Clock::time_point t0);
// The point `seconds` after t0 (seconds may be fractional).
Clock::time_point after(Clock::time_point t0, double seconds);

// Reports one Ipopt iteration to the installed source (an IterationTime advances).
void clock_iteration();

// Where Clock's readings come from.
class TimeSource {
 public:
  virtual ~TimeSource() = default;
  // Time since the source's own epoch; never decreasing.
  virtual Clock::duration now() const = 0;
  // One Ipopt iteration was reported (clock_iteration).
  virtual void on_iteration() {}
};

// The machine's steady clock.
class WallTime final : public TimeSource {
 public:
  Clock::duration now() const override;
};

// Simulated time: `seconds_per_iteration` (> 0) per Ipopt iteration report, nothing else.
class IterationTime : public TimeSource {
 public:
  explicit IterationTime(double seconds_per_iteration);
  Clock::duration now() const override;
  void on_iteration() override;
  std::int64_t iterations() const { return ticks_.load(); }  // reports so far

 private:
  Clock::duration per_iteration_;
  std::atomic<std::int64_t> ticks_{0};
};

// Which source a run uses: the `clock:` section of configs/disco.yaml (clock_settings,
// core/config/solver_settings.h).
enum class ClockKind {
  kWall,        // WallTime
  kIterations,  // IterationTime(seconds_per_iteration)
};
struct ClockSettings {
  ClockKind kind = ClockKind::kWall;
  double seconds_per_iteration = 0.0;  // kIterations: > 0
};
std::unique_ptr<TimeSource> make_time_source(const ClockSettings& settings);

// Makes `source` the process's time source until the scope ends, then puts the previous one
// back. `source` must outlive the scope.
class ScopedTimeSource {
 public:
  explicit ScopedTimeSource(TimeSource& source);
  ~ScopedTimeSource();
  ScopedTimeSource(const ScopedTimeSource&) = delete;
  ScopedTimeSource& operator=(const ScopedTimeSource&) = delete;

 private:
  TimeSource* previous_;
};

// Seconds of the machine's steady clock since it was made (or restarted), whatever the
// installed source: for measuring the machine itself (tests/bench_eval.cpp).
class Stopwatch {
 public:
  Stopwatch();
  void restart();
  double seconds() const;

 private:
  std::chrono::steady_clock::time_point t0_;
};

// The calendar date and time now (std::time), whatever the installed source.
std::time_t calendar_now();

}  // namespace disco
