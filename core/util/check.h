// disco — programming-error checks.
//
// DISCO_CHECK guards invariants that only a bug in disco can break (sizes,
// indices, call order). It never guards anything a user can cause: user errors
// are disco::InputError (core/util/errors.h). A failed check throws
// disco::InternalError, "internal check failed at FILE:LINE: CONDITION (WHY)", so that
// the code around it decides what a bug costs:
//   - never inside Ipopt: the TNLP adapter (core/ipopt/ipopt_solver.cpp) catches it in
//     the callback, stops the solve and rethrows it after Ipopt has returned;
//   - a start of the search records it as its `error` status and the search goes on
//     (search/run_start.h);
//   - `disco solve` reports "internal error: ..." and exits 1 (mpi/disco_main.cpp).
// No check may sit inside an OpenMP parallel region or a destructor (an exception
// there ends the process).
#pragma once

#include <stdexcept>
#include <string>

namespace disco {

class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// "internal check failed at FILE:LINE: CONDITION (WHY)".
inline std::string check_failure(const char* file, int line, const char* condition, const char* why) {
  return std::string("internal check failed at ") + file + ":" + std::to_string(line) + ": " +
         condition + " (" + why + ")";
}

}  // namespace disco

#define DISCO_CHECK(cond, msg)                                                         \
  do {                                                                                 \
    if (!(cond)) throw ::disco::InternalError(::disco::check_failure(__FILE__, __LINE__, #cond, msg)); \
  } while (0)
