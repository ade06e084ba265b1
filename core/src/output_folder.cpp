#include "talus/core/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <set>
#include <system_error>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLockName = ".talus.lock";
constexpr const char* kManifestName = ".talus-manifest";
constexpr const char* kStagingPrefix = ".talus-staging-";
constexpr const char* kSummaryName = "summary.json";

std::set<std::string> read_manifest(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / kManifestName);
  for (std::string line; std::getline(in, line);) {
    // Only plain names: a tampered manifest must not reach outside DIR.
    if (!line.empty() && line.find('/') == std::string::npos && line != "." && line != "..") {
      names.insert(line);
    }
  }
  return names;
}

void write_manifest(const fs::path& dir, const std::vector<std::string>& names) {
  const fs::path temporary = dir / (std::string(kManifestName) + ".new");
  {
    std::ofstream out(temporary, std::ios::binary);
    for (const std::string& name : names) out << name << '\n';
    if (!out) throw InputError(dir.string() + ": cannot write " + kManifestName);
  }
  fs::rename(temporary, dir / kManifestName);
}

extern "C" void exit_on_signal(int signal_number) {
  ::_exit(128 + signal_number);
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir, std::string option)
    : dir_(std::move(dir)), option_(std::move(option)) {
  const std::string shown = option_ + " " + printable(dir_.string(), 200);
  if (dir_.empty()) throw InputError("no output folder given (" + option_ + " DIR)");
  std::error_code error;
  if (fs::exists(dir_, error) && !fs::is_directory(dir_, error)) {
    throw InputError(shown + " exists and is not a folder");
  }
  created_ = fs::create_directories(dir_, error);
  if (error) throw InputError(shown + ": cannot create the folder (" + error.message() + ")");

  lock_fd_ = ::open((dir_ / kLockName).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw InputError(shown + ": cannot create its lock file");
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw InputError(shown +
                     " is in use by another talus run; wait for it or choose another folder");
  }
  // Inside an enclosing run's staging folder: write in place.
  for (const fs::path& part : dir_) {
    if (part.string().rfind(kStagingPrefix, 0) == 0) {
      nested_ = true;
    } else {
      final_dir_ /= part;
    }
  }
  if (!nested_) final_dir_ = dir_;
  if (nested_) {
    staging_ = dir_;
    return;
  }
  // We hold the lock: any staging folder left is from a run that died.
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_, error)) {
    if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0) {
      fs::remove_all(entry.path(), error);
    }
  }
  staging_ = dir_ / (kStagingPrefix + std::to_string(::getpid()));
  fs::create_directories(staging_, error);
  if (error) throw InputError(shown + ": cannot create a staging folder (" + error.message() + ")");
}

OutputFolder::~OutputFolder() {
  std::error_code error;
  if (!committed_ && !nested_ && !staging_.empty()) fs::remove_all(staging_, error);
  if (!committed_ && created_) {  // leave no trace of a run that produced nothing
    fs::remove(dir_ / kLockName, error);
    fs::remove(dir_, error);  // only if empty
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

void OutputFolder::refuse_foreign_files(const std::vector<std::string>& names) const {
  if (nested_) return;  // the enclosing run's commit judges its folder
  const std::set<std::string> previous = read_manifest(dir_);
  for (const std::string& name : names) {
    if (fs::exists(dir_ / name) && !previous.count(name)) {
      throw InputError(option_ + " " + printable((dir_ / name).string(), 200) +
                       " exists and was not written by talus; move it or choose another folder");
    }
  }
}

void OutputFolder::commit() {
  if (nested_) {  // written in place; the enclosing run commits it
    committed_ = true;
    return;
  }
  std::vector<std::string> staged;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_)) {
    staged.push_back(entry.path().filename().string());
  }
  std::sort(staged.begin(), staged.end());
  refuse_foreign_files(staged);
  const std::set<std::string> previous = read_manifest(dir_);
  // Out with the previous result, its summary first: from here until the new
  // summary lands, the folder holds no summary.json that could vouch for it.
  std::error_code error;
  if (previous.count(kSummaryName)) fs::remove(dir_ / kSummaryName, error);
  for (const std::string& name : previous) fs::remove_all(dir_ / name, error);
  // In with the new, summary last.
  std::stable_partition(staged.begin(), staged.end(),
                        [](const std::string& name) { return name != kSummaryName; });
  write_manifest(dir_, staged);
  for (const std::string& name : staged) fs::rename(staging_ / name, dir_ / name);
  fs::remove(staging_, error);
  committed_ = true;
}

void exit_cleanly_on_signals() {
  std::signal(SIGINT, exit_on_signal);
  std::signal(SIGTERM, exit_on_signal);
}

}  // namespace talus
