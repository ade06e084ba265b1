// The declared parameter table on a toy options struct: defaults are the
// struct's, values round-trip through text, bounds are enforced with the
// parameter named as the caller spells it, and nested members are reached.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/parameter_table.hpp"

namespace talus {
namespace {

enum class Shade { kLight, kDark };
const char* shade_name(Shade s) {
  return s == Shade::kLight ? "light" : "dark";
}
Shade parse_shade(const std::string& name) {
  if (name == "light") return Shade::kLight;
  if (name == "dark") return Shade::kDark;
  throw InputError("unknown shade '" + name + "'");
}

struct Inner {
  int count = 3;
  std::vector<std::size_t> sizes;
};
struct Toy {
  Inner inner;
  double spacing = 0.5;
  double budget = std::numeric_limits<double>::infinity();
  bool fast = true;
  Shade shade = Shade::kLight;
};

const ParameterTable<Toy>& toy_table() {
  static const ParameterTable<Toy> table(
      "Toy", {integer_parameter<Toy>(
                  "count", [](auto& o) -> auto& { return o.inner.count; }, 1, 10, "how many"),
              integer_list_parameter<Toy>(
                  "sizes", [](auto& o) -> auto& { return o.inner.sizes; }, 4, 64, "sizes"),
              real_parameter<Toy>(
                  "spacing", [](auto& o) -> auto& { return o.spacing; }, 0.0,
                  std::numeric_limits<double>::infinity(), "[m]"),
              real_parameter<Toy>(
                  "budget", [](auto& o) -> auto& { return o.budget; }, 0.0,
                  std::numeric_limits<double>::infinity(), "[s]", true, true),
              flag_parameter<Toy>(
                  "fast", [](auto& o) -> auto& { return o.fast; }, "go fast"),
              choice_parameter<Toy>(
                  "shade", [](auto& o) -> auto& { return o.shade; }, {"light", "dark"}, shade_name,
                  parse_shade, "the shade")});
  return table;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParameterTable, DefaultsAreTheStructsOwn) {
  const auto& t = toy_table();
  EXPECT_EQ(ParameterTable<Toy>::default_value(t.at("count")), ParameterValue(3LL));
  EXPECT_EQ(ParameterTable<Toy>::default_value(t.at("fast")), ParameterValue(true));
  EXPECT_EQ(ParameterTable<Toy>::default_value(t.at("shade")),
            ParameterValue(std::string("light")));
  EXPECT_EQ(value_text(ParameterTable<Toy>::default_value(t.at("budget"))), "inf");
  EXPECT_NO_THROW(t.check(Toy{}));
}

TEST(ParameterTable, TextSetsNestedMembersAndRoundTrips) {
  const auto& t = toy_table();
  Toy toy;
  t.set_text(toy, "count", "7");
  t.set_text(toy, "sizes", "8,16, 32");
  t.set_text(toy, "spacing", "0.125");
  t.set_text(toy, "budget", "2.5");
  t.set_text(toy, "fast", "false");
  t.set_text(toy, "shade", "dark");
  EXPECT_EQ(toy.inner.count, 7);
  EXPECT_EQ(toy.inner.sizes, (std::vector<std::size_t>{8, 16, 32}));
  EXPECT_EQ(toy.spacing, 0.125);
  EXPECT_EQ(toy.budget, 2.5);
  EXPECT_FALSE(toy.fast);
  EXPECT_EQ(toy.shade, Shade::kDark);
  // Every value's text sets the same value again.
  Toy copy;
  for (const auto& [name, value] : t.values(toy)) t.set_text(copy, name, value_text(value));
  EXPECT_EQ(t.values(copy), t.values(toy));
  t.set_text(copy, "sizes", "0");  // a single 0 is none
  EXPECT_TRUE(copy.inner.sizes.empty());
}

TEST(ParameterTable, BoundsAreEnforcedAndNamedAsSpelled) {
  const auto& t = toy_table();
  Toy toy;
  EXPECT_EQ(error_of([&] { t.set_text(toy, "count", "11"); }),
            "--count must be an integer in [1, 10], got 11");
  EXPECT_EQ(error_of([&] { t.set(toy, "count", 0LL); }),
            "count must be an integer in [1, 10], got 0");
  EXPECT_EQ(error_of([&] { t.set_text(toy, "sizes", "8,65"); }),
            "--sizes must each be in [4, 64] (or a single 0 for none), got 65");
  EXPECT_EQ(error_of([&] { t.set_text(toy, "spacing", "inf"); }),
            "--spacing must be a number >= 0, got inf");
  EXPECT_EQ(error_of([&] { t.set_text(toy, "budget", "0"); }),
            "--budget must be a number > 0 (inf = none), got 0");
  EXPECT_EQ(error_of([&] { t.set_text(toy, "shade", "grey"); }), "--shade: unknown shade 'grey'");
  EXPECT_EQ(error_of([&] { t.set_text(toy, "count", "3.5"); }),
            "--count must be an integer in [1, 10], got '3.5'");
  EXPECT_EQ(error_of([&] { t.set(toy, "count", 2.0); }),
            "count must be an integer in [1, 10], got 2");
  EXPECT_NE(error_of([&] { t.set(toy, "colour", 2.0); }).find("its parameters: count, sizes"),
            std::string::npos);
  EXPECT_EQ(toy.inner.count, 3) << "a refused value leaves the options as they were";
  toy.spacing = std::nan("");
  EXPECT_EQ(error_of([&] { t.check(toy); }), "spacing must be a number >= 0, got nan");
}

TEST(ParameterTable, CliSpellingOfDefaultTrueFlagsIsNo) {
  const auto& t = toy_table();
  EXPECT_EQ(ParameterTable<Toy>::spelled(t.at("fast"), ParameterSpelling::kCli), "--no-fast");
  EXPECT_EQ(ParameterTable<Toy>::spelled(t.at("budget"), ParameterSpelling::kCli), "--budget");
  EXPECT_EQ(cli_spelling("more_control_points"), "--more-control-points");
}

}  // namespace
}  // namespace talus
