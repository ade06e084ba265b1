#include "talus/kinematic/hait/hait_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <span>
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

namespace {

/// The smoothing state: the current path, its control changes and length,
/// and the one replacement step every stage uses.
class Smoother {
 public:
  Smoother(const std::vector<PathPoint>& path, const ValidityFunction& validity,
           const ReedsShepp& curves, double spacing, HaitSmoothingReport& report)
      : path_(path),
        validity_(validity),
        curves_(curves),
        spacing_(spacing),
        report_(report),
        changes_(control_changes(path)),
        length_(path_length(path, curves.radius())) {}

  const std::vector<PathPoint>& path() const { return path_; }
  std::size_t changes() const { return changes_; }
  double length() const { return length_; }

  /// Tries to replace path_[i..j] (i + 2 <= j) by the shortest Reeds–Shepp
  /// curve between its ends. The cheap test (control changes, length) comes
  /// before the validity checks. On success returns the index of the curve's
  /// last point (the old j) in the new path.
  std::optional<std::size_t> try_replace(std::size_t i, std::size_t j) {
    const std::vector<PathPoint> curve = curves_.sample(path_[i].pose, path_[j].pose, spacing_);
    // Candidate path: [0, i] + curve (without its first point) + (j, n); the
    // point after j keeps its control, j itself is the curve's last point.
    std::vector<PathPoint> candidate(path_.begin(),
                                     path_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    candidate.insert(candidate.end(), curve.begin() + 1, curve.end());
    candidate.insert(candidate.end(), path_.begin() + static_cast<std::ptrdiff_t>(j) + 1,
                     path_.end());
    const std::size_t new_changes = control_changes(candidate);
    const double new_length = path_length(candidate, curves_.radius());
    if (new_changes > changes_ || (new_changes == changes_ && new_length >= length_ - 1e-9)) {
      return std::nullopt;
    }
    for (std::size_t k = 1; k + 1 < curve.size(); ++k) {  // both ends are on the path already
      const ConfigurationCheck c = validity_(curve[k].pose);
      report_.placements += c.placements;
      if (!c.valid) return std::nullopt;
    }
    path_ = std::move(candidate);
    changes_ = new_changes;
    length_ = new_length;
    ++report_.replacements;
    return i + curve.size() - 1;
  }

 private:
  std::vector<PathPoint> path_;
  const ValidityFunction& validity_;
  const ReedsShepp& curves_;
  double spacing_;
  HaitSmoothingReport& report_;
  std::size_t changes_;
  double length_;
};

/// Cumulative driven length at every configuration of `path`.
std::vector<double> cumulative_length(const std::vector<PathPoint>& path, double radius) {
  std::vector<double> s(path.size(), 0.0);
  for (std::size_t k = 1; k < path.size(); ++k) {
    s[k] = s[k - 1] + path_length(std::span<const PathPoint>(path.data() + k - 1, 2), radius);
  }
  return s;
}

/// Index of the control run (segment) of every configuration: 0 for the
/// first point and the points after it with its successor's control, +1 at
/// every control change. The segment between points k − 1 and k has the
/// control of point k, so a portion i..j covers runs run[i + 1] .. run[j].
std::vector<std::size_t> control_runs(const std::vector<PathPoint>& path) {
  std::vector<std::size_t> run(path.size(), 0);
  for (std::size_t k = 2; k < path.size(); ++k) {
    run[k] = run[k - 1] + (path[k].control == path[k - 1].control ? 0 : 1);
  }
  return run;
}

/// The paper's random pairs (§4.4).
void random_pairs(Smoother& sm, const HaitSmoothingOptions& options, double radius) {
  std::mt19937_64 rng(options.seed);
  std::vector<double> s = cumulative_length(sm.path(), radius);
  std::vector<std::size_t> run = control_runs(sm.path());
  const bool by_length = options.max_span > 0.0;
  const bool by_controls = options.max_span_controls > 0;
  // Controls covered by the portion i..j (i < j).
  const auto controls = [&](std::size_t i, std::size_t j) { return run[j] - run[i + 1] + 1; };
  for (std::size_t it = 0; it < options.iterations; ++it) {
    const std::size_t n = sm.path().size();
    if (n < 3) break;
    std::size_t i = uniform_index(rng, n);
    std::size_t j = 0;
    if (options.draw_within_span && (by_length || by_controls)) {
      // j uniform among the configurations within both limits of i (i excluded).
      std::size_t lo = 0, hi = n;
      if (by_length) {
        lo = static_cast<std::size_t>(
            std::lower_bound(s.begin(), s.end(), s[i] - options.max_span) - s.begin());
        hi = static_cast<std::size_t>(
            std::upper_bound(s.begin(), s.end(), s[i] + options.max_span) - s.begin());
      }
      if (by_controls) {
        // Forward: j with run[j] <= run[i + 1] + N − 1; backward: j with run[j + 1] >=
        // run[i] − (N − 1), i.e. run[j] >= run[i] − N + 1 up to the one-point offset (checked
        // exactly below).
        const std::size_t span = options.max_span_controls - 1;
        const std::size_t up = (i + 1 < n ? run[i + 1] : run[i]) + span;
        const std::size_t down = run[i] > span ? run[i] - span : 0;
        lo = std::max(lo, static_cast<std::size_t>(std::lower_bound(run.begin(), run.end(), down) -
                                                   run.begin()));
        hi = std::min(hi, static_cast<std::size_t>(std::upper_bound(run.begin(), run.end(), up) -
                                                   run.begin()));
      }
      lo = std::min(lo, i);
      hi = std::max(hi, i + 1);
      if (hi - lo < 2) continue;
      j = lo + uniform_index(rng, hi - lo - 1);
      if (j >= i) ++j;
    } else {
      j = uniform_index(rng, n);
    }
    if (i > j) std::swap(i, j);
    if (j < i + 2) continue;  // nothing between them to replace
    if (by_length && s[j] - s[i] > options.max_span) continue;
    if (by_controls && controls(i, j) > options.max_span_controls) continue;
    if (sm.try_replace(i, j)) {
      s = cumulative_length(sm.path(), radius);
      run = control_runs(sm.path());
    }
  }
}

/// One greedy shortcut pass (our addition); returns true if it replaced anything.
bool greedy_pass(Smoother& sm) {
  bool changed = false;
  std::size_t i = 0;
  while (i + 2 < sm.path().size()) {
    const std::vector<PathPoint>& p = sm.path();
    const std::size_t n = p.size();
    // Candidate ends, farthest first: the goal, then the last configuration
    // of every control run after i (where a switch happens).
    std::vector<std::size_t> ends{n - 1};
    for (std::size_t k = n - 2; k >= i + 2; --k) {
      if (!(p[k + 1].control == p[k].control)) ends.push_back(k);
    }
    std::optional<std::size_t> reached;
    for (const std::size_t j : ends) {
      reached = sm.try_replace(i, j);
      if (reached) break;
    }
    if (reached) {
      changed = true;
      i = *reached;
      continue;
    }
    // Nothing from i: move to the end of i's control run.
    const std::vector<PathPoint>& q = sm.path();
    std::size_t k = i + 1;
    while (k + 1 < q.size() && q[k + 1].control == q[k].control) ++k;
    i = k;
  }
  return changed;
}

}  // namespace

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
  HaitSmoothingReport r;
  r.control_changes_before = control_changes(path);
  r.length_before = path_length(path, radius);
  Smoother sm(path, validity, curves, options.check_spacing, r);
  random_pairs(sm, options, radius);
  r.control_changes_random = sm.changes();
  if (options.method == HaitSmoothingMethod::kRandomPairsThenGreedy) {
    // Each pass strictly lowers (changes, length) when it changes anything, so this ends;
    // the cap only bounds the work on pathological paths.
    constexpr std::size_t kMaxPasses = 20;
    while (r.greedy_passes < kMaxPasses) {
      ++r.greedy_passes;
      if (!greedy_pass(sm)) break;
    }
  }
  r.control_changes_after = sm.changes();
  r.length_after = sm.length();
  if (report != nullptr) *report = r;
  return sm.path();
}

}  // namespace talus
