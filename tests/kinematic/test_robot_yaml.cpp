#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {
namespace {

const std::string kWheeled = R"(type: wheeled
name: test
wheels:
  - [0.6, 0.4]
  - [0.6, -0.4]
  - [-0.6, -0.4]
  - [-0.6, 0.4]
cg_height: 0.45
max_spring_extension: 0.12
max_roll: 0.35
max_pitch: 0.4
body:
  front: 0.75
  rear: 0.7
  half_width: 0.45
  clearance: 0.25
)";

const std::string kChassis = R"(type: articulated_chassis
half_axle_width: 0.45
axle_spacing: 0.6
max_axle_roll_difference: 0.35
max_roll: 0.4
min_pitch: -0.4
max_pitch: 0.4
min_body_angle: 2.64
max_body_angle: 3.64
body:
  half_width: 0.3
  clearance: 0.3
  overhang: 0.15
)";

/// `text` with the line starting with `prefix` replaced by `line` (removed if empty).
std::string edit(const std::string& text, const std::string& prefix, const std::string& line) {
  const std::size_t at = text.find(prefix);
  EXPECT_NE(at, std::string::npos) << prefix;
  const std::size_t end = text.find('\n', at);
  return text.substr(0, at) + (line.empty() ? "" : line + "\n") + text.substr(end + 1);
}

/// Parsing must throw InputError whose message names `key`.
void expect_error_naming(const std::string& yaml, const std::string& key) {
  try {
    parse_robot(yaml, "robot.yaml");
    ADD_FAILURE() << "no error for key " << key << " in\n" << yaml;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(key), std::string::npos) << "message '" << what << "' lacks " << key;
    EXPECT_NE(what.find("robot.yaml"), std::string::npos) << what;
  }
}

TEST(RobotYaml, ParsesWheeledRobot) {
  const Robot r = parse_robot(kWheeled);
  ASSERT_TRUE(std::holds_alternative<WheeledRobot>(r));
  const auto& w = std::get<WheeledRobot>(r);
  EXPECT_EQ(w.name, "test");
  ASSERT_EQ(w.wheels.size(), 4u);
  EXPECT_DOUBLE_EQ(w.wheels[1].x(), 0.6);
  EXPECT_DOUBLE_EQ(w.wheels[1].y(), -0.4);
  EXPECT_DOUBLE_EQ(w.cg_height, 0.45);
  EXPECT_DOUBLE_EQ(w.max_spring_extension, 0.12);
  EXPECT_DOUBLE_EQ(w.max_roll, 0.35);
  EXPECT_DOUBLE_EQ(w.max_pitch, 0.4);
  EXPECT_DOUBLE_EQ(w.body.front, 0.75);
  EXPECT_DOUBLE_EQ(w.body.rear, 0.7);
  EXPECT_DOUBLE_EQ(w.body.half_width, 0.45);
  EXPECT_DOUBLE_EQ(w.body.clearance, 0.25);
}

TEST(RobotYaml, ParsesChassis) {
  const Robot r = parse_robot(kChassis);
  ASSERT_TRUE(std::holds_alternative<ArticulatedChassis>(r));
  const auto& c = std::get<ArticulatedChassis>(r);
  EXPECT_DOUBLE_EQ(c.half_axle_width, 0.45);
  EXPECT_DOUBLE_EQ(c.axle_spacing, 0.6);
  EXPECT_DOUBLE_EQ(c.max_axle_roll_difference, 0.35);
  EXPECT_DOUBLE_EQ(c.min_pitch, -0.4);
  EXPECT_DOUBLE_EQ(c.max_body_angle, 3.64);
  EXPECT_DOUBLE_EQ(c.body.overhang, 0.15);
}

TEST(RobotYaml, BundledRobotFilesLoad) {
  const std::string dir = std::string(TALUS_DATA_DIR) + "/robots/";
  EXPECT_TRUE(std::holds_alternative<WheeledRobot>(load_robot(dir + "rover4_sprung.yaml")));
  EXPECT_TRUE(
      std::holds_alternative<ArticulatedChassis>(load_robot(dir + "marsokhod_chassis.yaml")));
}

TEST(RobotYaml, DuplicateKeysAndSecondDocumentsAreErrors) {
  // yaml-cpp alone would take the first max_roll and ignore the second document.
  expect_error_naming(kChassis + "max_roll: 0.1\n", "'max_roll' appears twice");
  expect_error_naming(edit(kWheeled, "  clearance:", "  clearance: 0.25\n  clearance: 0.2"),
                      "'clearance' appears twice");
  expect_error_naming(kChassis + "---\n" + kWheeled, "second YAML document");
}

TEST(RobotYaml, MissingFileIsInputError) {
  EXPECT_THROW(load_robot("/nonexistent/robot.yaml"), InputError);
}

TEST(RobotYaml, TypeKeyIsRequiredAndChecked) {
  expect_error_naming(edit(kWheeled, "type:", ""), "type");
  expect_error_naming(edit(kWheeled, "type:", "type: tracked"), "type");
  expect_error_naming("- 1\n- 2\n", "robot.yaml");
  expect_error_naming("type: [wheeled\n", "robot.yaml");
}

TEST(RobotYaml, UnknownKeysAreNamed) {
  expect_error_naming(kWheeled + "wheel_radius: 0.2\n", "wheel_radius");
  expect_error_naming(kChassis + "mass: 100\n", "mass");
  expect_error_naming(edit(kWheeled, "  clearance:", "  clearance: 0.25\n  height: 0.1"),
                      "body.height");
  expect_error_naming(edit(kChassis, "  overhang:", "  overhang: 0.1\n  front: 0.1"), "body.front");
  // A chassis key in a wheeled robot is unknown there.
  expect_error_naming(kWheeled + "axle_spacing: 0.6\n", "axle_spacing");
}

TEST(RobotYaml, MissingKeysAreNamed) {
  for (const std::string key :
       {"cg_height", "max_spring_extension", "max_roll", "max_pitch", "wheels"}) {
    std::string yaml = kWheeled;
    if (key == "wheels") {
      yaml = edit(yaml, "wheels:", "");
      for (int k = 0; k < 4; ++k) yaml = edit(yaml, "  - [", "");
    } else {
      yaml = edit(yaml, key + ":", "");
    }
    expect_error_naming(yaml, key);
  }
  for (const std::string key : {"front", "rear", "half_width", "clearance"})
    expect_error_naming(edit(kWheeled, "  " + key + ":", ""), "body." + key);
  for (const std::string key :
       {"half_axle_width", "axle_spacing", "max_axle_roll_difference", "max_roll", "min_pitch",
        "max_pitch", "min_body_angle", "max_body_angle"})
    expect_error_naming(edit(kChassis, key + ":", ""), key);
  for (const std::string key : {"half_width", "clearance", "overhang"})
    expect_error_naming(edit(kChassis, "  " + key + ":", ""), "body." + key);
}

TEST(RobotYaml, WrongTypesAreNamed) {
  expect_error_naming(edit(kWheeled, "cg_height:", "cg_height: tall"), "cg_height");
  expect_error_naming(edit(kWheeled, "max_roll:", "max_roll: [1, 2]"), "max_roll");
  expect_error_naming(edit(kWheeled, "  - [0.6, -0.4]", "  - [0.6, left]"), "wheels[1]");
  expect_error_naming(edit(kWheeled, "  - [0.6, -0.4]", "  - [0.6, -0.4, 0.1]"), "wheels[1]");
  expect_error_naming(kWheeled.substr(0, kWheeled.find("body:")) + "body: 3\n", "body");
  expect_error_naming(edit(kChassis, "axle_spacing:", "axle_spacing: {a: 1}"), "axle_spacing");
  expect_error_naming(edit(kChassis, "  clearance:", "  clearance: low"), "body.clearance");
}

TEST(RobotYaml, NonPositiveSizesAndBadAnglesAreNamed) {
  for (const std::string& value : std::vector<std::string>{"0", "-0.1", ".nan", ".inf"}) {
    expect_error_naming(edit(kWheeled, "cg_height:", "cg_height: " + value), "cg_height");
    expect_error_naming(edit(kWheeled, "max_spring_extension:", "max_spring_extension: " + value),
                        "max_spring_extension");
    expect_error_naming(edit(kWheeled, "  front:", "  front: " + value), "body.front");
    expect_error_naming(edit(kChassis, "half_axle_width:", "half_axle_width: " + value),
                        "half_axle_width");
    expect_error_naming(edit(kChassis, "axle_spacing:", "axle_spacing: " + value), "axle_spacing");
    expect_error_naming(edit(kChassis, "  half_width:", "  half_width: " + value),
                        "body.half_width");
  }
  expect_error_naming(edit(kChassis, "  overhang:", "  overhang: -0.1"), "body.overhang");
  expect_error_naming(edit(kWheeled, "max_roll:", "max_roll: 1.6"), "max_roll");
  expect_error_naming(edit(kWheeled, "max_pitch:", "max_pitch: 0"), "max_pitch");
  expect_error_naming(edit(kChassis, "min_pitch:", "min_pitch: 0.1"), "min_pitch");
  expect_error_naming(edit(kChassis, "max_pitch:", "max_pitch: -0.1"), "max_pitch");
  expect_error_naming(edit(kChassis, "min_body_angle:", "min_body_angle: 3.2"), "min_body_angle");
  expect_error_naming(edit(kChassis, "max_body_angle:", "max_body_angle: 3.0"), "max_body_angle");
  expect_error_naming(edit(kChassis, "max_axle_roll_difference:", "max_axle_roll_difference: 0"),
                      "max_axle_roll_difference");
}

TEST(RobotYaml, WheelLayoutIsChecked) {
  // Two wheels only.
  std::string two = kWheeled;
  two = edit(two, "  - [-0.6, -0.4]", "");
  two = edit(two, "  - [-0.6, 0.4]", "");
  expect_error_naming(two, "wheels");
  // Collinear wheels leave the contact plane undefined.
  std::string line = kWheeled;
  line = edit(line, "  - [0.6, 0.4]", "  - [0.6, 0.0]");
  line = edit(line, "  - [0.6, -0.4]", "  - [0.2, 0.0]");
  line = edit(line, "  - [-0.6, -0.4]", "  - [-0.6, 0.0]");
  line = edit(line, "  - [-0.6, 0.4]", "  - [-0.2, 0.0]");
  expect_error_naming(line, "collinear");
  expect_error_naming(edit(kWheeled, "wheels:", "wheels: 4"), "wheels");
}

TEST(RobotYaml, ValidateRejectsBadModelsBuiltInCode) {
  WheeledRobot w;
  EXPECT_THROW(w.validate(), InputError);  // no wheels
  w.wheels = {{0.5, 0.3}, {0.5, -0.3}, {-0.5, 0.0}};
  EXPECT_NO_THROW(w.validate());
  w.body.clearance = 0.0;
  EXPECT_THROW(validate(Robot(w)), InputError);
  ArticulatedChassis c;
  EXPECT_NO_THROW(c.validate());
  c.min_body_angle = std::numbers::pi;
  EXPECT_THROW(validate(Robot(c)), InputError);
}

}  // namespace
}  // namespace talus
