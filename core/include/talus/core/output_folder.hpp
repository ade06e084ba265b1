#pragma once
/// @file
/// A command's output folder (`--out DIR`), filled atomically, so that what
/// is in DIR is always one run's complete result:
/// - a lock (DIR/.talus.lock, flock) makes a second run on the same DIR fail
///   at once instead of interleaving its files with the first's;
/// - the run writes into a hidden staging folder inside DIR, and commit()
///   moves its files into DIR, summary.json last; a run that fails, throws or
///   is interrupted (SIGINT, SIGTERM) leaves DIR's previous result as it was;
/// - DIR/.talus-manifest lists what the last committed run wrote: commit()
///   replaces exactly those files, and refuses to overwrite a file of the
///   same name that talus did not write (a user's plan.png stays);
/// - inside another run's staging folder (an experiment that runs `plan`
///   into a subfolder) it writes in place, since the enclosing commit is the
///   atomic step, and final_path() names where the files will be after it.
#include <filesystem>
#include <string>
#include <vector>

namespace talus {

class OutputFolder {
 public:
  /// Creates `dir` if needed, takes its lock and prepares an empty staging
  /// folder (removing the staging folders of runs that died). InputError,
  /// naming `option`, if `dir` is not a folder, cannot be created or is in
  /// use by another run.
  explicit OutputFolder(std::filesystem::path dir, std::string option = "--out");
  /// Not committed: removes the staging folder (and the folder itself if this
  /// run created it); the lock is released.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Where the run writes its files.
  const std::filesystem::path& staging() const { return staging_; }
  /// Where `name` will be once committed (for summaries that list files).
  std::filesystem::path final_path(const std::string& name) const { return final_dir_ / name; }

  /// Moves every staged file and folder into the output folder, replacing the
  /// previous run's (the manifest), summary.json last. InputError, before
  /// anything moves, if a staged name exists in the folder and the manifest
  /// does not list it.
  void commit();

  /// InputError now, as commit() would at the end, if one of `names` (the files the run may
  /// write) exists in the folder and the manifest does not list it: a run whose result could
  /// not be committed fails before its work.
  void refuse_foreign_files(const std::vector<std::string>& names) const;

 private:
  std::filesystem::path dir_, staging_;
  std::filesystem::path final_dir_;  ///< dir_ as it will be named once every commit is done
  bool nested_ = false;              ///< dir_ lies in an enclosing run's staging folder
  std::string option_;
  int lock_fd_ = -1;
  bool committed_ = false;
  bool created_ = false;  ///< the folder did not exist before this run
};

/// Take it before the long work, so that a second run on the same folder
/// fails at once.

/// Makes SIGINT and SIGTERM end the process at once with exit code 130 or
/// 143. Output folders stay consistent: nothing is committed half-way.
void exit_cleanly_on_signals();

}  // namespace talus
