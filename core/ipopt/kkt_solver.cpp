// disco — the linear solver behind Ipopt's KKT solves (core/ipopt/kkt_solver.h says what it
// does and why). The only file of disco that includes Ipopt's internal headers.
#include "core/ipopt/kkt_solver.h"

#include <IpAlgBuilder.hpp>
#include <IpIpoptData.hpp>
#include <IpIteratesVector.hpp>
#include <IpMumpsSolverInterface.hpp>
#include <IpStdAugSystemSolver.hpp>
#include <IpTNLPAdapter.hpp>
#include <IpTSymLinearSolver.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/linalg/pivoted_ldlt.h"
#include "core/linalg/sparse_ldlt.h"
#include "core/util/errors.h"

namespace disco {
namespace {

using Ipopt::ESymSolverStatus;
using Ipopt::Index;

// How many iterations get their unperturbed factorisations answered: Ipopt declares the Hessian
// degenerate after three (IpPDPerturbationHandler's degen_iters_max).
constexpr int kAnsweredIterations = 3;

// Writes one KKT matrix and its first right-hand side (the format: kkt_solver.h, KktDump).
void write_matrix(const std::string& path, Index dim, Index nonzeros, const Index* ia,
                  const Index* ja, const double* values, const double* rhs, int dual_from,
                  bool check_inertia, Index negative) {
  std::ofstream out(path, std::ios::binary);
  auto put = [&](const void* data, size_t bytes) {
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  };
  const int32_t header[6] = {kKktFileVersion, dim, nonzeros, dual_from, check_inertia ? 1 : 0,
                             negative};
  put(kKktFileMagic, 8);
  put(header, sizeof header);
  static_assert(sizeof(Index) == sizeof(int32_t), "Ipopt's Index is a 32-bit int");
  put(ia, sizeof(Index) * nonzeros);
  put(ja, sizeof(Index) * nonzeros);
  put(values, sizeof(double) * nonzeros);
  put(rhs, sizeof(double) * dim);
  out.close();
  if (!out) throw InputError("key 'kkt.dump.dir': cannot write " + path);
}

// S of kkt_solver.h: disco's LDLᵀ or Ipopt's MUMPS interface, with the degeneracy test answered.
class KktLinearSolver : public Ipopt::SparseSymLinearSolverInterface {
 public:
  KktLinearSolver(const KktOptions& options, KktCounts& counts, std::exception_ptr& error)
      : options_(options), counts_(counts), error_(error), estimate_pending_(options.cold) {}

  bool InitializeImpl(const Ipopt::OptionsList& options, const std::string& prefix) override {
    return mumps_->Initialize(Jnlst(), IpNLP(), IpData(), IpCq(), options, prefix);
  }
  ESymSolverStatus InitializeStructure(Index dim, Index nonzeros, const Index* ia,
                                       const Index* ja) override {
    dim_ = dim;
    nonzeros_ = nonzeros;
    if (own()) {
      values_.assign(nonzeros, 0.0);
      ldlt_analysed_ = pivoted_analysed_ = false;
    }
    return mumps_->InitializeStructure(dim, nonzeros, ia, ja);
  }
  double* GetValuesArrayPtr() override {
    return own() ? values_.data() : mumps_->GetValuesArrayPtr();
  }

  ESymSolverStatus MultiSolve(bool new_matrix, const Index* ia, const Index* ja, Index nrhs,
                              double* rhs, bool check_inertia, Index negative) override {
    try {
      return multi_solve(new_matrix, ia, ja, nrhs, rhs, check_inertia, negative);
    } catch (...) {  // never into Ipopt: optimize() rethrows it once Ipopt has returned
      error_ = std::current_exception();
      return Ipopt::SYMSOLVER_FATAL_ERROR;
    }
  }

  Index NumberOfNegEVals() const override {
    switch (holder_) {
      case Holder::kLdlt:
        return ldlt_.negative();
      case Holder::kPivoted:
        return pivoted_.negative();
      case Holder::kMumps:
        break;
    }
    return mumps_->NumberOfNegEVals();
  }
  // Ipopt asks for more accuracy than a solve gave: a matrix on disco's LDLᵀ falls back
  // (counted: to the pivoting LDLᵀ with kkt.ldlt.fallback pivoted, else to MUMPS); one on the
  // pivoting LDLᵀ is factorised again with a raised threshold (u ← √u, as Ipopt raises MUMPS's
  // pivot tolerance, up to kkt.ldlt.pivoting.threshold_max), then goes to MUMPS; one on MUMPS
  // raises MUMPS's pivot tolerance. The next call (a solve with the same matrix) does it.
  bool IncreaseQuality() override {
    switch (holder_) {
      case Holder::kMumps:
        return mumps_->IncreaseQuality();
      case Holder::kLdlt:
        pending_ = Pending::kFallBack;
        return true;
      case Holder::kPivoted:
        pending_ = raise_threshold() ? Pending::kRefactor : Pending::kMumps;
        return true;
    }
    return false;
  }
  bool ProvidesInertia() const override { return true; }
  EMatrixFormat MatrixFormat() const override { return mumps_->MatrixFormat(); }
  bool ProvidesDegeneracyDetection() const override {
    return mumps_->ProvidesDegeneracyDetection();
  }
  ESymSolverStatus DetermineDependentRows(const Index* ia, const Index* ja,
                                          std::list<Index>& rows) override {
    return mumps_->DetermineDependentRows(ia, ja, rows);
  }

 private:
  bool pivoted() const { return options_.solver == KktSolverKind::kPivoted; }
  bool own() const { return options_.solver != KktSolverKind::kMumps; }  // one of disco's

  ESymSolverStatus multi_solve(bool new_matrix, const Index* ia, const Index* ja, Index nrhs,
                               double* rhs, bool check_inertia, Index negative) {
    if (!new_matrix) {
      const Pending pending = pending_;
      pending_ = Pending::kNone;
      switch (pending) {
        case Pending::kMumps:
          return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
        case Pending::kFallBack:
          return fall_back(ia, ja, nrhs, rhs, check_inertia, negative);
        case Pending::kRefactor:  // the pivoting LDLᵀ with a raised threshold
          ++counts_.factorisations;
          return factor_pivoted(ia, ja, nrhs, rhs, check_inertia, negative);
        case Pending::kNone:
          break;
      }
      if (holder_ == Holder::kMumps)
        return mumps_->MultiSolve(false, ia, ja, nrhs, rhs, check_inertia, negative);
      // Another right-hand side for factors Ipopt has accepted (it refines its own solution):
      // the best the factors give, whatever its error. Ipopt aborts the solve on any answer but
      // success here; it judges the residual itself and, when it is too large, asks for more
      // quality (IncreaseQuality: the fallback next) or perturbs the matrix.
      for (Index j = 0; j < nrhs; ++j) solve_own(rhs + static_cast<size_t>(j) * dim_);
      return Ipopt::SYMSOLVER_SUCCESS;
    }
    if (estimate_pending_) {  // the least-squares multiplier estimate: not a test
      estimate_pending_ = false;
      analysed_ = true;
      ++counts_.factorisations;
      return factorise(ia, ja, nrhs, rhs, check_inertia, negative);
    }
    if (answer_singular()) {
      ++tries_;
      ++counts_.answered;
      if (!analysed_ && !own()) {
        // MUMPS analyses the structure at its first factorisation, and its column permutation
        // (ICNTL(6) 7) reads the values: it must see this matrix, the one Ipopt's own order of
        // tries first gives it. An inertia no matrix has (-1 negative eigenvalues) makes
        // MumpsSolverInterface factorise and stop before solving; the answer stays "singular".
        analysed_ = true;
        ++counts_.factorisations;
        mumps_->MultiSolve(true, ia, ja, nrhs, rhs, true, -1);
      }
      return Ipopt::SYMSOLVER_SINGULAR;  // Ipopt then perturbs
    }
    analysed_ = true;
    ++tries_;
    ++counts_.factorisations;
    const ESymSolverStatus status = factorise(ia, ja, nrhs, rhs, check_inertia, negative);
    if (status == Ipopt::SYMSOLVER_SUCCESS) {  // the iteration's factorisation: the next begins
      ++iteration_;
      tries_ = 0;
    }
    return status;
  }

  // A new matrix: factorised by the configured solver, solved with it.
  ESymSolverStatus factorise(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                             bool check_inertia, Index negative) {
    pending_ = Pending::kNone;
    if (options_.dump.every > 0 && (*options_.dumped)++ % options_.dump.every == 0)
      dump(ia, ja, rhs, check_inertia, negative);
    if (!own()) return mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
    if (pivoted()) return factor_pivoted(ia, ja, nrhs, rhs, check_inertia, negative);
    if (!ldlt_analysed_) {
      ldlt_.analyse(dim_, nonzeros_, ia, ja, 1, dual_from(), ordering(ia, ja));
      if (ldlt_.ordering().ordering == Ordering::kNestedDissection) ++counts_.nested_dissection;
      ldlt_analysed_ = true;
    }
    holder_ = Holder::kLdlt;
    switch (ldlt_.factor(values_.data(), options_.ldlt)) {
      case SparseLdlt::Factorised::kDone:
        break;
      case SparseLdlt::Factorised::kEmptyRow:
        // A row without a nonzero (a constraint whose variables are all fixed, with δc = 0):
        // the matrix is singular, as MUMPS would find (a zero pivot, its INFO(1) −10); Ipopt
        // then regularises the constraint block (δc > 0).
        return Ipopt::SYMSOLVER_SINGULAR;
      case SparseLdlt::Factorised::kNotFinite:
      case SparseLdlt::Factorised::kUnstable:  // factors too inaccurate to vouch for anything
        return fall_back(ia, ja, nrhs, rhs, check_inertia, negative);
    }
    // A wrong inertia is answered only when certified (below); one that may be the
    // regularisation's goes to MUMPS. A right one is taken only once a solve has reached the
    // tolerance, which vouches for it.
    if (check_inertia && ldlt_.negative() != negative) {
      if (!ldlt_.inertia_certified()) return fall_back(ia, ja, nrhs, rhs, check_inertia, negative);
      return Ipopt::SYMSOLVER_WRONG_INERTIA;
    }
    return solve_ldlt(ia, ja, nrhs, rhs, check_inertia, negative);
  }

  // The current matrix by the pivoting LDLᵀ with the current threshold: its inertia is exact
  // (D's 1×1 and 2×2 blocks), a singular one is answered so (Ipopt then perturbs).
  ESymSolverStatus factor_pivoted(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                                  bool check_inertia, Index negative) {
    if (!pivoted_analysed_) {
      pivoted_.analyse(dim_, nonzeros_, ia, ja, 1, dual_from(), ordering(ia, ja));
      if (pivoted_.ordering().ordering == Ordering::kNestedDissection)
        ++counts_.nested_dissection;
      pivoted_analysed_ = true;
      threshold_ = options_.ldlt.pivot_threshold;
    }
    holder_ = Holder::kPivoted;
    switch (pivoted_.factor(values_.data(), options_.ldlt, threshold_)) {
      case PivotedLdlt::Factorised::kDone:
        break;
      case PivotedLdlt::Factorised::kEmptyRow:
      case PivotedLdlt::Factorised::kSingular:
        return Ipopt::SYMSOLVER_SINGULAR;
      case PivotedLdlt::Factorised::kNotFinite:
        return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
    }
    if (check_inertia && pivoted_.negative() != negative) return Ipopt::SYMSOLVER_WRONG_INERTIA;
    return solve_ldlt(ia, ja, nrhs, rhs, check_inertia, negative);
  }

  // Solves with the factors of whichever of disco's solvers holds the current matrix (refined);
  // returns the backward error reached.
  double solve_own(double* b) {
    return holder_ == Holder::kPivoted ? pivoted_.solve(b) : ldlt_.solve(b);
  }

  // u ← √u up to kkt.ldlt.pivoting.threshold_max (counted); false when already there.
  bool raise_threshold() {
    if (threshold_ >= options_.ldlt.pivot_threshold_max) return false;
    threshold_ = std::min(options_.ldlt.pivot_threshold_max, std::sqrt(threshold_));
    ++counts_.threshold_raises;
    return true;
  }

  // Solves with disco's factors; any right-hand side they cannot solve to the tolerance sends
  // the matrix on (the LDLᵀ's: fall_back(); the pivoting LDLᵀ first factorises it again with a
  // raised threshold, while it can, then sends it to MUMPS).
  ESymSolverStatus solve_ldlt(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                              bool check_inertia, Index negative) {
    original_.assign(rhs, rhs + static_cast<size_t>(dim_) * nrhs);
    for (Index j = 0; j < nrhs; ++j) {
      double* b = rhs + static_cast<size_t>(j) * dim_;
      if (solve_own(b) > options_.ldlt.residual_tolerance) {
        std::copy(original_.begin(), original_.end(), rhs);
        if (holder_ != Holder::kPivoted) return fall_back(ia, ja, nrhs, rhs, check_inertia, negative);
        if (raise_threshold()) {
          ++counts_.factorisations;
          return factor_pivoted(ia, ja, nrhs, rhs, check_inertia, negative);
        }
        return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
      }
    }
    return Ipopt::SYMSOLVER_SUCCESS;
  }

  // A matrix the LDLᵀ cannot serve: to the pivoting LDLᵀ (kkt.ldlt.fallback pivoted; counted
  // in KktCounts::to_pivoted), else to MUMPS.
  ESymSolverStatus fall_back(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                             bool check_inertia, Index negative) {
    if (!options_.ldlt.fallback_pivoted) return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
    ++counts_.to_pivoted;
    ++counts_.factorisations;
    return factor_pivoted(ia, ja, nrhs, rhs, check_inertia, negative);
  }

  // The current matrix to MUMPS (kkt.solver ldlt or pivoted: counted as a fallback).
  ESymSolverStatus on_mumps(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                            bool check_inertia, Index negative) {
    holder_ = Holder::kMumps;
    ++counts_.fallbacks;
    ++counts_.factorisations;
    std::copy(values_.begin(), values_.end(), mumps_->GetValuesArrayPtr());
    return mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
  }

  // The fill-reducing ordering of the current structure (kkt.ldlt.ordering), computed once for
  // the IpoptSolver's solves and both solvers.
  const FillReducingOrder& ordering(const Index* ia, const Index* ja) {
    OrderingCache& cache = options_.orderings ? *options_.orderings : own_orderings_;
    const int computed = cache.computed();
    const FillReducingOrder& chosen =
        cache.order(dim_, nonzeros_, ia, ja, 1, options_.ldlt.ordering);
    counts_.orderings += cache.computed() - computed;
    return chosen;
  }

  // The first row of the constraint block: Ipopt's augmented system is ordered x, s, c, d
  // (IpStdAugSystemSolver), the last two the constraint multipliers.
  int dual_from() const {
    const auto& it = *IpData().curr();
    return dim_ - it.y_c()->Dim() - it.y_d()->Dim();
  }

  void dump(const Index* ia, const Index* ja, const double* rhs, bool check_inertia,
            Index negative) {
    std::filesystem::create_directories(options_.dump.dir);
    char name[32];
    std::snprintf(name, sizeof name, "%06d.kkt", *options_.dumped - 1);
    write_matrix((std::filesystem::path(options_.dump.dir) / name).string(), dim_, nonzeros_, ia,
                 ja, GetValuesArrayPtr(), rhs, dual_from(), check_inertia, negative);
  }

  // Whether this factorisation is one Ipopt makes with δx = 0 for its degeneracy test.
  bool answer_singular() const {
    if (!options_.perturbed_first || iteration_ >= kAnsweredIterations) return false;
    return tries_ < (iteration_ == 0 ? 2 : 1);
  }

  Ipopt::SmartPtr<Ipopt::MumpsSolverInterface> mumps_ = new Ipopt::MumpsSolverInterface();
  const KktOptions options_;
  KktCounts& counts_;
  std::exception_ptr& error_;
  bool estimate_pending_;
  bool analysed_ = false;  // MUMPS has seen a matrix of this solve
  int iteration_ = 0;  // iterations whose factorisation succeeded
  int tries_ = 0;      // factorisations asked for in the current iteration
  Index dim_ = 0, nonzeros_ = 0;
  // kkt.solver ldlt
  SparseLdlt ldlt_;
  bool ldlt_analysed_ = false;
  // Which solver holds the current matrix's factors.
  enum class Holder { kLdlt, kPivoted, kMumps };
  Holder holder_ = Holder::kMumps;
  // What IncreaseQuality asked to be done with the current matrix at the next call.
  enum class Pending { kNone, kFallBack, kRefactor, kMumps };
  Pending pending_ = Pending::kNone;
  // kkt.solver pivoted
  PivotedLdlt pivoted_;
  bool pivoted_analysed_ = false;
  double threshold_ = 0.0;  // its pivot threshold in this solve (raised by IncreaseQuality)
  OrderingCache own_orderings_{1};  // without KktOptions::orderings
  std::vector<double> values_, original_;
};

}  // namespace

Ipopt::ApplicationReturnStatus optimize(Ipopt::IpoptApplication& app,
                                        const Ipopt::SmartPtr<Ipopt::TNLP>& tnlp,
                                        const KktOptions& options, KktCounts& counts) {
  std::exception_ptr error;
  Ipopt::SmartPtr<Ipopt::SparseSymLinearSolverInterface> solver =
      new KktLinearSolver(options, counts, error);
  Ipopt::SmartPtr<Ipopt::SymLinearSolver> scaled = new Ipopt::TSymLinearSolver(solver, nullptr);
  Ipopt::SmartPtr<Ipopt::AugSystemSolver> augmented = new Ipopt::StdAugSystemSolver(*scaled);
  Ipopt::SmartPtr<Ipopt::AlgorithmBuilder> builder = new Ipopt::AlgorithmBuilder(augmented);
  Ipopt::SmartPtr<Ipopt::NLP> nlp =
      new Ipopt::TNLPAdapter(Ipopt::GetRawPtr(tnlp), Ipopt::ConstPtr(app.Jnlst()));
  const Ipopt::ApplicationReturnStatus status = app.OptimizeNLP(nlp, builder);
  if (error) std::rethrow_exception(error);
  return status;
}

}  // namespace disco
