#pragma once
/// @file
/// The `talus limits` command's work, separate from argument parsing: a
/// vehicle's speed limits at stations along a path on a terrain, written as CSV.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/bspline/surface_path_from_points.hpp"

namespace talus::experiments {

/// `talus limits --terrain T.asc --path P.csv --vehicle V.yaml [--stations N]
/// [--smoothing LAMBDA] -o OUT.csv`.
struct LimitsRequest {
  std::string terrain;             ///< DEM (load_terrain)
  std::string reproject = "none";  ///< --reproject: none | auto (load_terrain)
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string path;     ///< path CSV (read_path_csv): way points in the terrain's frame [m]
  std::string vehicle;  ///< vehicle YAML/JSON (load_vehicle)
  std::string output;   ///< CSV written here
  /// Stations (2 to kMaxStations), equally spaced in the curve parameter; none = the default.
  std::optional<long long> stations;
  /// lambda of the smoothing fit; none = interpolating fit.
  std::optional<double> smoothing;
};

/// Largest --stations accepted (memory: about 0.3 kB per station).
inline constexpr long long kMaxStations = 10'000'000;
/// Smallest and largest default station count.
inline constexpr std::size_t kMinDefaultStations = 100;
inline constexpr std::size_t kMaxDefaultStations = 100000;

/// Default station count for a path whose planar polyline (the straight
/// segments between its way points) is `planar_length` metres long: one per
/// metre, ceil(planar_length) + 1, clamped to [100, 100000].
std::size_t default_station_count(double planar_length);

/// Checks the options that `talus limits` and `talus profile` share, before
/// any file is read: --stations (if given) in [2, kMaxStations], --smoothing
/// (if given) positive and finite, and an output file. Throws InputError.
void check_path_options(const std::optional<long long>& stations,
                        const std::optional<double>& smoothing, const std::string& output);

/// Reads the way points of `path_file` (read_path_csv) and the terrain
/// (load_terrain with `reproject` and `band`),
/// fits the B-patch (interpolating, or the smoothing fit with lambda
/// `smoothing`), and lifts the interpolating cubic B-spline through the way
/// points (chord-length parameters) onto it: surface_path_from_points, whose
/// InputErrors name the point, file and line.
TerrainPath build_terrain_path(const std::string& terrain_file, const std::string& path_file,
                               const std::optional<double>& smoothing,
                               const std::string& reproject = "none", int band = 0);

/// Appends the shortest text that reads back as exactly `value`; infinity is "inf".
void append_csv_number(std::string& out, double value);

/// The columns of the CSV, in order.
inline constexpr const char* kLimitsCsvHeader =
    "s,x,y,z,v_min,v_max,binding,k_t,k_q,k_r,kappa_n,kappa_g";

/// Builds the path (interpolating cubic B-spline through the way points,
/// chord-length parameters, lifted onto the terrain's B-patch), computes the
/// vehicle's speed limits at every station, writes them to request.output and
/// returns the summary: stations, length_m, min_v_max (null if unbounded),
/// untraversable_stations, binding_counts, seconds (and fit, smoothing,
/// output). Bad input throws InputError.
nlohmann::json limits(const LimitsRequest& request);

}  // namespace talus::experiments
