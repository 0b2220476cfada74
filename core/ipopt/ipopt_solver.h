// disco — solving an Nlp with Ipopt (exact Jacobian, exact Hessian).
//
// IpoptSolver owns one Ipopt application configured from option entries
// (normally the `ipopt:` section of configs/disco.yaml plus `--set ipopt.*`).
// Each entry is checked against Ipopt's registry when the solver is made: an
// unknown name or a bad value is an InputError naming where it was given.
//
// solve() runs one Ipopt solve from a start point, optionally warm-started
// with the multipliers of an earlier solve of an NLP of the same shape. MUMPS
// (Ipopt's linear solver here) is not thread-safe: call solve() from one
// thread of a process at a time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/nlp/nlp.h"

namespace disco {

struct IpoptOption {
  std::string name, value;
  std::string where;  // "FILE:LINE" or "--set", for error messages
};

// Primal and dual values of an NLP solve (Ipopt's sign conventions).
struct NlpPoint {
  Vector z;       // primal
  Vector lambda;  // constraint multipliers
  Vector z_lo;    // lower-bound multipliers (>= 0)
  Vector z_hi;    // upper-bound multipliers (>= 0)
  double mu = 0.0;  // Ipopt's barrier parameter at the last iteration (0: not from a solve)
  // Duals exist when the bound multipliers do (an NLP may have no rows).
  bool has_duals() const { return z_lo.size() > 0; }
};

struct NlpResult {
  NlpPoint point;
  double objective = 0.0;
  int ipopt_status = 0;  // Ipopt::ApplicationReturnStatus
  int iterations = 0;
  double seconds = 0.0;
  bool converged() const { return ipopt_status == 0 || ipopt_status == 1; }
};

// Ipopt's name for a return status, e.g. "Solve_Succeeded".
std::string ipopt_status_name(int status);

class IpoptSolver {
 public:
  explicit IpoptSolver(const std::vector<IpoptOption>& options);
  ~IpoptSolver();
  IpoptSolver(const IpoptSolver&) = delete;
  IpoptSolver& operator=(const IpoptSolver&) = delete;

  // Solves `nlp` from start.z; when start has duals (from a solve of an NLP
  // of the same shape) they warm-start Ipopt. A positive limit stops the
  // solve after that many seconds or iterations (status User_Requested_Stop).
  // A positive mu_init replaces the configured initial barrier parameter for
  // this solve (a warm start close to a solution should not start far inside).
  NlpResult solve(const Nlp& nlp, const NlpPoint& start, double wall_limit_s = 0.0,
                  int iteration_limit = 0, double mu_init = 0.0);

 private:
  struct Application;  // holds Ipopt's reference-counted application
  std::unique_ptr<Application> app_;
  double mu_init_ = 0.1;  // the configured one (Ipopt's default unless set)
};

}  // namespace disco
