#include "talus/optimal/profile_convergence.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"

namespace talus {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Fastest of repeated calls of `f`: at least `repeats`, and until `budget`
/// seconds have been spent.
template <typename F>
double fastest_seconds(int repeats, double budget, F&& f) {
  using Clock = std::chrono::steady_clock;
  double best = std::numeric_limits<double>::infinity(), spent = 0.0;
  for (int repeat = 0; repeat < repeats || spent < budget; ++repeat) {
    const auto t0 = Clock::now();
    f();
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    best = std::min(best, seconds);
    spent += seconds;
  }
  return best;
}

[[noreturn]] void invalid(const std::string& what) {
  throw InputError("ProfileConvergenceOptions." + what);
}

}  // namespace

void ProfileConvergenceOptions::validate() const {
  if (station_counts.size() < 2) {
    invalid("station_counts needs at least 2 entries, got " +
            std::to_string(station_counts.size()));
  }
  for (std::size_t i = 0; i < station_counts.size(); ++i) {
    if (station_counts[i] < 2) {
      invalid("station_counts[" + std::to_string(i) + "] must be >= 2, got " +
              std::to_string(station_counts[i]));
    }
    if (i > 0 && station_counts[i] <= station_counts[i - 1]) {
      invalid("station_counts must be strictly increasing, got " +
              std::to_string(station_counts[i - 1]) + " then " + std::to_string(station_counts[i]));
    }
  }
  for (std::size_t i = 0; i < extra_station_counts.size(); ++i) {
    const std::size_t n = extra_station_counts[i];
    if (n < 2 || n >= station_counts.back()) {
      invalid("extra_station_counts[" + std::to_string(i) +
              "] must be >= 2 and below the reference's " + std::to_string(station_counts.back()) +
              ", got " + std::to_string(n));
    }
  }
  speeds.validate();
  if (!(std::isfinite(richardson_order) && richardson_order > 0.0)) {
    std::ostringstream msg;
    msg << "richardson_order must be finite and > 0, got " << richardson_order;
    invalid(msg.str());
  }
  if (timing_repeats < 1) {
    invalid("timing_repeats must be >= 1, got " + std::to_string(timing_repeats));
  }
  if (!(std::isfinite(timing_budget_seconds) && timing_budget_seconds >= 0.0)) {
    std::ostringstream msg;
    msg << "timing_budget_seconds must be finite and >= 0, got " << timing_budget_seconds;
    invalid(msg.str());
  }
}

std::size_t ProfileConvergence::coarsest_within(double target) const {
  std::size_t found = levels.size();
  for (std::size_t i = levels.size() - 1; i-- > 0;) {  // finest non-reference first
    if (!(std::abs(levels[i].error) <= target)) break;
    if (levels[i].in_sequence) found = i;
  }
  return found;
}

std::size_t ProfileConvergence::find(std::size_t stations) const {
  for (std::size_t i = 0; i < levels.size(); ++i)
    if (levels[i].stations == stations) return i;
  return levels.size();
}

ProfileConvergence profile_convergence(const Vehicle& vehicle, const SurfacePath& path,
                                       const ProfileConvergenceOptions& options) {
  options.validate();
  ProfileConvergence result;
  for (const std::size_t n : options.station_counts) {
    ConvergenceLevel level;
    level.stations = n;
    level.in_sequence = true;
    result.levels.push_back(level);
  }
  for (const std::size_t n : options.extra_station_counts) {
    if (result.find(n) != result.levels.size()) continue;
    ConvergenceLevel extra;
    extra.stations = n;
    result.levels.insert(std::upper_bound(result.levels.begin(), result.levels.end(), extra,
                                          [](const ConvergenceLevel& a, const ConvergenceLevel& b) {
                                            return a.stations < b.stations;
                                          }),
                         extra);
  }

  VelocityLimits limits(vehicle);
  TimeOptimalProfileSolver solver;
  TimeOptimalProfile out;
  for (ConvergenceLevel& level : result.levels) {
    level.limits_seconds = fastest_seconds(options.timing_repeats, options.timing_budget_seconds,
                                           [&] { limits.compute(path, level.stations); });
    level.solve_seconds = fastest_seconds(options.timing_repeats, options.timing_budget_seconds,
                                          [&] { solver.solve(limits, options.speeds, out); });
    level.feasible = out.status == ProfileStatus::kOk;
    if (level.feasible) {
      level.travel_time = out.travel_time;
    } else {
      level.failure = describe_infeasibility(limits, out);
    }
    const std::vector<PathFrame>& frames = limits.frames();
    level.mean_spacing = frames.back().s / static_cast<double>(frames.size() - 1);
    for (std::size_t k = 1; k < frames.size(); ++k)
      level.max_spacing = std::max(level.max_spacing, frames[k].s - frames[k - 1].s);
  }

  const ConvergenceLevel& finest = result.levels.back();
  result.status =
      finest.feasible ? ConvergenceStatus::kOk : ConvergenceStatus::kReferenceInfeasible;
  for (ConvergenceLevel& level : result.levels)
    level.error = level.travel_time / finest.travel_time - 1.0;  // NaN if either is NaN

  std::vector<std::size_t> sequence;
  for (std::size_t i = 0; i < result.levels.size(); ++i)
    if (result.levels[i].in_sequence) sequence.push_back(i);
  for (std::size_t d = 0; d + 2 < sequence.size(); ++d) {
    ConvergenceLevel& coarse = result.levels[sequence[d]];
    const ConvergenceLevel& fine = result.levels[sequence[d + 1]];
    const double e0 = std::abs(coarse.error), e1 = std::abs(fine.error);
    if (e0 > 0.0 && e1 > 0.0)
      coarse.order = std::log(e0 / e1) / std::log(coarse.mean_spacing / fine.mean_spacing);
  }

  const ConvergenceLevel& coarse = result.levels[sequence[sequence.size() - 2]];
  const double ratio =
      std::pow(coarse.mean_spacing / finest.mean_spacing, options.richardson_order);
  result.extrapolated_time =
      finest.travel_time + (finest.travel_time - coarse.travel_time) / (ratio - 1.0);
  return result;
}

}  // namespace talus
