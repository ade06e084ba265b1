// End-to-end tests of `talus placement`: on a level plane at height h the
// sprung six-wheel robot stands at z = h + cg_height with every spring at
// rest, the chassis' middle axle at z = h, both level; on a tilted plane the
// attitude is the plane's, in closed form (rigid body: pitch = atan(s_u),
// roll = asin(s_v / sqrt(1 + s_u^2 + s_v^2)); chassis: every axle roll =
// atan(s_v), pitch = atan(s_u)); a slope beyond the roll limit is invalid for
// that reason; bad input exits 1 with one stderr line and no output file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace talus::cli_test {
namespace {

std::string six_wheel() {
  return data_file("robots/dacre_wright_six_wheel.yaml");
}
std::string chassis() {
  return data_file("robots/marsokhod_chassis.yaml");
}

/// 20 m x 20 m at 0.5 m, centre (10, 10) at height z0, slope along `aspect`.
std::string plane(const std::string& name, double slope, double aspect, double z0) {
  return generate_terrain(name, "plane --ncols 41 --nrows 41 --cellsize 0.5 --slope " +
                                    std::to_string(slope) + " --aspect " + std::to_string(aspect) +
                                    " --z0 " + std::to_string(z0));
}

std::string configs(const std::string& name, const std::string& rows) {
  const std::string file = scratch_file(name);
  write_text(file, "x,y,theta\n" + rows);
  return file;
}

const std::string kWheeledHeader =
    "x,y,theta,z,roll,pitch,extension_1,extension_2,extension_3,extension_4,extension_5,"
    "extension_6,valid,reason";
const std::string kChassisHeader =
    "x,y,theta,z,roll,pitch,roll_front,roll_middle,roll_rear,pitch_front,pitch_rear,valid,reason";

std::vector<std::vector<std::string>> place(const std::string& terrain, const std::string& robot,
                                            const std::string& config_file,
                                            const std::string& header, nlohmann::json* summary) {
  const std::string out = scratch_file("placement_out.csv");
  std::filesystem::remove(out);
  const RunResult r =
      run_talus("placement --terrain " + quoted(terrain) + " --robot " + quoted(robot) +
                " --configs " + quoted(config_file) + " -o " + quoted(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  if (summary) *summary = parse_json(r.out, "stdout");
  return read_csv(out, header);
}

TEST(CliPlacement, LevelPlaneGivesRestingSpringsAndTheDocumentedHeight) {
  const double h = 1.25;
  const std::string terrain = plane("placement_level.asc", 0.0, 0.0, h);
  const std::string c = configs("level.csv", "10,10,0\n7.5,12,1.3\n12,8,-2.8\n");
  nlohmann::json summary;
  const auto rows = place(terrain, six_wheel(), c, kWheeledHeader, &summary);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(summary.value("valid", 0), 3);
  EXPECT_EQ(summary.value("robot_kind", ""), "wheeled");
  EXPECT_DOUBLE_EQ(parse_number(rows[1][0]), 7.5);
  EXPECT_DOUBLE_EQ(parse_number(rows[1][2]), 1.3);
  for (const auto& row : rows) {
    EXPECT_NEAR(parse_number(row[3]), h + 0.5, 1e-12);  // cg_height 0.5
    EXPECT_NEAR(parse_number(row[4]), 0.0, 1e-12);
    EXPECT_NEAR(parse_number(row[5]), 0.0, 1e-12);
    for (int j = 6; j < 12; ++j) EXPECT_NEAR(parse_number(row[j]), 0.0, 1e-12);
    EXPECT_EQ(row[12], "1");
    EXPECT_EQ(row[13], "none");
  }
  const auto crows = place(terrain, chassis(), c, kChassisHeader, &summary);
  ASSERT_EQ(crows.size(), 3u);
  EXPECT_EQ(summary.value("robot_kind", ""), "articulated_chassis");
  for (const auto& row : crows) {
    EXPECT_NEAR(parse_number(row[3]), h, 1e-12);
    for (int j = 4; j < 11; ++j) EXPECT_NEAR(parse_number(row[j]), 0.0, 1e-12) << j;
    EXPECT_EQ(row[11], "1");
    EXPECT_EQ(row[12], "none");
  }
}

TEST(CliPlacement, TiltedPlaneGivesTheAnalyticAttitude) {
  const double slope = 0.2, aspect = 0.5, z0 = 2.0;
  const std::string terrain = plane("placement_tilted.asc", slope, aspect, z0);
  const std::vector<std::array<double, 3>> qs = {{10, 10, 0.0}, {8, 11, 1.0}, {11.5, 9, 2.5}};
  std::string text;
  for (const auto& q : qs)
    text += std::to_string(q[0]) + "," + std::to_string(q[1]) + "," + std::to_string(q[2]) + "\n";
  const std::string c = configs("tilted.csv", text);
  const auto rows = place(terrain, six_wheel(), c, kWheeledHeader, nullptr);
  const auto crows = place(terrain, chassis(), c, kChassisHeader, nullptr);
  ASSERT_EQ(rows.size(), qs.size());
  ASSERT_EQ(crows.size(), qs.size());
  const double g = std::tan(slope);
  for (std::size_t k = 0; k < qs.size(); ++k) {
    const double th = qs[k][2];
    const double su = g * std::cos(th - aspect);  // slope along the heading
    const double sv = g * std::sin(aspect - th);  // slope to the left
    const double zq =
        z0 + g * ((qs[k][0] - 10) * std::cos(aspect) + (qs[k][1] - 10) * std::sin(aspect));
    // Rigid body: the rest plane is the terrain plane; G is cg_height along its normal.
    EXPECT_NEAR(parse_number(rows[k][3]), zq + 0.5 / std::cos(slope), 1e-9) << k;
    EXPECT_NEAR(parse_number(rows[k][4]), std::asin(sv / std::sqrt(1 + su * su + sv * sv)), 1e-9)
        << k;
    EXPECT_NEAR(parse_number(rows[k][5]), std::atan(su), 1e-9) << k;
    for (int j = 6; j < 12; ++j) EXPECT_NEAR(parse_number(rows[k][j]), 0.0, 1e-9);
    EXPECT_EQ(rows[k][12], "1");
    // Chassis: each axle rolls by the lateral slope, the axle line pitches by the longitudinal.
    EXPECT_NEAR(parse_number(crows[k][3]), zq, 1e-9) << k;
    EXPECT_NEAR(parse_number(crows[k][4]), std::atan(sv), 1e-9) << k;
    EXPECT_NEAR(parse_number(crows[k][5]), std::atan(su), 1e-9) << k;
    for (int j = 6; j < 9; ++j) EXPECT_NEAR(parse_number(crows[k][j]), std::atan(sv), 1e-9) << k;
    EXPECT_NEAR(parse_number(crows[k][9]), std::atan(su), 1e-9) << k;
    EXPECT_NEAR(parse_number(crows[k][10]), -std::atan(su), 1e-9) << k;
    EXPECT_EQ(crows[k][11], "1");
  }
}

TEST(CliPlacement, SteepCrossSlopeAndOffMapWheelsAreInvalidWithTheirReason) {
  // 0.5 rad across the heading: the roll (about 0.5) is past the limit 0.35.
  const std::string terrain = plane("placement_steep.asc", 0.5, 1.5707963267948966, 0.0);
  const std::string c = configs("steep.csv", "10,10,0\n0.2,10,0\n");
  nlohmann::json summary;
  const auto rows = place(terrain, six_wheel(), c, kWheeledHeader, &summary);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_GT(parse_number(rows[0][4]), 0.35);
  EXPECT_EQ(rows[0][12], "0");
  EXPECT_EQ(rows[0][13], "roll");
  EXPECT_EQ(rows[1][3], "nan");
  EXPECT_EQ(rows[1][12], "0");
  EXPECT_EQ(rows[1][13], "off_map");
  EXPECT_EQ(summary.value("valid", -1), 0);
  EXPECT_EQ(summary["invalid_reasons"].value("roll", 0), 1);
  EXPECT_EQ(summary["invalid_reasons"].value("off_map", 0), 1);
}

TEST(CliPlacement, BadInputExitsOneWithOneLineAndNoFile) {
  const std::string terrain = plane("placement_bad.asc", 0.0, 0.0, 0.0);
  const std::string out = scratch_file("placement_never.csv");
  std::filesystem::remove(out);
  const auto write = [](const std::string& name, const std::string& text) {
    const std::string file = scratch_file(name);
    write_text(file, text);
    return file;
  };
  const std::string base = "--terrain " + quoted(terrain) + " --robot " + quoted(six_wheel());
  const std::string o = " -o " + quoted(out);
  expect_bad_input(
      "placement",
      {{base + " --configs " + quoted(write("h.csv", "x,y\n1,2\n")) + o, "header 'x,y,theta'"},
       {base + " --configs " + quoted(write("n.csv", "x,y,theta\n1,2,north\n")) + o,
        "n.csv:2: theta value 'north' is not a finite number"},
       {base + " --configs " + quoted(write("nan.csv", "x,y,theta\n1,2,0\n1,nan,0\n")) + o,
        "nan.csv:3: y value"},
       {base + " --configs " + quoted(write("c.csv", "x,y,theta\n1,2,0,4\n")) + o,
        "c.csv:2: expected 3 columns"},
       {base + " --configs " + quoted(write("off.csv", "x,y,theta\n5,5,0\n25,5,0\n")) + o,
        "off.csv:3: (25, 5) is off the terrain"},
       {base + " --configs " + quoted(write("e.csv", "")) + o, "empty file"},
       {base + " --configs " + quoted(write("only.csv", "x,y,theta\n")) + o, "no configuration"},
       {base + " --configs " + quoted(scratch_file("missing.csv")) + o, "missing.csv"},
       {"--terrain " + quoted(terrain) + " --robot " + quoted(scratch_file("nobody.yaml")) +
            " --configs " + quoted(write("ok.csv", "x,y,theta\n5,5,0\n")) + o,
        "nobody.yaml"}},
      out);
  // 8 x 10^6 configurations reached 1.2 GB: the reader stops at the first one beyond 10^6.
  std::string many = "x,y,theta\n";
  many.reserve(7 * 1'000'002);
  for (int k = 0; k <= 1'000'000; ++k) many += "5,5,0\n";
  expect_bad_input("placement",
                   {{base + " --configs " + quoted(write("many.csv", many)) + o,
                     "many.csv:1000002: more than 1000000 configurations"}},
                   out);
}

}  // namespace
}  // namespace talus::cli_test
