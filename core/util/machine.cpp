#include "core/util/machine.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace disco {
namespace {

// The number a cgroup file holds ("max" or a missing file: none, +inf).
double cgroup_limit(const char* path) {
  std::ifstream in(path);
  double v = 0;
  return in >> v && v > 0 ? v : INFINITY;
}

}  // namespace

double physical_memory_bytes() {
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(sysconf(_SC_PAGESIZE));
  return std::min({pages * page, cgroup_limit("/sys/fs/cgroup/memory.max"),
                   cgroup_limit("/sys/fs/cgroup/memory/memory.limit_in_bytes")});
}

}  // namespace disco
