#pragma once
/// @file
/// The `talus profile` command's work, separate from argument parsing: the
/// time-optimal velocity profile of a vehicle along a path on a terrain,
/// written as CSV, with a JSON summary.
#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace talus::experiments {

/// `talus profile --terrain T.asc --path P.csv --vehicle V.yaml [--v0 A]
/// [--v1 B] [--stations N] [--smoothing LAMBDA] -o OUT.csv`.
struct ProfileRequest {
  std::string terrain;             ///< DEM (load_terrain)
  std::string reproject = "none";  ///< --reproject: none | auto (load_terrain)
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string path;          ///< path CSV (read_path_csv): way points in the terrain's frame [m]
  std::string vehicle;       ///< vehicle YAML/JSON (load_vehicle)
  std::string output;        ///< CSV written here
  double start_speed = 0.0;  ///< --v0 [m/s] (finite, >= 0)
  double end_speed = 0.0;    ///< --v1 [m/s] (finite, >= 0)
  /// Stations (2 to kMaxStations), equally spaced in the curve parameter; none = the default.
  std::optional<long long> stations;
  /// lambda of the smoothing fit; none = interpolating fit.
  std::optional<double> smoothing;
};

/// Smallest and largest default station count of `talus profile`.
inline constexpr std::size_t kMinDefaultProfileStations = 100;
inline constexpr std::size_t kMaxDefaultProfileStations = 1'000'000;

/// Default station count for a path whose 3-D length (on the surface) is
/// `length` metres: ceil(length / kDefaultStationSpacing) + 1, clamped to
/// [100, 1000000].
std::size_t default_profile_station_count(double length);
/// That rule in words, for --help: "ceil(length_m / 0.1) + 1 with ...".
std::string default_profile_stations_text();

/// The columns of the CSV, in order.
inline constexpr const char* kProfileCsvHeader = "s,x,y,z,v,a,t,v_max,binding";

/// Exit code of `talus profile` when no admissible profile exists.
inline constexpr int kInfeasibleExitCode = 2;

/// What `profile` returns: the JSON summary and whether a profile exists.
struct ProfileOutcome {
  nlohmann::json summary;
  bool feasible = false;
};

/// Builds the path as `talus limits` does, computes the speed limits and the
/// time-optimal profile from start_speed to end_speed, writes the CSV and
/// returns the summary: status ("ok" | "infeasible"), travel_time (null when
/// infeasible), stations, length_m, switching_points [{station, s, from, to}],
/// solve_seconds, limits_seconds, merged_stations, message, infeasible_station,
/// infeasible_s, infeasible_binding (the last four null when ok), and
/// start_speed, end_speed, fit, smoothing, output, seconds.
///
/// An infeasible path is not an error: the CSV is still written, with s, x, y,
/// z, v_max and binding as usual and v = 0, a = 0, t = inf at every station.
/// Bad input (including a start or end speed above the speed limit there)
/// throws InputError and writes nothing.
ProfileOutcome profile(const ProfileRequest& request);

}  // namespace talus::experiments
