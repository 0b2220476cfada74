// disco — the linear solver behind Ipopt's KKT solves, plugged in through Ipopt's own extension
// point.
//
// Every Ipopt solve of disco runs through optimize(): IpoptApplication::OptimizeNLP with an
// AlgorithmBuilder whose augmented-system solver is StdAugSystemSolver(TSymLinearSolver(S)),
// Ipopt's option linear_solver "custom": exactly what Ipopt builds for linear_solver mumps without
// scaling (our `ipopt:` settings), but with S a SparseSymLinearSolverInterface of disco's. S
// factorises with the solver kkt.solver names, counts the factorisations, and with
// KktOptions::perturbed_first answers Ipopt's degeneracy test (below).
//
// kkt.solver mumps: Ipopt's own MUMPS interface (MumpsSolverInterface: every `mumps_*` option of
// Ipopt applies), exactly as Ipopt calls it.
//
// kkt.solver ldlt: disco's LDLᵀ (core/linalg/sparse_ldlt.h; analysed once per solve, at its
// first factorisation, with the structure's fill-reducing ordering computed once per
// IpoptSolver and shared by both LDLᵀ solvers: KktOptions::orderings; the constraint block is
// Ipopt's rows of y_c and y_d, the last of the augmented system x, s, c, d). MUMPS's overhead
// per factorisation (11 ms on n ≈ 11 k for 5 MFlop; ~6 ms for a diagonal matrix) is what the
// LDLᵀ saves (scripts/results/bench_kkt.md).
//   - A factorisation whose inertia is not the one Ipopt asks for is answered "wrong inertia"
//     at once, or, with kkt.ldlt.certificate.iterations > 0 (not the default: core/README.md,
//     "Why the defaults"), only when that inertia is certified: the smallest |eigenvalue| of the regularised scaled matrix
//     M = S A S + R, estimated by kkt.ldlt.certificate.iterations steps of inverse iteration
//     with the factors (SparseLdlt::smallest_eigenvalue), is above kkt.ldlt.certificate.margin
//     × ‖R‖₂. By Weyl's inequality every eigenvalue of S A S is then within ‖R‖₂ of one of M
//     with the same sign, and S A S has A's inertia (Sylvester). Otherwise an eigenvalue of A
//     may lie within the regularisation of zero, its sign decided by R: the matrix falls back
//     (below; counted). On the bench_kkt corpus this is what made the inertia differ from
//     MUMPS's on the two matrices of B3_s1 (A's eigenvalue 1e-11 against δ = 1e-8).
//   - A matrix with a row without a nonzero (a constraint whose variables are all fixed, with
//     δc = 0, as in a polish solve) is answered "singular", as MUMPS finds it (a zero pivot):
//     Ipopt then regularises the constraint block. (Without that, the LDLᵀ's regularisation
//     solved such matrices, Ipopt never learned of the singularity, and polish solves took
//     hundreds of iterations instead of tens: paper B2 start 0.) A Jacobian that is
//     rank-deficient without an empty row is not caught so; a polish that has not converged
//     within kkt.polish_rescue.after iterations starts again with the pivoting LDLᵀ
//     (IpoptSolver::solve, NlpLimits::fixed_branch).
//   - One with the asked-for inertia is solved; the first solve with a new matrix refines to
//     kkt.ldlt.residual_tolerance, which vouches for the inertia too (sparse_ldlt.h). Later
//     solves with the same factors (Ipopt refining its own solution) return what the factors
//     give: Ipopt judges those residuals itself and asks for more quality when they are poor.
//   - A matrix whose factors have grown above kkt.ldlt.growth_limit (a tiny pivot kept, L
//     huge: without pivoting, what can make the inertia wrong; sparse_ldlt.h kUnstable), one
//     it cannot solve to the tolerance (or with a NaN or Inf in its values or pivots), and one
//     whose solves Ipopt wants more accurate (IncreaseQuality), falls back: factorised again
//     by the solver kkt.ldlt.fallback names, solved there until the next matrix. mumps: counted
//     in KktCounts::fallbacks (and reported in the solve summary, runs.jsonl and
//     solution.json); MUMPS's own IncreaseQuality (a larger pivot tolerance) then applies to
//     that matrix. pivoted: the pivoting LDLᵀ below, counted in KktCounts::to_pivoted, with
//     MUMPS behind it as below (the same certificate answers for the LDLᵀ's wrong inertias).
//
// kkt.solver pivoted: disco's multifrontal LDLᵀ with threshold 1×1/2×2 pivoting
// (core/linalg/pivoted_ldlt.h; analysed once per solve, each constraint row ordered behind a
// primal neighbour). No regularisation: its inertia is D's, exact, so a wrong one
// is answered "wrong inertia" at once, and a matrix with a singular remaining block (or an
// empty row) "singular". A right one is solved and refined to kkt.ldlt.residual_tolerance.
// When a solve does not reach it, or Ipopt asks for more quality, the pivot threshold u is
// raised (u ← √u, as Ipopt raises MUMPS's pivot tolerance; up to
// kkt.ldlt.pivoting.threshold_max; counted in KktCounts::threshold_raises; it stays raised for
// the rest of the solve) and the matrix factorised again; at threshold_max, it goes to MUMPS
// (counted in KktCounts::fallbacks).
//
// The degeneracy test:
//
// Each Ipopt iteration factorises its KKT matrix [W + Σ + δx I, Jᵀ; J, −δc I] and checks its
// inertia (n positive, m negative eigenvalues). Ipopt 3.11.9 first tries δx = 0 and, when the
// inertia is wrong, factorises again with δx = max(min_hessian_perturbation,
// perturb_dec_fact · δ_last), then larger (IpPDPerturbationHandler, IpPDFullSpaceSolver). In an
// MPCC the bilinear G·H terms make the matrix indefinite at most iterations (76–89 % on the
// paper's scenes), so most iterations pay for a factorisation that is thrown away: 2.17
// factorisations per iteration on paper A3's start 0.
//
// Ipopt skips the δx = 0 try only once it has classified the Hessian as *structurally
// degenerate*: when, in its first iterations, the unperturbed matrix is singular three times
// (its "degeneracy test"); 3.11.9 has no option to ask for that mode. With perturbed_first, S
// answers SYMSOLVER_SINGULAR, without factorising, to the factorisations Ipopt asks for with
// δx = 0 in its first three iterations:
//   - iteration 0: the first two (δx = δc = 0, then δc > 0, δx = 0: Ipopt's order of tests);
//   - iterations 1 and 2: the first (δx = 0).
// An iteration's factorisations end with the first that succeeds (MumpsSolverInterface then
// solves with it). The first try MUMPS sees in a solve is factorised all the same (its inertia
// check made to fail, the answer still "singular"): MUMPS analyses the structure at its first
// factorisation, and its column permutation (ICNTL(6) 7) reads the values, so the analysis sees
// the matrix Ipopt's own order of tries gives it, and a solve is the same bit for bit as with
// Ipopt's own MUMPS path (without that, two_robots_swap_avoid took 412 instead of 621 iterations
// and push_coin 801 instead of 739: other paths; which analysis serves better is for the start
// set to measure). A solve without warm-start duals first factorises once for its least-squares
// multipliers (Ipopt's constr_mult_init_max): that factorisation is passed through untouched.
// Ipopt then declares the Hessian degenerate (and the Jacobian not) and from then on starts
// every iteration's factorisation at δx = max(min_hessian_perturbation, δ_last / 3): one
// factorisation saved on every iteration whose matrix was indefinite, and a perturbation of at
// most a third of the last one on those that were not. What Ipopt computes is otherwise
// unchanged: every answer is still certified by disco (core/elastic/elastic_solver.h).
//
// A failed internal check (or bad_alloc) inside S is kept and rethrown by optimize() once Ipopt
// has returned (S answers Ipopt "fatal error"): no exception crosses into Ipopt.
//
// Ipopt's internal classes come from the headers of Debian's source package of the installed
// Ipopt (scripts/setup; core/README.md, "Ipopt's internals"); only kkt_solver.cpp includes them.
// S is made anew for every solve (the algorithm is rebuilt per solve), so a solve keeps no state
// across solves. Not thread-safe, like MUMPS itself: one Ipopt solve at a time per process.
#pragma once

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "core/ipopt/ipopt_solver.h"  // KktCounts

namespace disco {

// How S treats Ipopt's factorisations in one solve.
struct KktOptions {
  bool perturbed_first = false;  // answer the degeneracy test (above)
  bool cold = false;  // the solve starts without warm-start duals: its first factorisation is
                      // the least-squares multiplier estimate, passed through
  KktSolverKind solver = KktSolverKind::kMumps;  // which solver factorises (below)
  LdltSettings ldlt;
  KktDump dump;
  int* dumped = nullptr;  // matrices factorised so far by this IpoptSolver (kkt.dump.every)
  // The orderings of the structures analysed so far by this IpoptSolver (its solves and both
  // LDLᵀ solvers share them; permuted_symmetric.h); nullptr: the solve keeps its own.
  OrderingCache* orderings = nullptr;
};

// kkt.dump writes every `every`-th matrix Ipopt hands over for factorisation (the degeneracy
// test's answered ones excepted) to DIR/NNNNNN.kkt, NNNNNN its count in this IpoptSolver from 0.
// Binary, little-endian: the 8 bytes kKktFileMagic; int32 version (kKktFileVersion), n, nnz,
// dual_from (rows dual_from..n−1: the constraint block), check_inertia (0/1), the number of
// negative eigenvalues Ipopt wants; int32 ia[nnz], ja[nnz] (Ipopt's triplets: 1-based, one
// triangle, repeats to be summed); double values[nnz]; double rhs[n] (the first right-hand
// side). scripts/bench_kkt reads them.
inline constexpr char kKktFileMagic[9] = "DISCOKKT";
inline constexpr int kKktFileVersion = 1;

// Ipopt's option `linear_solver` while disco's solver is plugged in ("custom").
inline constexpr const char* kCustomLinearSolver = "custom";

// Solves `tnlp` with `app` (its options set; linear_solver kCustomLinearSolver) through S.
Ipopt::ApplicationReturnStatus optimize(Ipopt::IpoptApplication& app,
                                        const Ipopt::SmartPtr<Ipopt::TNLP>& tnlp,
                                        const KktOptions& options, KktCounts& counts);

}  // namespace disco
