// NLopt on the box-constrained path problem: LBFGS with the exact gradient,
// BOBYQA derivative-free.
#include <nlopt.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "local_solvers.hpp"
#include "talus/core/error.hpp"

namespace talus::detail {
namespace {

std::string result_text(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS:
      return "success";
    case nlopt::STOPVAL_REACHED:
      return "stopval_reached";
    case nlopt::FTOL_REACHED:
      return "ftol_reached";
    case nlopt::XTOL_REACHED:
      return "xtol_reached";
    case nlopt::MAXEVAL_REACHED:
      return "maxeval_reached";
    case nlopt::MAXTIME_REACHED:
      return "maxtime_reached";
    case nlopt::ROUNDOFF_LIMITED:
      return "roundoff_limited";
    case nlopt::FORCED_STOP:
      return "forced_stop";
    default:
      return "failure (" + std::to_string(static_cast<int>(r)) + ")";
  }
}

struct Context {
  TrackedObjective& objective;
  std::size_t calls = 0;
  const Termination& termination;  ///< BoxProblem::termination
  bool timed_out = false;
};

// Infeasible paths cost a large finite value above any feasible time, with a
// zero gradient: NLopt needs finite numbers, and its line searches and trust
// regions then step back.
double penalised(unsigned n, const double* z, double* gradient, void* data) {
  auto& context = *static_cast<Context*>(data);
  if (context.termination.should_stop()) {
    context.timed_out = true;
    throw nlopt::forced_stop();
  }
  ++context.calls;
  const Eigen::Map<const Eigen::VectorXd> x(z, n);
  Eigen::VectorXd g;
  const double t = context.objective(x, gradient != nullptr ? &g : nullptr);
  if (std::isfinite(t)) {
    if (gradient != nullptr) Eigen::Map<Eigen::VectorXd>(gradient, n) = g;
    return t;
  }
  if (gradient != nullptr) Eigen::Map<Eigen::VectorXd>(gradient, n).setZero();
  return 1e3 * context.objective.best_value() + 1e3;
}

SolverRun run_nlopt(nlopt::algorithm algorithm, TrackedObjective& objective,
                    const BoxProblem& problem) {
  const auto n = static_cast<unsigned>(problem.start.size());
  nlopt::opt optimizer(algorithm, n);
  const auto to_vector = [](const Eigen::VectorXd& v) {
    return std::vector<double>(v.data(), v.data() + v.size());
  };
  optimizer.set_lower_bounds(to_vector(problem.lower));
  optimizer.set_upper_bounds(to_vector(problem.upper));
  Context context{objective, 0, problem.termination, false};
  optimizer.set_min_objective(penalised, &context);
  optimizer.set_maxeval(static_cast<int>(problem.max_evaluations));
  optimizer.set_ftol_rel(problem.relative_tolerance);
  if (algorithm == nlopt::LN_BOBYQA) optimizer.set_initial_step(problem.initial_step);
  std::vector<double> x = to_vector(problem.start);
  double value = 0.0;
  SolverRun run;
  nlopt::result result = nlopt::FAILURE;
  try {
    result = optimizer.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
    result = nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    result = nlopt::FORCED_STOP;
  } catch (const std::exception& e) {
    run.status = std::string("failure: ") + e.what();
    run.failed = true;
    run.iterations = context.calls;
    return run;
  }
  run.status = result_text(result);
  run.failed = result < 0 && result != nlopt::ROUNDOFF_LIMITED;
  if (context.timed_out) {
    run.status = "time_limit";
    run.failed = false;
  }
  // NLopt counts evaluations, not iterations: report the evaluations.
  run.iterations = context.calls;
  return run;
}

}  // namespace

SolverRun run_nlopt_lbfgs(TrackedObjective& objective, const BoxProblem& problem) {
  return run_nlopt(nlopt::LD_LBFGS, objective, problem);
}

SolverRun run_nlopt_bobyqa(TrackedObjective& objective, const BoxProblem& problem) {
  return run_nlopt(nlopt::LN_BOBYQA, objective, problem);
}

}  // namespace talus::detail
