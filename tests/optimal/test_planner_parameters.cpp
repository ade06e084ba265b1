// The planner's declared parameters: each reaches the PlannerOptions member
// it names, the defaults are PlannerOptions{}'s, and validate() enforces the
// declared bounds.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "talus/core/error.hpp"
#include "talus/optimal/planner_parameters.hpp"

namespace talus {
namespace {

TEST(PlannerParameters, EachParameterSetsItsMember) {
  const ParameterTable<PlannerOptions>& t = planner_parameters();
  PlannerOptions o;
  t.set_text(o, "candidates", "5");
  t.set_text(o, "lattice_spacing", "0.5");
  t.set_text(o, "connectivity", "32");
  t.set_text(o, "resolution", "multi");
  t.set_text(o, "threads", "0");
  t.set_text(o, "braking_rule", "false");
  t.set_text(o, "turn_limit", "false");
  t.set_text(o, "feedback_rounds", "2");
  t.set_text(o, "feedback_radius", "1.5");
  t.set_text(o, "station_spacing", "0.05");
  t.set_text(o, "time_limit", "3");
  t.set_text(o, "control_points", "56");
  t.set_text(o, "more_control_points", "8,24");
  t.set_text(o, "solver", "nlopt-bobyqa");
  t.set_text(o, "formulation", "simultaneous");
  t.set_text(o, "restarts", "0");
  t.set_text(o, "polish", "true");
  t.set_text(o, "certify", "false");
  EXPECT_EQ(o.global.candidates, 5u);
  EXPECT_EQ(o.global.lattice_spacing, 0.5);
  EXPECT_EQ(o.global.connectivity, 32);
  EXPECT_EQ(o.global.resolution, GlobalSearchResolution::kMulti);
  EXPECT_EQ(o.global.threads, 0u);
  EXPECT_FALSE(o.global.braking_rule);
  EXPECT_FALSE(o.global.turn_limit);
  EXPECT_EQ(o.feedback_rounds, 2u);
  EXPECT_EQ(o.feedback_radius, 1.5);
  EXPECT_EQ(o.station_spacing, 0.05);
  EXPECT_EQ(o.termination.smallest_budget(), 3.0);
  EXPECT_EQ(o.local.control_points, 56u);
  EXPECT_GE(o.local.max_control_points, 56u) << "the adaptive fit never shrinks below M";
  EXPECT_EQ(o.local.more_control_points, (std::vector<std::size_t>{8, 24}));
  EXPECT_EQ(o.local.solver, PathSolver::kNloptBobyqa);
  EXPECT_EQ(o.local.formulation, PathFormulation::kSimultaneous);
  EXPECT_EQ(o.local.restarts, 0u);
  EXPECT_TRUE(o.local.polish);
  EXPECT_FALSE(o.certify);
  // Every parameter was set above, to a value other than its default.
  const PlannerOptions defaults;
  std::set<std::string> changed;
  for (const auto& [name, value] : t.values(o)) {
    EXPECT_NE(value, t.at(name).get(defaults)) << name;
    changed.insert(name);
  }
  EXPECT_EQ(changed.size(), t.entries().size());
  EXPECT_NO_THROW(o.validate());
}

TEST(PlannerParameters, ValidateEnforcesTheDeclaredBounds) {
  PlannerOptions o;
  o.global.connectivity = 12;
  try {
    o.validate();
    FAIL() << "connectivity 12 accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "connectivity must be 8, 16 or 32, got 12");
  }
  PlannerOptions spacing;
  spacing.station_spacing = -1.0;
  EXPECT_THROW(spacing.validate(), InputError);
  EXPECT_NO_THROW(PlannerOptions{}.validate());
}

}  // namespace
}  // namespace talus
