#include "talus/kinematic/hait_smoothing.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

namespace {

/// Uniform integer in [0, n) from the raw 64-bit draws of mt19937_64, by
/// rejection, so the sequence is the same on every platform (the standard
/// distributions are implementation-defined).
std::size_t uniform_index(std::mt19937_64& rng, std::size_t n) {
  const std::uint64_t range = static_cast<std::uint64_t>(n);
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % range;
  std::uint64_t x = rng();
  while (x >= limit) x = rng();
  return static_cast<std::size_t>(x % range);
}

}  // namespace

void HaitSmoothingOptions::validate() const {
  if (!(max_span >= 0.0) || !std::isfinite(max_span)) {
    std::ostringstream msg;
    msg << "HaitSmoothingOptions: max_span = " << max_span << ", expected >= 0";
    throw InputError(msg.str());
  }
  if (!(check_spacing > 0.0) || !std::isfinite(check_spacing)) {
    std::ostringstream msg;
    msg << "HaitSmoothingOptions: check_spacing = " << check_spacing << ", expected > 0";
    throw InputError(msg.str());
  }
}

std::vector<PathPoint> smooth_path(const std::vector<PathPoint>& path,
                                   const ValidityFunction& validity, const ReedsShepp& curves,
                                   const HaitSmoothingOptions& options,
                                   HaitSmoothingReport* report) {
  options.validate();
  if (path.size() < 2) {
    throw InputError("smooth_path: the path has " + std::to_string(path.size()) +
                     " configurations, expected at least 2");
  }
  if (!validity) throw InputError("smooth_path: no validity function");
  const double radius = curves.radius();
  std::vector<PathPoint> current = path;
  HaitSmoothingReport r;
  r.control_changes_before = control_changes(current);
  r.length_before = path_length(current, radius);
  std::size_t changes = r.control_changes_before;
  double length = r.length_before;
  std::mt19937_64 rng(options.seed);

  for (std::size_t it = 0; it < options.iterations; ++it) {
    const std::size_t n = current.size();
    if (n < 3) break;
    std::size_t i = uniform_index(rng, n);
    std::size_t j = uniform_index(rng, n);
    if (i > j) std::swap(i, j);
    if (j < i + 2) continue;  // nothing between them to replace
    // Arc length between the pair, for the "close configurations" limit.
    const std::span<const PathPoint> portion(current.data() + i, j - i + 1);
    if (options.max_span > 0.0 && path_length(portion, radius) > options.max_span) continue;

    const std::vector<PathPoint> curve =
        curves.sample(current[i].pose, current[j].pose, options.check_spacing);
    // Candidate path: [0, i] + curve (without its first point) + (j, n).
    std::vector<PathPoint> candidate(current.begin(), current.begin() + i + 1);
    candidate.insert(candidate.end(), curve.begin() + 1, curve.end());
    // The point after j keeps its control; j itself is the curve's last point.
    candidate.insert(candidate.end(), current.begin() + j + 1, current.end());
    const std::size_t new_changes = control_changes(candidate);
    const double new_length = path_length(candidate, radius);
    if (new_changes > changes || (new_changes == changes && new_length >= length - 1e-9)) continue;

    bool ok = true;
    for (std::size_t k = 1; k + 1 < curve.size() && ok; ++k) {  // both ends are on the path already
      const ConfigurationCheck c = validity(curve[k].pose);
      r.placements += c.placements;
      ok = c.valid;
    }
    if (!ok) continue;
    current = std::move(candidate);
    changes = new_changes;
    length = new_length;
    ++r.replacements;
  }
  r.control_changes_after = changes;
  r.length_after = length;
  if (report != nullptr) *report = r;
  return current;
}

}  // namespace talus
