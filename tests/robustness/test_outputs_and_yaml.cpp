// Hardening, second round (issue 39), the library's side of two severe
// families:
// - outputs: every writer goes through write_file_atomically(), which never
//   replaces anything but a regular file (a private mknod copy of /dev/null,
//   never the real one: these tests run as root), and leaves the previous file
//   and no temporary behind when the disk is full (a small tmpfs, root only);
// - YAML: cyclic aliases, alias bombs and deep nesting are one InputError
//   each, quickly, for every reader (vehicles here; robots and sweeps share
//   load_strict_yaml).
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/output_file.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("talus_outputs_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Files in `dir` whose name holds the temporary marker.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".talus-tmp-") != std::string::npos) ++n;
  }
  return n;
}

/// Expects every writer to refuse `target` with an InputError naming `what`,
/// and `target` to be left exactly as `before` (type and device numbers).
void expect_refused_and_untouched(const fs::path& target, const std::string& what) {
  struct stat before {};
  ASSERT_EQ(::lstat(target.c_str(), &before), 0);
  ElevationGrid grid(3, 3, 1.0, 0.0, 0.0);
  const auto check = [&](const std::function<void()>& write, const char* writer) {
    try {
      write();
      ADD_FAILURE() << writer << " wrote onto " << target;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << writer << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
    struct stat after {};
    ASSERT_EQ(::lstat(target.c_str(), &after), 0) << writer << " removed " << target;
    EXPECT_EQ(after.st_mode, before.st_mode) << writer;
    EXPECT_EQ(after.st_rdev, before.st_rdev) << writer;
    EXPECT_EQ(after.st_ino, before.st_ino) << writer << " replaced " << target;
  };
  check([&] { write_text_file(target, "x\n"); }, "write_text_file");
  check([&] { write_esri_ascii(grid, target.string()); }, "write_esri_ascii");
  check([&] { require_regular_output(target, "-o"); }, "require_regular_output");
  EXPECT_EQ(temporaries_in(target.parent_path()), 0) << "a temporary was left beside " << target;
}

TEST(OutputFiles, ACharacterDeviceIsNeverReplaced) {
  // A private copy of /dev/null (major 1, minor 3), so the real one is never at risk.
  const fs::path node = scratch() / "null";
  fs::remove(node);
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    GTEST_SKIP() << "mknod needs root (CAP_MKNOD): the device case is not run";
  }
  expect_refused_and_untouched(node, "a character device");
  // A symbolic link to it is the device too.
  const fs::path link = scratch() / "link_to_null";
  fs::remove(link);
  fs::create_symlink(node, link);
  expect_refused_and_untouched(link, "a character device");
  struct stat info {};
  ASSERT_EQ(::stat(node.c_str(), &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
}

TEST(OutputFiles, AFifoASocketAndAFolderAreRefused) {
  const fs::path fifo = scratch() / "out.fifo";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused_and_untouched(fifo, "a FIFO");

  const fs::path socket_path = scratch() / "out.sock";
  fs::remove(socket_path);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.string().size(), sizeof address.sun_path);
  std::strncpy(address.sun_path, socket_path.c_str(), sizeof address.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  expect_refused_and_untouched(socket_path, "a socket");
  ::close(fd);

  const fs::path folder = scratch() / "out_folder";
  fs::create_directories(folder);
  expect_refused_and_untouched(folder, "a folder");
}

TEST(OutputFiles, ARegularFileIsReplacedWholeAndALinkIsKept) {
  const fs::path file = scratch() / "data.txt";
  write_text_file(file, "old\n");
  write_text_file(file, "new\n");
  EXPECT_EQ(read_all(file), "new\n");
  const fs::path link = scratch() / "data_link.txt";
  fs::remove(link);
  fs::create_symlink(file, link);
  write_text_file(link, "through the link\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_all(file), "through the link\n");
  EXPECT_EQ(temporaries_in(scratch()), 0);
}

TEST(OutputFiles, AFullDiskKeepsThePreviousFileAndLeavesNoTemporary) {
  const fs::path mount_point = scratch() / "small_tmpfs";
  fs::create_directories(mount_point);
  if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "mounting a tmpfs needs root (CAP_SYS_ADMIN): the full-disk case is not run";
  }
  struct Unmount {
    fs::path at;
    ~Unmount() { ::umount2(at.c_str(), MNT_DETACH); }
  } unmount{mount_point};
  const fs::path file = mount_point / "grid.asc";
  ElevationGrid small(3, 3, 1.0, 0.0, 0.0);
  write_esri_ascii(small, file.string());
  const std::string previous = read_all(file);
  ASSERT_FALSE(previous.empty());

  ElevationGrid large(200, 200, 1.0, 0.0, 0.0);  // about 300 kB of text: does not fit
  for (std::size_t j = 0; j < 200; ++j)
    for (std::size_t i = 0; i < 200; ++i) large.at(i, j) = 1000.0 + 1e-3 * double(i * j);
  EXPECT_THROW(write_esri_ascii(large, file.string()), Error);
  EXPECT_THROW(write_text_file(file, std::string(300'000, 'x')), Error);
  EXPECT_EQ(read_all(file), previous) << "the previous grid was damaged";
  EXPECT_EQ(temporaries_in(mount_point), 0) << "a temporary was left on the full disk";
}

// ---- YAML ----------------------------------------------------------------

/// Parses `yaml` as a vehicle; expects one InputError containing `fragment`
/// within a second.
void expect_vehicle_refused(const std::string& yaml, const std::string& fragment) {
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)parse_vehicle(yaml, "hostile.yaml");
    ADD_FAILURE() << "accepted:\n" << yaml.substr(0, 300);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("hostile.yaml:", 0), 0u) << e.what();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.0) << "took " << seconds << " s";
}

TEST(StrictYaml, ACyclicAliasIsRefusedNotFollowed) {
  expect_vehicle_refused("x: &a [1, *a]\n", "cycle");
  expect_vehicle_refused("model: point_mass\nmass: &m {a: *m}\n", "cycle");
  expect_vehicle_refused("a: &top\n  b:\n    c: [*top]\n", "cycle");
}

TEST(StrictYaml, AnAliasBombIsRefusedWithinTheNodeBudget) {
  // Nine levels of ten aliases each: 10^9 nodes expanded from 1.6 kB.
  std::string yaml = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 9; ++level) {
    const std::string previous = "*l" + std::to_string(level - 1);
    yaml += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) yaml += (k ? ", " : "") + previous;
    yaml += "]\n";
  }
  expect_vehicle_refused(yaml, "aliases expanded");
}

TEST(StrictYaml, DeepNestingIsRefused) {
  expect_vehicle_refused("x: " + std::string(500, '[') + std::string(500, ']') + "\n",
                         "levels deep");
}

TEST(StrictYaml, AcyclicAliasesWithinTheBudgetStillLoad) {
  // An anchor reused by an alias is legitimate YAML: the vehicle loads.
  const Vehicle v = parse_vehicle(
      "model: point_mass\nfriction: &mu 0.6\ncg_height: 0.5\nhalf_track: 0.8\nmax_speed: 10\n"
      "max_accel: &a 3\nmax_decel: *a\n",
      "aliases.yaml");
  EXPECT_DOUBLE_EQ(v.friction, 0.6);
  EXPECT_DOUBLE_EQ(v.max_decel, 3.0);
}

}  // namespace
}  // namespace talus
