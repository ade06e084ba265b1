// The local-optimality certificate (issue #36): it certifies the straight line on a plane
// (the known optimum, rest to rest) and finds the known improvement of a path bent away
// from it, returning a faster path.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/optimal/planner.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using vehicle_test::point_mass_rover;

BPatch flat_plane() {
  return BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
}

/// An "optimum" with these control points, evaluated at `stations` search stations.
OptimizedPath optimum_through(const BPatch& terrain, const std::vector<Vec2>& polyline,
                              std::size_t control_points, std::size_t stations,
                              const PathOptimizerOptions& options) {
  OptimizedPath o(fit_candidate(terrain, polyline, control_points, options));
  o.control_points = control_points;
  o.stations = stations;
  return o;
}

double time_of(const BPatch& terrain, const Curve2& curve, std::size_t stations) {
  const std::vector<Vec2>& c = curve.control_points();
  PathTimeObjective objective(terrain, point_mass_rover(0.5), c.front(), c.back(), c.size(),
                              stations, {});
  return objective.evaluate(objective.variables(c));
}

TEST(LocalCertificate, CertifiesTheStraightLineOnAPlane) {
  const BPatch flat = flat_plane();
  const PathOptimizerOptions options;
  const OptimizedPath line = optimum_through(flat, {{5, 20}, {55, 20}}, 6, 101, options);
  const LocalCertificate c = certify_local_optimum(flat, point_mass_rover(0.5), line, options);
  EXPECT_TRUE(c.certified) << c.improvement << " " << c.solver_status;
  EXPECT_EQ(c.radius, 0.25);  // a quarter of the 1 m cell
  // Not exactly zero: moving control points along the line moves the stations (equally
  // spaced in the curve parameter), and the first-order profile's discretisation error at
  // 0.5 m stations changes with them (1.4e-5 measured), far below the 5e-4 tolerance.
  EXPECT_LE(c.improvement, 5e-5);
  EXPECT_GE(c.improvement, 0.0);
  EXPECT_GT(c.evaluations, 2 * 4u);  // it searched: at least two probes per free coordinate
  EXPECT_EQ(c.travel_time, time_of(flat, line.curve, 101));
}

TEST(LocalCertificate, FindsTheKnownImprovementOfABentPath) {
  const BPatch flat = flat_plane();
  const PathOptimizerOptions options;
  // Bent 2 m off the straight line at its middle: the straight line (reachable within the
  // 2.5 m radius) is faster by about 0.4 % (a 0.15 m bend costs 2.5e-5 and the cost grows
  // with the square of the bend).
  const OptimizedPath bent = optimum_through(flat, {{5, 20}, {30, 22}, {55, 20}}, 6, 101, options);
  const OptimizedPath line = optimum_through(flat, {{5, 20}, {55, 20}}, 6, 101, options);
  const double known = 1.0 - time_of(flat, line.curve, 101) / time_of(flat, bent.curve, 101);
  ASSERT_GT(known, 2e-3);
  LocalCertificateOptions radius;
  radius.radius = 2.5;
  radius.rounds = 1;  // one search: the bent path is not a local optimum
  const LocalCertificate once =
      certify_local_optimum(flat, point_mass_rover(0.5), bent, options, radius);
  EXPECT_FALSE(once.certified);
  EXPECT_GT(once.improvement, 0.5 * known) << "known " << known;
  // With further rounds from the better point the search ends certified near the line.
  radius.rounds = 3;
  const LocalCertificate c =
      certify_local_optimum(flat, point_mass_rover(0.5), bent, options, radius);
  EXPECT_TRUE(c.certified);
  EXPECT_GE(c.rounds, 2u);
  EXPECT_GT(c.improvement, 0.5 * known) << "known " << known;
  EXPECT_LE(c.improvement, known * (1.0 + 1e-6));  // nothing beats the straight line
  ASSERT_TRUE(c.better.has_value());
  EXPECT_DOUBLE_EQ(time_of(flat, *c.better, 101), c.best_time);
  EXPECT_LT(c.best_time, c.travel_time);
}

// PlannerOptions::certify: every optimum carries its certificate, and a plan with it is
// never slower than without (a faster point the certificate finds is kept only if faster).
TEST(LocalCertificate, ThePlannerCertifiesEveryOptimum) {
  const auto hill =
      std::make_shared<const BPatch>(BPatch::interpolate(terrain_test::grid_from_function(
          [](double x, double y) {
            return 3.0 * std::exp(-((x - 30) * (x - 30) + (y - 20) * (y - 20)) / 50.0);
          },
          0, 0, 60, 40, 1.0)));
  const PlanningProblem problem(hill, point_mass_rover(0.5), {5, 20}, {55, 20});
  PlannerOptions options;
  options.global.candidates = 2;
  const PlannerResult plain = plan(problem, options);
  options.certify = true;
  const PlannerResult certified = plan(problem, options);
  ASSERT_NE(certified.best(), nullptr) << certified.brief_report();
  for (const CandidateOutcome& c : certified.candidates) {
    if (!c.optimization) continue;
    ASSERT_TRUE(c.certificate.has_value());
    EXPECT_GT(c.certificate->evaluations, 0u);
    EXPECT_GE(c.certificate->improvement, 0.0);
  }
  EXPECT_LE(certified.travel_time(), plain.travel_time());
}

TEST(LocalCertificate, RefusesBadOptions) {
  const BPatch flat = flat_plane();
  const OptimizedPath line = optimum_through(flat, {{5, 20}, {55, 20}}, 6, 101, {});
  LocalCertificateOptions bad;
  bad.radius = -1.0;
  EXPECT_THROW(certify_local_optimum(flat, point_mass_rover(0.5), line, {}, bad), InputError);
}

}  // namespace
}  // namespace talus
