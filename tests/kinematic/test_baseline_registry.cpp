// The baseline registry and text options: names, lookup, registration rules,
// typed reading of options, statuses and the brief report.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/kinematic/baseline_registry.hpp"

namespace talus {
namespace {

/// A stand-in planner: every pose is valid, every query found as a straight line.
class LinePlanner final : public BaselinePlanner {
 public:
  std::string name() const override { return "line"; }
  std::vector<BaselineSetting> settings() const override { return {}; }
  ValidityFunction validity(const RuledTerrain&) const override {
    return [](const SE2Pose&) { return ConfigurationCheck{true, 1.0, 0}; };
  }

 protected:
  BaselineResult solve(const RuledTerrain&, const SE2Pose& start,
                       const SE2Pose& goal) const override {
    BaselineResult r;
    r.status = BaselineStatus::kFound;
    r.message = "straight";
    r.path = {start, goal};
    r.length_m = (goal.position() - start.position()).norm();
    r.counters = {{"poses", 2}};
    return r;
  }
};

BaselineEntry line_entry() {
  return {"line", "a straight line", {{"budget", "10", "unused"}}, [](const BaselineOptions&) {
            return std::make_unique<LinePlanner>();
          }};
}

TEST(BaselineRegistry, BuiltinListsHaitFirst) {
  const std::vector<std::string> names = BaselineRegistry::builtin().names();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "hait");
  for (const std::string& n : names) {
    EXPECT_EQ(BaselineRegistry::builtin().entry(n).name, n);
    EXPECT_FALSE(BaselineRegistry::builtin().entry(n).summary.empty()) << n;
  }
}

TEST(BaselineRegistry, UnknownNameListsTheRegisteredOnes) {
  try {
    (void)BaselineRegistry::builtin().entry("dijkstra");
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hait"), std::string::npos) << e.what();
  }
}

TEST(BaselineRegistry, AddRefusesDuplicatesMissingFactoriesAndMissingBudgets) {
  BaselineRegistry r;
  r.add(line_entry());
  EXPECT_EQ(r.names(), std::vector<std::string>{"line"});
  EXPECT_THROW(r.add(line_entry()), InputError);
  BaselineEntry no_factory = line_entry();
  no_factory.name = "other";
  no_factory.make = nullptr;
  EXPECT_THROW(r.add(no_factory), InputError);
  BaselineEntry no_budget = line_entry();
  no_budget.name = "other";
  no_budget.options.clear();
  EXPECT_THROW(r.add(no_budget), InputError);
  BaselineEntry unnamed = line_entry();
  unnamed.name.clear();
  EXPECT_THROW(r.add(unnamed), InputError);
}

TEST(BaselinePlanner, PlanChecksTheQueryBeforeSolving) {
  const RuledTerrain terrain(ElevationGrid(5, 5, 1.0, 0.0, 0.0, 0.0));
  const LinePlanner p;
  const BaselineResult r = p.plan(terrain, {0, 0, 0}, {4, 3, 0});
  EXPECT_TRUE(r.found());
  EXPECT_DOUBLE_EQ(r.length_m, 5.0);
  EXPECT_THROW(p.plan(terrain, {0, 0, 0}, {5, 3, 0}), InputError);
  EXPECT_THROW(p.plan(terrain, {0, 0, std::nan("")}, {4, 3, 0}), InputError);
  ElevationGrid holed(5, 5, 1.0, 0.0, 0.0, 0.0);
  holed.set_void(2, 2);
  EXPECT_THROW(p.plan(RuledTerrain(holed), {2, 2, 0}, {4, 3, 0}), InputError);
}

TEST(BaselineResult, DefaultsShowAnUnfilledResultAndTheReportSaysWhatHappened) {
  const BaselineResult unfilled;
  EXPECT_FALSE(unfilled.found());
  EXPECT_NE(unfilled.brief_report().find("not called"), std::string::npos);
  BaselineResult r;
  r.status = BaselineStatus::kBudgetExceeded;
  r.message = "node budget of 5 nodes exhausted";
  r.counters = {{"nodes_created", 5}};
  const std::string report = r.brief_report();
  for (const char* part : {"budget_exceeded", "nodes_created 5", "node budget of 5"}) {
    EXPECT_NE(report.find(part), std::string::npos) << part << " not in " << report;
  }
}

TEST(BaselineStatus, ToStringNamesEveryStatus) {
  EXPECT_EQ(to_string(BaselineStatus::kFound), "found");
  EXPECT_EQ(to_string(BaselineStatus::kNoPath), "no_path");
  EXPECT_EQ(to_string(BaselineStatus::kStartInvalid), "start_invalid");
  EXPECT_EQ(to_string(BaselineStatus::kGoalInvalid), "goal_invalid");
  EXPECT_EQ(to_string(BaselineStatus::kBudgetExceeded), "budget_exceeded");
}

std::vector<BaselineOptionSpec> specs() {
  return {{"name", "", "required text", false, true},
          {"weight", "1.5", "a number in [0, 2]"},
          {"budget", "7", "a count"},
          {"verbose", "false", "a flag", true},
          {"pair", "", "two numbers"}};
}

TEST(BaselineOptionReader, ReadsDefaultsAndGivenValues) {
  const BaselineOptionReader d(specs(), {{"name", "x"}});
  EXPECT_EQ(d.text("name"), "x");
  EXPECT_DOUBLE_EQ(d.number("weight", 0, 2), 1.5);
  EXPECT_EQ(d.count("budget", 1), 7u);
  EXPECT_FALSE(d.flag("verbose"));
  EXPECT_TRUE(d.numbers("pair", 2).empty());
  const BaselineOptionReader g(specs(), {{"name", "x"},
                                         {"weight", " 0.25 "},
                                         {"budget", "12"},
                                         {"verbose", "true"},
                                         {"pair", "0.1, -2"}});
  EXPECT_DOUBLE_EQ(g.number("weight", 0, 2), 0.25);
  EXPECT_EQ(g.count("budget", 1), 12u);
  EXPECT_TRUE(g.flag("verbose"));
  EXPECT_EQ(g.numbers("pair", 2), (std::vector<double>{0.1, -2.0}));
}

TEST(BaselineOptionReader, NamesTheKeyOfEveryBadValue) {
  EXPECT_THROW(BaselineOptionReader(specs(), {}), BaselineOptionError);  // name is required
  const auto key_of = [](const BaselineOptions& o, auto read) {
    try {
      BaselineOptions all = o;
      all.emplace("name", "x");
      read(BaselineOptionReader(specs(), all));
    } catch (const BaselineOptionError& e) {
      EXPECT_NE(std::string(e.what()).find(e.key()), std::string::npos);
      return e.key();
    }
    return std::string("(no throw)");
  };
  EXPECT_EQ(key_of({{"colour", "red"}}, [](const auto&) {}), "colour");
  EXPECT_EQ(key_of({{"weight", "3"}}, [](const auto& r) { r.number("weight", 0, 2); }), "weight");
  EXPECT_EQ(key_of({{"weight", "nan"}}, [](const auto& r) { r.number("weight", 0, 2); }), "weight");
  EXPECT_EQ(key_of({{"budget", "0"}}, [](const auto& r) { r.count("budget", 1); }), "budget");
  EXPECT_EQ(key_of({{"budget", "-3"}}, [](const auto& r) { r.count("budget", 1); }), "budget");
  EXPECT_EQ(key_of({{"verbose", "yes"}}, [](const auto& r) { r.flag("verbose"); }), "verbose");
  EXPECT_EQ(key_of({{"pair", "1"}}, [](const auto& r) { r.numbers("pair", 2); }), "pair");
  EXPECT_EQ(key_of({{"pair", "1,2,3"}}, [](const auto& r) { r.numbers("pair", 2); }), "pair");
  EXPECT_EQ(key_of({{"pair", "1,,2"}}, [](const auto& r) { r.numbers("pair", 2); }), "pair");
}

}  // namespace
}  // namespace talus
