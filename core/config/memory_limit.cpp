#include "core/config/memory_limit.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "core/util/errors.h"

namespace disco {
namespace {

constexpr double kAutoShare = 0.5;  // auto: this share of physical_memory_bytes()
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

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

MemoryLimit memory_limit(const Settings& s) {
  const std::string text = s.text(kMemoryLimitKey);  // a missing key fails here, named
  MemoryLimit m;
  m.where = s.where(kMemoryLimitKey);
  if (text == "auto") {
    const double machine = physical_memory_bytes();
    m.bytes = kAutoShare * machine;
    m.auto_meaning = "auto = half of the machine's " + memory_text(machine);
    return m;
  }
  double gib = NAN;
  try {
    gib = s.number(kMemoryLimitKey);
  } catch (const InputError&) {  // not a number: the message below says what is allowed
  }
  if (!(gib > 0))
    throw InputError(located_message(m.where, 0, kMemoryLimitKey,
                                     "must be 'auto' or a number of GiB > 0 (got '" +
                                         printable(text, kEchoLimit) + "')"));
  m.bytes = gib * kGiB;
  return m;
}

}  // namespace disco
