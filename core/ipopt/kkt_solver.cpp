// disco — the linear solver behind Ipopt's KKT solves (core/ipopt/kkt_solver.h says what it
// does and why). The only file of disco that includes Ipopt's internal headers.
#include "core/ipopt/kkt_solver.h"

#include <IpAlgBuilder.hpp>
#include <IpMumpsSolverInterface.hpp>
#include <IpStdAugSystemSolver.hpp>
#include <IpTNLPAdapter.hpp>
#include <IpTSymLinearSolver.hpp>

namespace disco {
namespace {

using Ipopt::ESymSolverStatus;
using Ipopt::Index;

// How many iterations get their unperturbed factorisations answered: Ipopt declares the Hessian
// degenerate after three (IpPDPerturbationHandler's degen_iters_max).
constexpr int kAnsweredIterations = 3;

// S of kkt_solver.h: Ipopt's MUMPS interface, with the degeneracy test answered.
class KktLinearSolver : public Ipopt::SparseSymLinearSolverInterface {
 public:
  KktLinearSolver(const KktOptions& options, KktCounts& counts)
      : options_(options), counts_(counts), estimate_pending_(options.cold) {}

  bool InitializeImpl(const Ipopt::OptionsList& options, const std::string& prefix) override {
    return mumps_->Initialize(Jnlst(), IpNLP(), IpData(), IpCq(), options, prefix);
  }
  ESymSolverStatus InitializeStructure(Index dim, Index nonzeros, const Index* ia,
                                       const Index* ja) override {
    return mumps_->InitializeStructure(dim, nonzeros, ia, ja);
  }
  double* GetValuesArrayPtr() override { return mumps_->GetValuesArrayPtr(); }

  ESymSolverStatus MultiSolve(bool new_matrix, const Index* ia, const Index* ja, Index nrhs,
                              double* rhs, bool check_inertia, Index negative) override {
    if (!new_matrix) return mumps_->MultiSolve(false, ia, ja, nrhs, rhs, check_inertia, negative);
    if (estimate_pending_) {  // the least-squares multiplier estimate: MUMPS's own
      estimate_pending_ = false;
      analysed_ = true;
      ++counts_.factorisations;
      return mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
    }
    if (answer_singular()) {
      ++tries_;
      ++counts_.answered;
      if (!analysed_) {
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
    const ESymSolverStatus status =
        mumps_->MultiSolve(true, ia, ja, nrhs, rhs, check_inertia, negative);
    if (status == Ipopt::SYMSOLVER_SUCCESS) {  // the iteration's factorisation: the next begins
      ++iteration_;
      tries_ = 0;
    }
    return status;
  }

  Index NumberOfNegEVals() const override { return mumps_->NumberOfNegEVals(); }
  bool IncreaseQuality() override { return mumps_->IncreaseQuality(); }
  bool ProvidesInertia() const override { return mumps_->ProvidesInertia(); }
  EMatrixFormat MatrixFormat() const override { return mumps_->MatrixFormat(); }
  bool ProvidesDegeneracyDetection() const override {
    return mumps_->ProvidesDegeneracyDetection();
  }
  ESymSolverStatus DetermineDependentRows(const Index* ia, const Index* ja,
                                          std::list<Index>& rows) override {
    return mumps_->DetermineDependentRows(ia, ja, rows);
  }

 private:
  // Whether this factorisation is one Ipopt makes with δx = 0 for its degeneracy test.
  bool answer_singular() const {
    if (!options_.perturbed_first || iteration_ >= kAnsweredIterations) return false;
    return tries_ < (iteration_ == 0 ? 2 : 1);
  }

  Ipopt::SmartPtr<Ipopt::MumpsSolverInterface> mumps_ = new Ipopt::MumpsSolverInterface();
  const KktOptions options_;
  KktCounts& counts_;
  bool estimate_pending_;
  bool analysed_ = false;  // MUMPS has seen a matrix of this solve
  int iteration_ = 0;  // iterations whose factorisation succeeded
  int tries_ = 0;      // factorisations asked for in the current iteration
};

}  // namespace

Ipopt::ApplicationReturnStatus optimize(Ipopt::IpoptApplication& app,
                                        const Ipopt::SmartPtr<Ipopt::TNLP>& tnlp,
                                        const KktOptions& options, KktCounts& counts) {
  Ipopt::SmartPtr<Ipopt::SparseSymLinearSolverInterface> solver =
      new KktLinearSolver(options, counts);
  Ipopt::SmartPtr<Ipopt::SymLinearSolver> scaled = new Ipopt::TSymLinearSolver(solver, nullptr);
  Ipopt::SmartPtr<Ipopt::AugSystemSolver> augmented = new Ipopt::StdAugSystemSolver(*scaled);
  Ipopt::SmartPtr<Ipopt::AlgorithmBuilder> builder = new Ipopt::AlgorithmBuilder(augmented);
  Ipopt::SmartPtr<Ipopt::NLP> nlp =
      new Ipopt::TNLPAdapter(Ipopt::GetRawPtr(tnlp), Ipopt::ConstPtr(app.Jnlst()));
  return app.OptimizeNLP(nlp, builder);
}

}  // namespace disco
