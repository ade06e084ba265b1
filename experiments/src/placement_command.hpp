#pragma once
/// @file
/// The `talus placement` command's work, separate from argument parsing: a
/// robot's placement (PlacementQuery, kinematic/hait/placement_query.hpp) at
/// every configuration of a CSV file, written as CSV.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/kinematic/configuration_space.hpp"

namespace talus::experiments {

/// `talus placement --terrain T.asc --robot R.yaml --configs C.csv -o OUT.csv`.
struct PlacementRequest {
  std::string terrain;             ///< DEM (load_terrain: .asc or any GDAL raster)
  std::string reproject = "none";  ///< --reproject none|auto
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string robot;    ///< Haït robot file (load_robot): wheeled or articulated_chassis
  std::string configs;  ///< configurations CSV (read_configurations_csv)
  std::string output;   ///< CSV written here
};

/// What `talus placement` writes, for its --help.
inline constexpr const char* kPlacementHelp =
    "the Hait-Simeon-Taix placement of a robot at given configurations. --configs C.csv has "
    "the header x,y,theta and one configuration per line (x, y [m] in the terrain's frame, "
    "heading theta [rad] counter-clockwise from east). Writes OUT.csv with columns "
    "x,y,theta,z,roll,pitch, then one column per contact, then valid,reason: z [m] is the "
    "centre of gravity G for a wheeled robot (terrain height + cg_height on level ground) and "
    "the middle axle centre for an articulated chassis (the terrain height on level ground); "
    "roll, pitch [rad] (roll > 0 raises the left side, pitch > 0 the nose; the chassis' mean "
    "axle roll and global pitch); the contact columns are extension_1..extension_n [m], each "
    "wheel's spring extension (wheeled), or roll_front,roll_middle,roll_rear,pitch_front,"
    "pitch_rear [rad] (chassis, which has no springs); valid 1 or 0; reason none, off_map, "
    "no_data, roll, pitch, spring_extension, axle_roll_difference, body_angle or collision (the "
    "first failed test). Values are nan where no placement exists. Prints a JSON summary. Exit "
    "code 0; 1 on bad input (a bad header, a non-numeric or non-finite value, a configuration "
    "off the terrain, a missing or bad file: one line on stderr naming the file and line, "
    "nothing written)";

/// The most configurations `talus placement` takes in one file (8 x 10^6 reached 1.2 GB).
inline constexpr std::size_t kMaxPlacementConfigurations = 1'000'000;

/// Reads a configurations CSV: line 1 the header `x,y,theta` (spaces around
/// names allowed, an optional UTF-8 byte-order mark skipped), then one line
/// `x,y,theta` of three finite numbers per configuration, LF or CRLF, blank
/// lines only at the end, at least one and at most kMaxPlacementConfigurations. Any deviation
/// throws InputError naming the file and line (`C.csv:4: theta value 'a' is not a number`).
std::vector<SE2Pose> read_configurations_csv(const std::string& file);

/// The header of OUT.csv for the given contact column names.
std::string placement_csv_header(const std::vector<std::string>& contact_names);

/// Reads the terrain, robot and configurations, checks that every
/// configuration's (x, y) is on the terrain (InputError naming the file, line
/// and the terrain's domain otherwise), places the robot at each and writes
/// request.output (atomically, only when every input is good). Returns the
/// summary printed on stdout: configurations, valid, invalid_reasons (reason
/// -> count), robot_kind, columns, output, seconds.
nlohmann::json run_placement(const PlacementRequest& request);

}  // namespace talus::experiments
