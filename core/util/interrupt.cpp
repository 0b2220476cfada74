#include "core/util/interrupt.h"

#include <atomic>

namespace disco {
namespace {

std::atomic<int> requested{-1};  // -1: none; else the signal (0: requested without one)
static_assert(std::atomic<int>::is_always_lock_free, "signal handlers need a lock-free flag");

}  // namespace

void request_interrupt(int signal) {
  int none = -1;
  requested.compare_exchange_strong(none, signal);  // the first request's signal is kept
}
bool interrupt_requested() { return requested.load() >= 0; }
int interrupt_signal() { return requested.load() > 0 ? requested.load() : 0; }
void clear_interrupt() { requested.store(-1); }

}  // namespace disco
