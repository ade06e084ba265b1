#pragma once
/// @file
/// A parameter sweep's configuration (`talus sweep CONFIG.yaml`): the job to
/// run and the design that turns its parameters into cases.
///
/// Format (YAML, one document, no duplicate keys):
///
///     job: plan                  # plan | profile | navigate | baseline NAME | noop
///     design: grid               # grid | list | random
///     parameters:                # in this order; a list is swept (grid) or
///       terrain.generator: fractal   #   chosen from (random)
///       terrain.seed: [1, 2, 3, 4]
///       vehicle.file: data/vehicles/rover.yaml
///       vehicle.friction: [0.5, 0.7]
///       start: "2,2"
///       goal: "13,13"
///     cases: [{...}, ...]        # design list: one map per case, merged
///                                #   over `parameters` (a key in both: error)
///     samples: 20                # design random: number of cases
///     seed: 1                    #   and its seed; {uniform: [lo, hi]} and
///                                #   {integers: [lo, hi]} draw a value
///     retries: 2                 # a case whose worker crashed or hung is
///                                #   run again at most this often
///     case_time_limit: 600       # [s] a worker running longer is killed
///     quick: {terrain.ncols: 33} # values replacing parameters' in quick runs
///                                #   (`talus experiment NAME --quick`)
///
/// Parameter keys: `terrain.file` (a grid), or `terrain.generator` (a kind of
/// `talus terrain generate`) with `terrain.*` its options (ncols, seed,
/// fractal_dimension, …); `vehicle.file` and `vehicle.*` overriding keys of
/// that vehicle file; `robot.file`, the robot file of a baseline job
/// (`--robot`); any other key is an option of the job's command
/// (`--key value`; `true` is a bare flag, `false` leaves it out; `_` may
/// stand for `-`). Relative paths are taken from the working directory.
///
/// Grid cases are the Cartesian product with the last listed parameter
/// varying fastest. Each case's id is a hash of its job and resolved
/// parameters, so it does not depend on its position, the job count or the
/// rank count: results can be resumed after the config grows.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace talus {

/// One case: its position in the design, its id and its parameters (keys in
/// the design's order, values JSON scalars).
struct SweepCase {
  std::size_t index = 0;
  std::string id;  ///< 16 hex digits (FNV-1a 64 of the job and the sorted parameters)
  nlohmann::ordered_json parameters;
};

/// Most cases a sweep design may have (grid: the product of the list sizes;
/// random: `samples`), checked before any case is built.
inline constexpr std::size_t kMaxSweepCases = 1000000;

struct SweepConfig {
  std::string job;     ///< "plan", "profile", "navigate", "baseline NAME" or "noop"
  std::string design;  ///< grid | list | random
  std::vector<SweepCase> cases;
  /// Parameters whose value differs between cases, in the design's order.
  std::vector<std::string> swept;
  /// Every parameter key that occurs, in the design's order.
  std::vector<std::string> keys;
  int retries = 2;
  double case_time_limit = 600.0;  ///< [s]
  std::string source;              ///< the file, for messages
  /// Relative file parameters (terrain.file, vehicle.file, robot.file) are taken from
  /// here; empty = the working directory.
  std::filesystem::path base_dir;
};

/// Parses a sweep configuration. InputError naming the file and the key for
/// an unknown job, design or top-level key, an empty design, a malformed
/// parameter or two cases with the same parameters.
/// With `quick`, the values under `quick:` replace those parameters' values.
SweepConfig parse_sweep_config(const std::string& yaml_text, const std::string& source,
                               bool quick = false);
SweepConfig load_sweep_config(const std::filesystem::path& path, bool quick = false);

/// The files and commands that run one case in `case_dir`: the job's
/// command line (without the program name), preceded by a `terrain
/// generate` command when the terrain is generated. The `noop` job has no
/// commands. Throws InputError for a parameter the job cannot take.
struct PreparedCase {
  std::map<std::string, std::string> files;  ///< name in case_dir -> contents
  std::vector<std::vector<std::string>> commands;
};

/// Checks a file a case writes, given its text and a name for messages;
/// throws InputError if the file is not valid (for a vehicle file with
/// `vehicle.*` overrides, the caller that knows vehicles passes their parser:
/// this layer does not depend on dynamics).
using SweepFileCheck = std::function<void(const std::string& text, const std::string& source)>;

/// With `check_vehicle`, a case's vehicle file with its overrides applied is
/// checked before the case can run; without it, a bad override shows only
/// when the job reads the file (the case is then recorded as `error`).
PreparedCase prepare_case(const SweepConfig& config, const SweepCase& c,
                          const std::filesystem::path& case_dir,
                          const SweepFileCheck& check_vehicle = {});

/// 64-bit FNV-1a of `text` as 16 lower-case hex digits.
std::string fnv1a_hex(const std::string& text);

}  // namespace talus
