// disco — what the machine offers: its physical memory (for model.memory_limit: auto).
#pragma once

namespace disco {

// The machine's physical memory in bytes: sysconf's, or its cgroup's memory limit (v2
// memory.max or v1 memory.limit_in_bytes) when that is lower.
double physical_memory_bytes();

}  // namespace disco
