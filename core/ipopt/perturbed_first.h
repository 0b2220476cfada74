// disco — Ipopt's KKT factorisations: start every iteration from a Hessian perturbation.
//
// Each Ipopt iteration factorises its KKT matrix [W + Σ + δx I, Jᵀ; J, −δc I] and checks its
// inertia (n positive, m negative eigenvalues). Ipopt 3.11.9 first tries δx = 0 and, when the
// inertia is wrong, factorises again with δx = max(min_hessian_perturbation,
// perturb_dec_fact · δ_last), then larger (IpPDPerturbationHandler, IpPDFullSpaceSolver). In an
// MPCC the bilinear G·H terms make the matrix indefinite at most iterations (76–89 % on the
// paper's scenes, scripts/results/bench_starts.md), so most iterations pay for a
// factorisation that is thrown away: 2.17 factorisations per iteration on paper A3's start 0.
//
// Ipopt skips the δx = 0 try only once it has classified the Hessian as *structurally
// degenerate*: when, in its first iterations, the unperturbed matrix is singular three times
// (its "degeneracy test"). Ipopt 3.11.9 has no option to ask for that mode. With
// `kkt.perturbed_first: true` (configs/disco.yaml) disco gets it by answering that test:
// during a solve, MUMPS's C entry point `dmumps_c` (which Ipopt calls) is disco's
// (core/ipopt/perturbed_first.cpp; it calls MUMPS's own through dlsym(RTLD_NEXT)), and it
// reports "singular" (INFO(1) = −10), without factorising, to the factorisations Ipopt makes
// with δx = 0 in the first three iterations of each linear solver instance:
//   - iteration 0: the first two (δx = δc = 0, then δc > 0, δx = 0: Ipopt's order of tests);
//   - iterations 1 and 2: the first (δx = 0).
// An iteration is the run of factorisations up to the next back-solve (MUMPS job 3). A solve
// without warm-start duals first factorises once for its least-squares multipliers
// (Ipopt's constr_mult_init_max): that factorisation is passed through untouched.
// Ipopt then declares the Hessian degenerate (and the Jacobian not) and from then on starts
// every iteration's factorisation at δx = max(min_hessian_perturbation, δ_last / 3): one
// factorisation saved on every iteration whose matrix was indefinite, and a perturbation of
// at most a third of the last one on those that were not. What Ipopt computes is otherwise
// unchanged: every answer is still certified by disco (core/elastic/elastic_solver.h).
//
// The interposition holds when disco's object comes before libdmumps_seq in the link, as in
// every disco executable (its dmumps_c is then the one the dynamic linker binds Ipopt's call
// to); PerturbedFirstScope::active() says whether it took effect (a test checks it).
//
// Not thread-safe, like MUMPS itself: one Ipopt solve at a time per process.
#pragma once

#include <cstdint>

namespace disco {

// What the interposer did since the process started (for tests and logs).
struct PerturbedFirstCounts {
  std::int64_t factorisations = 0;  // MUMPS numerical factorisations run (job 2)
  std::int64_t answered = 0;        // factorisations answered "singular" without running
};
PerturbedFirstCounts perturbed_first_counts();

// Arms the interposer for one Ipopt solve (RAII): while it lives, new MUMPS instances get the
// treatment above. `cold` says the solve has no warm-start duals (Ipopt's first factorisation
// is then its least-squares multiplier estimate). With `enabled` false it does nothing.
class PerturbedFirstScope {
 public:
  PerturbedFirstScope(bool enabled, bool cold);
  ~PerturbedFirstScope();
  PerturbedFirstScope(const PerturbedFirstScope&) = delete;
  PerturbedFirstScope& operator=(const PerturbedFirstScope&) = delete;
  // Whether Ipopt's MUMPS calls reached disco's dmumps_c during this scope (false when the
  // link order let MUMPS's own definition win, or before Ipopt factorised anything).
  bool active() const;

 private:
  bool enabled_;
  std::int64_t calls_at_start_;
};

}  // namespace disco
