// disco — model.memory_limit (configs/disco.yaml): the memory a model may take, checked by
// core/model/model_size.h before anything is built.
//
//   auto    half of the machine's physical memory (or of its cgroup's memory limit, when
//           that is lower): room for the solve and for whatever else runs beside it
//   a number > 0   that many GiB (.inf: no limit)
// Anything else is an InputError naming the file, line and key.
#pragma once

#include "core/config/settings.h"
#include "core/model/model_size.h"

namespace disco {

MemoryLimit memory_limit(const Settings& settings);

// The machine's physical memory in bytes: sysconf's, or a cgroup's memory limit when lower.
double physical_memory_bytes();

}  // namespace disco
