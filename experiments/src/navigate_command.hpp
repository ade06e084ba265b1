#pragma once
/// @file
/// The `talus navigate` command's work, separate from argument parsing: the
/// layered scheme of Iagnemma, Shimoda & Shiller (navigate_layered,
/// navigation/layered_navigation.hpp) on a terrain file, its trace and summary.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/navigation/layered_navigation.hpp"

namespace talus::experiments {

/// `talus navigate --terrain FINE.asc [--coarse-factor K] --vehicle V.yaml
/// --start X,Y --goal X,Y [--no-lookahead] [--detect-hazards] [--time-limit S] [--seed N]
/// [--trace-interval DT] [--no-figures] --out DIR`.
struct NavigateRequest {
  std::string terrain;             ///< the fine DEM (load_terrain), no NODATA
  std::string reproject = "none";  ///< --reproject: none | auto
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string vehicle;             ///< vehicle file with a body and a finite max_speed
  std::string start, goal;         ///< "X,Y" [m] (parse_point)
  std::string output_dir;          ///< --out
  long long coarse_factor = 4;     ///< LayeredNavigationOptions::coarse_factor (>= 1)
  bool lookahead = true;           ///< false (--no-lookahead): the standard field
  /// --detect-hazards: PotentialFieldNavigationOptions::hazards_from_map (off by default:
  /// with the paper's hazard gains the UGV turns away from its waypoints; iagnemma-table1).
  bool detect_hazards = false;
  double time_limit = 60.0;      ///< simulated navigation time limit [s] (> 0)
  std::uint64_t seed = 1;        ///< the descent's randomisation
  double trace_interval = 0.02;  ///< trace.csv sample interval [s] (> 0)
  /// false (--no-figures): no navigation_map.png, navigation_speed.png and
  /// navigation_angles.png (sweeps draw their own).
  bool figures = true;
  bool progress = true;  ///< false (--quiet): no progress line on stderr
};

/// Exit code when the goal was not reached (failure, timeout, no plan); the
/// outputs are written.
inline constexpr int kNavigateNotReachedExitCode = 2;

/// The columns of DIR/trace.csv, in order: angles in radians, v the forward
/// speed, kappa and desired_v the commanded (v, κ) of the last control tick,
/// slip_angle the c.g.'s side slip, lookahead_cap the lookahead's cap at
/// that tick (inf where it did not cap or is off).
inline constexpr const char* kNavigateTraceHeader =
    "t,x,y,z,roll,pitch,yaw,v,kappa,slip_angle,desired_v,lookahead_cap";

struct NavigateOutcome {
  LayeredNavigationResult result;
  nlohmann::json summary;
  bool reached() const { return result.status == LayeredNavigationStatus::kReachedGoal; }
};

/// Loads the terrain and vehicle, runs navigate_layered and writes, in
/// request.output_dir (an OutputFolder, committed only when complete):
/// - trace.csv (kNavigateTraceHeader) every trace_interval;
/// - waypoints.csv (x,y,v): the high-level plan's waypoints;
/// - when the navigation ran and gnuplot is installed, the paper's figures
///   7–9 (navigation_figures.hpp): navigation_map.png (waypoints and driven
///   path over the relief), navigation_speed.png (speed against the
///   lookahead's safe speed), navigation_angles.png (roll and side slip);
/// - summary.json: status (reached | failed | timeout | no_plan), failure
///   (the simulation's failure kind, null otherwise), message,
///   navigation_time, optimal_time, time_increase, plan_status, lookahead,
///   detect_hazards, coarse_factor, waypoints, lookahead_caps_applied,
///   ticks, margins, inputs, files and seconds.
/// Bad input throws InputError and writes nothing.
NavigateOutcome navigate(const NavigateRequest& request);

}  // namespace talus::experiments
