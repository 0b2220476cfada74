// disco — Ipopt's KKT factorisations: start every iteration from a Hessian perturbation
// (core/ipopt/perturbed_first.h says why and what it answers).
#include "core/ipopt/perturbed_first.h"

#include <dlfcn.h>
#include <dmumps_c.h>

#include <map>

#include "core/util/check.h"

namespace disco {
namespace {

// How many iterations of a MUMPS instance get their unperturbed factorisations answered:
// Ipopt declares the Hessian degenerate after three (IpPDPerturbationHandler's degen_iters_max).
constexpr int kAnsweredIterations = 3;

// One MUMPS instance's progress through Ipopt's degeneracy test.
struct Instance {
  bool pass_first = false;  // the instance's first factorisation is the least-squares estimate
  int iteration = 0;        // iterations finished (a back-solve ends one)
  int factorisations = 0;   // factorisations in the current iteration
  bool any_factorisation = false;
  bool in_estimate = false;  // between the least-squares factorisation and its back-solve
};

struct State {
  bool armed = false;
  bool cold = false;
  std::int64_t calls = 0;  // calls of disco's dmumps_c
  PerturbedFirstCounts counts;
  std::map<const DMUMPS_STRUC_C*, Instance> instances;  // created while armed
};
State& state() {
  static State s;
  return s;
}

using DmumpsC = void (*)(DMUMPS_STRUC_C*);
DmumpsC mumps_dmumps_c() {
  static const DmumpsC f = reinterpret_cast<DmumpsC>(dlsym(RTLD_NEXT, "dmumps_c"));
  DISCO_CHECK(f != nullptr, "MUMPS's dmumps_c not found after disco's (link order)");
  return f;
}

// Whether Ipopt made this factorisation with no Hessian perturbation as part of its degeneracy
// test, in the first iterations (perturbed_first.h lists which).
bool answer_singular(const Instance& in) {
  if (in.iteration >= kAnsweredIterations) return false;
  const int answered_here = in.iteration == 0 ? 2 : 1;
  return in.factorisations < answered_here;
}

}  // namespace

PerturbedFirstCounts perturbed_first_counts() { return state().counts; }

PerturbedFirstScope::PerturbedFirstScope(bool enabled, bool cold)
    : enabled_(enabled), calls_at_start_(state().calls) {
  if (!enabled_) return;
  State& s = state();
  DISCO_CHECK(!s.armed, "one Ipopt solve at a time per process");
  s.armed = true;
  s.cold = cold;
}

PerturbedFirstScope::~PerturbedFirstScope() {
  if (!enabled_) return;
  State& s = state();
  s.armed = false;
  s.instances.clear();
}

bool PerturbedFirstScope::active() const { return state().calls > calls_at_start_; }

}  // namespace disco

// MUMPS's C entry point, as Ipopt calls it (perturbed_first.h). Outside an armed solve, and
// for every call but the answered factorisations, it is MUMPS's own.
extern "C" void dmumps_c(DMUMPS_STRUC_C* mumps) {
  using disco::state;
  auto& s = state();
  ++s.calls;
  auto it = s.instances.find(mumps);
  if (mumps->job == -1 && s.armed) {
    it = s.instances.insert_or_assign(mumps, disco::Instance{}).first;
    it->second.pass_first = s.cold;
  }
  if (it != s.instances.end()) {
    disco::Instance& in = it->second;
    if (mumps->job == 2 && in.pass_first && !in.any_factorisation) {
      in.any_factorisation = true;  // the least-squares estimate: MUMPS's own
      in.in_estimate = true;
    } else if (mumps->job == 2) {
      const bool answer = disco::answer_singular(in);
      in.any_factorisation = true;
      ++in.factorisations;
      if (answer) {
        ++s.counts.answered;
        mumps->info[0] = -10;  // INFO(1): numerically singular; Ipopt then perturbs
        mumps->infog[0] = -10;
        return;
      }
    } else if (mumps->job == 3 && in.in_estimate) {
      in.in_estimate = false;
    } else if (mumps->job == 3 && in.factorisations > 0) {
      ++in.iteration;
      in.factorisations = 0;
    } else if (mumps->job == -2) {
      s.instances.erase(it);
    }
  }
  if (mumps->job == 2) ++s.counts.factorisations;
  disco::mumps_dmumps_c()(mumps);
}
