#include "talus/optimal/path_optimizer.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "talus/bspline/curve_fit.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Curve2 clamped_cubic(const std::vector<Vec2>& control_points) {
  std::vector<double> breaks;
  const std::size_t spans = control_points.size() - 3;
  for (std::size_t k = 0; k <= spans; ++k) breaks.push_back(static_cast<double>(k) / spans);
  return Curve2(KnotVector::clamped(3, breaks), control_points);
}

std::string nlopt_result_text(nlopt::result r) {
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
    default:
      return "failure (" + std::to_string(static_cast<int>(r)) + ")";
  }
}

}  // namespace

void PathOptimizerOptions::validate() const {
  if (control_points < 4) throw InputError("PathOptimizerOptions.control_points must be >= 4");
  if (!(station_spacing > 0.0) || !std::isfinite(station_spacing)) {
    throw InputError("PathOptimizerOptions.station_spacing must be positive");
  }
  if (max_evaluations < 10) throw InputError("PathOptimizerOptions.max_evaluations must be >= 10");
  if (!(relative_tolerance > 0.0))
    throw InputError("PathOptimizerOptions.relative_tolerance must be positive");
  speeds.validate();
}

double path_travel_time(const BPatch& terrain, const Vehicle& vehicle,
                        const std::vector<Vec2>& control_points, double station_spacing,
                        const ProfileOptions& speeds) {
  for (const Vec2& c : control_points) {
    if (!c.allFinite()) return kInfinity;
  }
  try {
    const SurfacePath path(terrain, clamped_cubic(control_points));
    const auto stations =
        std::max<std::size_t>(static_cast<std::size_t>(path.length() / station_spacing) + 1, 2);
    const VelocityLimits limits(vehicle, path, stations);
    TimeOptimalProfileSolver solver;
    const TimeOptimalProfile profile = solver.solve(limits, speeds);
    return profile.status == ProfileStatus::kOk ? profile.travel_time : kInfinity;
  } catch (const InputError&) {
    return kInfinity;  // off the map, or a start/end speed above this path's limit
  }
}

OptimizedPath optimize_path_bobyqa(const BPatch& terrain, const Vehicle& vehicle,
                                   const std::vector<Vec2>& initial_polyline,
                                   const PathOptimizerOptions& options) {
  options.validate();
  if (initial_polyline.size() < 2) throw InputError("the initial path needs at least 2 vertices");
  const Curve2 initial = fit_clamped_cubic(
      resample_polyline(initial_polyline, std::max<std::size_t>(10 * options.control_points,
                                                                initial_polyline.size())),
      options.control_points);
  std::vector<Vec2> control = initial.control_points();
  const double initial_time =
      path_travel_time(terrain, vehicle, control, options.station_spacing, options.speeds);
  if (!std::isfinite(initial_time)) {
    throw InputError("the initial path leaves the map or has no admissible velocity profile");
  }
  const std::size_t free = control.size() - 2;
  std::vector<double> x(2 * free), lower(2 * free), upper(2 * free);
  for (std::size_t k = 0; k < free; ++k) {
    x[2 * k] = control[k + 1].x();
    x[2 * k + 1] = control[k + 1].y();
    lower[2 * k] = terrain.x_min();
    upper[2 * k] = terrain.x_max();
    lower[2 * k + 1] = terrain.y_min();
    upper[2 * k + 1] = terrain.y_max();
    // Start strictly inside the bounds: BOBYQA requires it.
    x[2 * k] = std::clamp(x[2 * k], lower[2 * k], upper[2 * k]);
    x[2 * k + 1] = std::clamp(x[2 * k + 1], lower[2 * k + 1], upper[2 * k + 1]);
  }
  struct Context {
    const BPatch& terrain;
    const Vehicle& vehicle;
    const PathOptimizerOptions& options;
    std::vector<Vec2> control;
    std::size_t evaluations = 0;
    double best = kInfinity;
    std::vector<Vec2> best_control;
  } context{terrain, vehicle, options, control, 0, initial_time, control};
  // Infeasible paths cost a large finite value (BOBYQA needs finite numbers)
  // well above any feasible time.
  const auto objective = [](unsigned n, const double* z, double*, void* data) {
    auto& ctx = *static_cast<Context*>(data);
    for (unsigned k = 0; k < n / 2; ++k) ctx.control[k + 1] = Vec2(z[2 * k], z[2 * k + 1]);
    ++ctx.evaluations;
    const double t = path_travel_time(ctx.terrain, ctx.vehicle, ctx.control,
                                      ctx.options.station_spacing, ctx.options.speeds);
    if (t < ctx.best) {
      ctx.best = t;
      ctx.best_control = ctx.control;
    }
    return std::isfinite(t) ? t : 1e3 * ctx.best + 1e3;
  };
  nlopt::opt optimizer(nlopt::LN_BOBYQA, static_cast<unsigned>(x.size()));
  optimizer.set_lower_bounds(lower);
  optimizer.set_upper_bounds(upper);
  optimizer.set_min_objective(objective, &context);
  optimizer.set_maxeval(static_cast<int>(options.max_evaluations));
  optimizer.set_ftol_rel(options.relative_tolerance);
  // Initial trust region: a tenth of the start–goal distance.
  const double scale = 0.1 * (initial_polyline.back() - initial_polyline.front()).norm();
  optimizer.set_initial_step(std::max(scale, terrain.cellsize()));
  double value = 0.0;
  nlopt::result result = nlopt::FAILURE;
  try {
    result = optimizer.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
    result = nlopt::ROUNDOFF_LIMITED;
  } catch (const std::exception& e) {
    throw SolverError(std::string("NLopt BOBYQA failed: ") + e.what());
  }
  OptimizedPath out{clamped_cubic(context.best_control), context.best, initial_time,
                    context.evaluations, nlopt_result_text(result)};
  return out;
}

}  // namespace talus
