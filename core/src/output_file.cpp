#include "talus/core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <system_error>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {
  return printable(path.string(), 200);
}

/// What a non-regular file is, for the message.
std::string kind_of(const struct stat& info) {
  if (S_ISDIR(info.st_mode)) return "a folder";
  if (S_ISCHR(info.st_mode)) return "a character device";
  if (S_ISBLK(info.st_mode)) return "a block device";
  if (S_ISFIFO(info.st_mode)) return "a FIFO";
  if (S_ISSOCK(info.st_mode)) return "a socket";
  return "not a regular file";
}

/// The file a write to `path` replaces: `path` itself, or what its symbolic
/// link points to (so the link survives and its target is written).
fs::path resolved_target(const fs::path& path) {
  std::error_code error;
  if (!fs::is_symlink(path, error)) return path;
  const fs::path target = fs::weakly_canonical(path, error);
  return error ? path : target;
}

/// A temporary name beside `target`, unique per process and call (two
/// threads writing one target never share a temporary).
fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += ".talus-tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return target.parent_path() / name;
}

/// fsync of a closed file, so the rename publishes data that is on disk.
void sync_file(const fs::path& file, const fs::path& target) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    throw Error("writing " + quoted(target) + " failed: " + std::strerror(errno));
  }
  const int synced = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  // EINVAL/EROFS: the file system cannot sync (a pipe-like mount); the data
  // is written, only not forced to disk.
  if (synced != 0 && saved != EINVAL && saved != EROFS) {
    throw Error("writing " + quoted(target) + " failed: " + std::strerror(saved));
  }
}

}  // namespace

namespace {

/// The (device, inode) of every protected input, and its name for messages.
struct ProtectedInputs {
  std::mutex mutex;
  std::map<std::pair<dev_t, ino_t>, std::string> files;
};

ProtectedInputs& protected_inputs() {
  static ProtectedInputs inputs;
  return inputs;
}

}  // namespace

void protect_from_outputs(const std::vector<std::string>& files) {
  ProtectedInputs& inputs = protected_inputs();
  const std::lock_guard<std::mutex> lock(inputs.mutex);
  for (const std::string& file : files) {
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0 && S_ISREG(info.st_mode))
      inputs.files.emplace(std::pair{info.st_dev, info.st_ino}, file);
  }
}

void require_regular_output(const fs::path& path, std::string_view option) {
  if (path.empty()) {
    throw InputError((option.empty() ? std::string() : std::string(option) + ": ") +
                     "no output file name given");
  }
  require_file_name(path.string());
  struct stat info {};
  // stat follows symbolic links: a link to /dev/null is /dev/null.
  if (::stat(path.c_str(), &info) != 0) return;  // absent (or unreachable: the write says)
  const std::string prefix = option.empty() ? std::string() : std::string(option) + " ";
  if (S_ISREG(info.st_mode)) {
    ProtectedInputs& inputs = protected_inputs();
    const std::lock_guard<std::mutex> lock(inputs.mutex);
    const auto input = inputs.files.find({info.st_dev, info.st_ino});
    if (input == inputs.files.end()) return;
    throw InputError(prefix + quoted(path) + " is an input of this run (" +
                     quoted(fs::path(input->second)) +
                     "): writing it would destroy it; choose another output name");
  }
  throw InputError(prefix + quoted(path) + " is " + kind_of(info) +
                   ", not a regular file; Talus writes its outputs only to regular files "
                   "(it would otherwise replace it): choose a file name");
}

void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path&)>& write) {
  require_regular_output(path);
  const fs::path target = resolved_target(path);
  std::error_code error;
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, error)) {
    throw InputError(quoted(path) + ": its folder " + quoted(folder) +
                     " does not exist; create it first");
  }
  const fs::path temporary = temporary_beside(target);
  try {
    write(temporary);
    sync_file(temporary, path);
    // Again just before the rename: the target may have been replaced by a
    // device or FIFO while we wrote.
    require_regular_output(target);
    fs::rename(temporary, target, error);
    if (error) {
      throw Error("writing " + quoted(path) +
                  " failed (cannot rename into place: " + error.message() + ")");
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_text_file(const fs::path& path, std::string_view text) {
  // Data files of a figure or report go into folders made on the way.
  if (path.has_parent_path()) {
    std::error_code error;
    fs::create_directories(path.parent_path(), error);
    if (error) {
      throw Error("cannot create folder " + quoted(path.parent_path()) + ": " + error.message());
    }
  }
  write_file_atomically(path, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out) {
      throw Error("cannot open " + quoted(temporary) + " for writing: " + std::strerror(errno));
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    const bool ok = static_cast<bool>(out);
    out.close();
    if (!ok || out.fail()) throw Error("writing " + quoted(path) + " failed (disk full?)");
  });
}

}  // namespace talus
