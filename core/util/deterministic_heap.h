// disco — fresh heap memory with the same bytes in every process.
//
// Ipopt 3.11.9 reads uninitialised heap memory in one case: when it cannot compute the step of
// a solve's first iteration, it starts its restoration phase without the line search that sets
// the filter's reference point, and adds a filter entry from that never-set point
// (FilterLSAcceptor::AugmentFilter; core/README.md, "A nondeterminism inside Ipopt 3.11.9").
// What the restoration then did depended on what the memory held before: on earlier
// allocations, and so on the command's paths and environment (configs/stress/spin_short.yaml
// start 3 took 111 or 131 Ipopt iterations by how it was started).
//
// A program that calls make_heap_deterministic() links this unit's replacements of the global
// operator new, which returns zero-filled memory (calloc; the array and nothrow forms call it),
// and the matching operator delete (free). Ipopt allocates through them, so the never-set reference
// point reads as zero in every process: the answer is reproducible, though not the one a
// corrected Ipopt would give. glibc's own fill (mallopt M_PERTURB) does not do it: memory
// recycled through its thread cache is returned unfilled (measured: MALLOC_PERTURB_ 1 and 64
// still gave 111 and 131). Cost: on the 18-start set the same iterations and T_f, wall 1.007
// (scripts/results/bench_starts.md, section "zero-filled operator new ..."); tested by CTest
// cli.deterministic_heap. disco's command line calls it first in main(). Not under
// AddressSanitizer, which replaces operator new itself and fills fresh memory with a fixed
// byte; valgrind replaces it too (and still reports that read).
#pragma once

namespace disco {

// Links the zero-filling operator new (above); true when it is in effect (false under ASan).
bool make_heap_deterministic();

}  // namespace disco
