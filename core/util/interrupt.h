// disco — a process-wide request to stop (SIGINT, SIGTERM; set by mpi/disco_main.cpp).
//
// request_interrupt() is async-signal-safe (it stores to a lock-free atomic), so a signal
// handler may call it. Once requested, every Ipopt solve stops at its next iteration
// (core/ipopt/ipopt_solver.cpp, as if its deadline had passed) and the objective reduction
// ends as if its time limit had passed (search/objective_reduction.cpp); the caller then
// sees interrupt_requested() and reports the start as interrupted (search/run_start.h).
// clear_interrupt() is for tests.
#pragma once

namespace disco {

void request_interrupt(int signal = 0);
bool interrupt_requested();
int interrupt_signal();  // the signal given to request_interrupt (0: none)
void clear_interrupt();

}  // namespace disco
