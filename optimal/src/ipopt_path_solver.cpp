// Ipopt on the box-constrained path problem, with the vehicle's steering
// limit as smooth constraints |κ_k| <= κ_max along the path when it has one
// (PathTimeObjective::curvatures); exact gradients, limited-memory BFGS
// Hessian, MUMPS (Debian's default).
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <cmath>
#include <string>

#include "ipopt_lock.hpp"
#include "ipopt_status.hpp"
#include "local_solvers.hpp"

namespace talus::detail {

std::string ipopt_status_text(Ipopt::SolverReturn status) {
  switch (status) {
    case Ipopt::SUCCESS:
      return "success";
    case Ipopt::MAXITER_EXCEEDED:
      return "maxiter_exceeded";
    case Ipopt::CPUTIME_EXCEEDED:
      return "cputime_exceeded";
    case Ipopt::STOP_AT_TINY_STEP:
      return "stop_at_tiny_step";
    case Ipopt::STOP_AT_ACCEPTABLE_POINT:
      return "stop_at_acceptable_point";
    case Ipopt::LOCAL_INFEASIBILITY:
      return "local_infeasibility";
    case Ipopt::USER_REQUESTED_STOP:
      return "user_requested_stop";
    case Ipopt::DIVERGING_ITERATES:
      return "diverging_iterates";
    case Ipopt::RESTORATION_FAILURE:
      return "restoration_failure";
    case Ipopt::ERROR_IN_STEP_COMPUTATION:
      return "error_in_step_computation";
    case Ipopt::INVALID_NUMBER_DETECTED:
      return "invalid_number_detected";
    case Ipopt::TOO_FEW_DEGREES_OF_FREEDOM:
      return "too_few_degrees_of_freedom";
    case Ipopt::INVALID_OPTION:
      return "invalid_option";
    case Ipopt::OUT_OF_MEMORY:
      return "out_of_memory";
    case Ipopt::INTERNAL_ERROR:
      return "internal_error";
    default:
      return "unassigned";
  }
}

namespace {

using Ipopt::Index;
using Ipopt::Number;

class PathNlp : public Ipopt::TNLP {
 public:
  PathNlp(TrackedObjective& objective, const BoxProblem& problem)
      : objective_(objective),
        problem_(problem),
        first_evaluation_(objective.evaluations()),
        steering_(std::isfinite(objective.objective().max_curvature())) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    const PathTimeObjective& path = objective_.objective();
    n = static_cast<Index>(problem_.start.size());
    m = steering_ ? static_cast<Index>(path.curvature_samples()) : 0;
    nnz_jac_g = steering_ ? static_cast<Index>(path.curvature_pattern().size()) : 0;
    nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = problem_.lower[i];
      x_u[i] = problem_.upper[i];
    }
    const double kappa =
        (1.0 - PathTimeObjective::kSteeringMargin) * objective_.objective().max_curvature();
    for (Index r = 0; r < m; ++r) {
      g_l[r] = -kappa;
      g_u[r] = kappa;
    }
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    for (Index i = 0; i < n; ++i) x[i] = problem_.start[i];
    return true;
  }
  // An infeasible path (off the data, no admissible profile) is an
  // evaluation error: Ipopt then shortens the step.
  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    value = objective_(Eigen::Map<const Eigen::VectorXd>(x, n), nullptr);
    return std::isfinite(value);
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    Eigen::VectorXd g(n);
    const double value = objective_(Eigen::Map<const Eigen::VectorXd>(x, n), &g);
    if (!std::isfinite(value)) return false;
    Eigen::Map<Eigen::VectorXd>(gradient, n) = g;
    return true;
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    if (m == 0) return true;
    return objective_.objective().curvatures(Eigen::Map<const Eigen::VectorXd>(x, n), g, nullptr);
  }
  bool eval_jac_g(Index n, const Number* x, bool, Index, Index, Index* i_row, Index* j_col,
                  Number* values) override {
    const PathTimeObjective& path = objective_.objective();
    if (!steering_) return true;
    if (values == nullptr) {
      const auto& pattern = path.curvature_pattern();
      for (std::size_t e = 0; e < pattern.size(); ++e) {
        i_row[e] = static_cast<Index>(pattern[e].first);
        j_col[e] = static_cast<Index>(pattern[e].second);
      }
      return true;
    }
    return path.curvatures(Eigen::Map<const Eigen::VectorXd>(x, n), nullptr, values);
  }
  bool intermediate_callback(Ipopt::AlgorithmMode, Index iteration, Number, Number, Number, Number,
                             Number, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = static_cast<std::size_t>(iteration);
    if (problem_.termination.should_stop()) {
      timed_out_ = true;
      return false;
    }
    // The budget is this run's: a restart on the same objective gets its own.
    return objective_.evaluations() - first_evaluation_ < problem_.max_evaluations;
  }
  bool timed_out() const { return timed_out_; }
  void finalize_solution(Ipopt::SolverReturn status, Index, const Number*, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    status_ = status;
  }

  Ipopt::SolverReturn status() const { return status_; }
  std::size_t iterations() const { return iterations_; }

 private:
  TrackedObjective& objective_;
  const BoxProblem& problem_;
  std::size_t first_evaluation_ = 0;  ///< objective evaluations before this run
  bool steering_ = false;             ///< the steering rows are present
  Ipopt::SolverReturn status_ = Ipopt::UNASSIGNED;
  std::size_t iterations_ = 0;
  bool timed_out_ = false;
};

}  // namespace

SolverRun run_ipopt(TrackedObjective& objective, const BoxProblem& problem) {
  const auto ipopt_lock = detail::lock_ipopt();  // before the SmartPtrs: released after them
  Ipopt::SmartPtr<PathNlp> nlp = new PathNlp(objective, problem);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  auto options = app->Options();
  options->SetIntegerValue("print_level", 0);
  options->SetStringValue("sb", "yes");
  options->SetStringValue("hessian_approximation", "limited-memory");
  // The quasi-Newton term inside the augmented system: one factorisation per
  // iteration. The default (Sherman-Morrison) route takes 2 x history extra
  // solves per update, and on a few dozen variables MUMPS 5.5 spends more of
  // each call in its own bookkeeping than in the solve: 17 % of a battery plan.
  options->SetStringValue("limited_memory_aug_solver", "extended");
  // No second-order correction: its trial points cost a profile each, and the
  // only constraints (steering) are mild beside the objective's kinks.
  options->SetIntegerValue("max_soc", 0);
  options->SetIntegerValue("max_iter", static_cast<int>(problem.max_iterations));
  // Travel times are O(10..1000 s): an absolute tolerance on the scaled
  // gradient plus Ipopt's relative objective test.
  options->SetNumericValue("tol", 1e-6);
  options->SetNumericValue("acceptable_tol", 1e-4);
  options->SetNumericValue("acceptable_obj_change_tol", problem.relative_tolerance);
  options->SetIntegerValue("acceptable_iter", 5);
  // Bounds are the terrain box: do not let Ipopt relax them off the map.
  options->SetNumericValue("bound_relax_factor", 0.0);
  options->SetStringValue("honor_original_bounds", "yes");
  // Start at the candidate itself: by default Ipopt pushes the start up to
  // 1 % of the box away from the bounds (tens of metres on a DEM).
  options->SetNumericValue("bound_push", 1e-8);
  options->SetNumericValue("bound_frac", 1e-8);
  // Never set linear_solver=ma97: Debian's Ipopt 3.11 calls exit(1) for it.
  SolverRun run;
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    run.status = "initialization_failed";
    run.failed = true;
    return run;
  }
  app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
  run.status = ipopt_status_text(nlp->status());
  // The user stops are the evaluation budget and the time limit
  // (intermediate_callback).
  if (nlp->status() == Ipopt::USER_REQUESTED_STOP) {
    run.status = nlp->timed_out() ? "time_limit" : "maxeval_reached";
  }
  run.iterations = nlp->iterations();
  const Ipopt::SolverReturn s = nlp->status();
  run.failed = !(s == Ipopt::SUCCESS || s == Ipopt::STOP_AT_ACCEPTABLE_POINT ||
                 s == Ipopt::MAXITER_EXCEEDED || s == Ipopt::CPUTIME_EXCEEDED ||
                 s == Ipopt::USER_REQUESTED_STOP || s == Ipopt::STOP_AT_TINY_STEP);
  return run;
}

}  // namespace talus::detail
