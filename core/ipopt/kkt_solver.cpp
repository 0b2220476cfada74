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

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <vector>

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
    if (ldlt()) {
      values_.assign(nonzeros, 0.0);
      ldlt_analysed_ = false;
    }
    return mumps_->InitializeStructure(dim, nonzeros, ia, ja);
  }
  double* GetValuesArrayPtr() override {
    return ldlt() ? values_.data() : mumps_->GetValuesArrayPtr();
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
    return on_ldlt_ ? ldlt_.negative() : mumps_->NumberOfNegEVals();
  }
  // Ipopt asks for more accuracy than a solve gave: a matrix on disco's LDLᵀ goes to MUMPS
  // (counted), one on MUMPS raises MUMPS's pivot tolerance.
  bool IncreaseQuality() override {
    if (!on_ldlt_) return mumps_->IncreaseQuality();
    to_mumps_ = true;
    return true;
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
  bool ldlt() const { return options_.solver == KktSolverKind::kLdlt; }

  ESymSolverStatus multi_solve(bool new_matrix, const Index* ia, const Index* ja, Index nrhs,
                               double* rhs, bool check_inertia, Index negative) {
    if (!new_matrix) {
      if (to_mumps_) return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
      if (!on_ldlt_) return mumps_->MultiSolve(false, ia, ja, nrhs, rhs, check_inertia, negative);
      // Another right-hand side for factors Ipopt has accepted (it refines its own solution):
      // the best the factors give, whatever its error. Ipopt aborts the solve on any answer but
      // success here; it judges the residual itself and, when it is too large, asks for more
      // quality (IncreaseQuality: MUMPS next) or perturbs the matrix.
      for (Index j = 0; j < nrhs; ++j) ldlt_.solve(rhs + static_cast<size_t>(j) * dim_);
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
      if (!analysed_ && !ldlt()) {
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
    to_mumps_ = false;
    if (options_.dump.every > 0 && (*options_.dumped)++ % options_.dump.every == 0)
      dump(ia, ja, rhs, check_inertia, negative);
    if (!ldlt()) return mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
    if (!ldlt_analysed_) {
      ldlt_.analyse(dim_, nonzeros_, ia, ja, 1, dual_from());
      ldlt_analysed_ = true;
    }
    on_ldlt_ = true;
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
        return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
    }
    // A wrong inertia is answered only when certified (below); one that may be the
    // regularisation's goes to MUMPS. A right one is taken only once a solve has reached the
    // tolerance, which vouches for it.
    if (check_inertia && ldlt_.negative() != negative) {
      if (!ldlt_.inertia_certified()) return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
      return Ipopt::SYMSOLVER_WRONG_INERTIA;
    }
    return solve_ldlt(ia, ja, nrhs, rhs, check_inertia, negative);
  }

  // Solves with disco's factors; any right-hand side they cannot solve to the tolerance sends
  // the matrix to MUMPS.
  ESymSolverStatus solve_ldlt(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                              bool check_inertia, Index negative) {
    original_.assign(rhs, rhs + static_cast<size_t>(dim_) * nrhs);
    for (Index j = 0; j < nrhs; ++j) {
      if (ldlt_.solve(rhs + static_cast<size_t>(j) * dim_) > options_.ldlt.residual_tolerance) {
        std::copy(original_.begin(), original_.end(), rhs);
        return on_mumps(ia, ja, nrhs, rhs, check_inertia, negative);
      }
    }
    return Ipopt::SYMSOLVER_SUCCESS;
  }

  // The current matrix to MUMPS (kkt.solver ldlt: counted as a fallback).
  ESymSolverStatus on_mumps(const Index* ia, const Index* ja, Index nrhs, double* rhs,
                            bool check_inertia, Index negative) {
    to_mumps_ = false;
    on_ldlt_ = false;
    ++counts_.fallbacks;
    ++counts_.factorisations;
    std::copy(values_.begin(), values_.end(), mumps_->GetValuesArrayPtr());
    return mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
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
  bool on_ldlt_ = false;   // the current matrix is factorised by ldlt_ (else by MUMPS)
  bool to_mumps_ = false;  // IncreaseQuality asked: the current matrix goes to MUMPS
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
