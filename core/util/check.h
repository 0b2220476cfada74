// disco — programming-error checks.
//
// DISCO_CHECK guards invariants that only a bug in disco can break (sizes,
// indices, call order). It prints the failed condition with file and line and
// aborts: it is never used for anything a user can cause. User errors are
// disco::InputError (core/util/errors.h).
#pragma once

#include <cstdio>
#include <cstdlib>

#define DISCO_CHECK(cond, msg)                                                       \
  do {                                                                               \
    if (!(cond)) {                                                                   \
      std::fprintf(stderr, "disco: internal check failed at %s:%d: %s (%s)\n",      \
                   __FILE__, __LINE__, #cond, msg);                                  \
      std::abort();                                                                  \
    }                                                                                \
  } while (0)
