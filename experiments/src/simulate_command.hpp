#pragma once
/// @file
/// The `talus simulate` command's work, separate from argument parsing: drive
/// a planned trajectory with the rigid-body vehicle simulation
/// (talus::track_trajectory, dynamics/trajectory_tracking.hpp) and report the
/// margins it kept and any failure.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/dynamics/trajectory_tracking.hpp"

namespace talus::experiments {

/// `talus simulate --terrain T.asc --vehicle V.yaml --trajectory trajectory.csv
/// [--speed-scale K] [--smoothing LAMBDA] [--trace-interval DT] --out DIR`.
struct SimulateRequest {
  std::string terrain;             ///< DEM (load_terrain)
  std::string reproject = "none";  ///< --reproject: none | auto
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string vehicle;             ///< vehicle file with a body (`mass`, ...)
  /// CSV with a header naming at least the columns x, y and v (the
  /// trajectory.csv of `talus plan` and `talus profile`); other columns are ignored.
  std::string trajectory;
  std::string output_dir;    ///< --out
  double speed_scale = 1.0;  ///< TrackingOptions::speed_scale (> 0)
  /// --steering-law: curvature | pure_pursuit (TrackingOptions::steering_law).
  std::string steering_law = "curvature";
  /// lambda of the smoothing fit (as the plan's --smoothing); none = interpolating fit.
  std::optional<double> smoothing;
  double trace_interval = 0.02;  ///< trace.csv sample interval [s] (> 0)
  bool progress = true;          ///< false (--quiet): no progress line on stderr
};

/// Exit code of `talus simulate` when the vehicle did not reach the goal
/// (a failure, the time limit or a solver failure); the outputs are written.
inline constexpr int kSimulateNotReachedExitCode = 2;

/// The columns of DIR/trace.csv, in order.
inline constexpr const char* kTraceCsvHeader =
    "t,x,y,z,roll,pitch,yaw,speed,desired_speed,steering,drive_force,s,cross_track,"
    "lateral_load_ratio,side_slip,min_normal_load,max_slip_angle";

/// Reads a trajectory CSV (header naming x, y and v among its columns; one
/// row of numbers per point, the named columns finite; consecutive points
/// distinct) as a ReferenceTrajectory. InputError naming file and line.
ReferenceTrajectory read_trajectory_csv(const std::string& path);

struct SimulateOutcome {
  TrackingResult result;
  nlohmann::json summary;
  bool reached = false;  ///< status reached_goal
};

/// Loads the terrain, vehicle and trajectory, fits the surface, runs
/// track_trajectory and writes, in request.output_dir (an OutputFolder):
/// - trace.csv (kTraceCsvHeader): every trace_interval and at the end; angles
///   in radians, min_normal_load the smallest wheel load [N], max_slip_angle
///   the largest |α| of the wheels on the ground;
/// - summary.json: status (reached_goal | timeout | rollover | side_slip |
///   loss_of_contact | stall | left_terrain | solver_failure), failure (null
///   when the goal was reached), message, progress, path_length, travel_time,
///   planned_time, speed_scale, margins {peak_lateral_load_ratio,
///   min_normal_load, min_normal_load_ratio, peak_slip_angle, peak_side_slip,
///   peak_roll, peak_speed}, tracking {max_cross_track, rms_cross_track,
///   max_speed_excess}, solver {method, steps, rhs_evaluations,
///   jacobian_evaluations, error_test_failures, nonlinear_failures},
///   real_time_factor, files, inputs and seconds.
/// Bad input throws InputError and writes nothing.
SimulateOutcome simulate(const SimulateRequest& request);

}  // namespace talus::experiments
