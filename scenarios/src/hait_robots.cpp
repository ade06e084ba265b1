#include "talus/scenarios/hait_robots.hpp"

#include <string>

#include "talus/core/error.hpp"

namespace talus::scenarios {
namespace {

Robot load_robot_file(const std::filesystem::path& data_dir, const char* stem) {
  const std::filesystem::path file = data_dir / "robots" / (std::string(stem) + ".yaml");
  if (!std::filesystem::exists(file)) {
    throw InputError("the Hait experiments need the bundled robot " + file.string());
  }
  return load_robot(file);
}

}  // namespace

Robot load_hait_chassis(const std::filesystem::path& data_dir) {
  return load_robot_file(data_dir, "marsokhod_chassis");
}

Robot load_hait_wheeled(const std::filesystem::path& data_dir) {
  return load_robot_file(data_dir, "rover4_sprung");
}

}  // namespace talus::scenarios
