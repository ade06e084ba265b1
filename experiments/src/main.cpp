// The `talus` command-line tool. Argument parsing only: the work is in the
// talus_experiments library so that tests and notebooks can call it too.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <list>
#include <map>
#include <new>
#include <string>

#include "baseline_command.hpp"
#include "baseline_profile.hpp"
#include "experiment.hpp"
#include "limits_command.hpp"
#include "navigate_command.hpp"
#include "parameter_options.hpp"
#include "placement_command.hpp"
#include "plan_command.hpp"
#include "profile_command.hpp"
#include "simulate_command.hpp"
#include "sweep_command.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/output_file.hpp"
#include "talus/core/output_folder.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/optimal/planner_parameters.hpp"
#include "talus/planners/planner_registry.hpp"
#include "terrain_commands.hpp"
#include "terrain_input.hpp"

namespace {

/// An unsigned option's text: "-1" would wrap to 2^64 - 1 in CLI11's conversion.
const CLI::Validator kWholeNumber(
    [](std::string& text) {
      return text.find_first_not_of("0123456789") == std::string::npos && !text.empty()
                 ? std::string()
                 : "must be a whole number >= 0, got '" + text + "'";
    },
    "UINT");

using namespace talus;
namespace ex = talus::experiments;

void add_shape_options(CLI::App& command, GridShape& shape) {
  // Unsigned fields: "-1" would wrap to 2^64 - 1 without the range checks.
  command.add_option("--ncols", shape.ncols, "nodes west to east")
      ->check(CLI::Range(2.0, 1e8))
      ->capture_default_str();
  command.add_option("--nrows", shape.nrows, "nodes south to north")
      ->check(CLI::Range(2.0, 1e8))
      ->capture_default_str();
  command.add_option("--cellsize", shape.cellsize, "node spacing [m]")->capture_default_str();
  command.add_option("--xmin", shape.x_min, "x of the south-west node [m]")->capture_default_str();
  command.add_option("--ymin", shape.y_min, "y of the south-west node [m]")->capture_default_str();
}

/// Options of every generator; each `terrain generate KIND` subcommand binds its own.
struct GenerateOptions {
  FractalTerrainOptions fractal;
  PlaneOptions plane;
  CylinderOptions cylinder;
  bool dip = false;
  SphereCapOptions sphere;
  GaussianHillsOptions hills;
  std::vector<std::vector<double>> hill_specs;
  BowlOptions bowl;
  EldershawYimOptions eldershaw_yim;
  std::string output;
};

void add_generate_commands(CLI::App& terrain, GenerateOptions& o) {
  CLI::App* generate = terrain.add_subcommand(
      "generate", "write a generated terrain as an ESRI ASCII grid (seeded, reproducible)");
  // Not require_subcommand(1): CLI11 would answer an unknown KIND with "A
  // subcommand is required"; the callback names the kind and the choices.
  generate->require_subcommand(0, 1);
  generate->allow_extras();
  const auto output = [&o](CLI::App* c) {
    c->add_option("-o,--output", o.output, "output .asc file")->required();
  };

  CLI::App* fractal = generate->add_subcommand(
      "fractal",
      "fractional Brownian surface (Iagnemma-Shimoda-Shiller defaults: D 2.05, 0.24 m "
      "spacing, 4.2 m height scale)");
  add_shape_options(*fractal, o.fractal.shape);
  fractal->add_option("--fractal-dimension", o.fractal.fractal_dimension, "D in (2, 3)")
      ->capture_default_str();
  fractal
      ->add_option("--height-scale", o.fractal.height_scale,
                   "peak-to-peak range of the fractal part [m]")
      ->capture_default_str();
  fractal->add_option("--undulation-amplitude", o.fractal.undulation_amplitude, "[m]")
      ->capture_default_str();
  fractal
      ->add_option("--undulation-wavelength", o.fractal.undulation_wavelength,
                   "[m], 0 = grid's longer side")
      ->capture_default_str();
  fractal->add_option("--peaks", o.fractal.peaks, "number of discrete Gaussian peaks")
      ->check(CLI::Range(0.0, static_cast<double>(talus::kMaxFractalPeaks)))
      ->capture_default_str();
  fractal->add_option("--peak-height", o.fractal.peak_height, "[m]")->capture_default_str();
  fractal->add_option("--peak-radius", o.fractal.peak_radius, "Gaussian standard deviation [m]")
      ->capture_default_str();
  fractal->add_option("--seed", o.fractal.seed, "random seed")
      ->check(kWholeNumber)
      ->capture_default_str();
  output(fractal);

  CLI::App* plane = generate->add_subcommand("plane", "inclined plane");
  add_shape_options(*plane, o.plane.shape);
  plane->add_option("--slope", o.plane.slope, "inclination [rad]")->capture_default_str();
  plane->add_option("--aspect", o.plane.aspect, "direction of steepest ascent [rad, CCW from east]")
      ->capture_default_str();
  plane->add_option("--z0", o.plane.z0, "elevation at the grid's centre [m]")
      ->capture_default_str();
  output(plane);

  CLI::App* cylinder =
      generate->add_subcommand("cylinder", "horizontal circular cylinder: crest or dip");
  add_shape_options(*cylinder, o.cylinder.shape);
  cylinder->add_option("--radius", o.cylinder.radius, "[m]")->capture_default_str();
  cylinder->add_option("--axis", o.cylinder.axis_direction, "axis direction [rad, CCW from east]")
      ->capture_default_str();
  cylinder->add_flag("--dip", o.dip, "concave up (a dip) instead of a crest");
  cylinder->add_option("--z0", o.cylinder.z0, "elevation on the axis [m]")->capture_default_str();
  output(cylinder);

  CLI::App* sphere = generate->add_subcommand("sphere-cap", "spherical cap over the grid's centre");
  add_shape_options(*sphere, o.sphere.shape);
  sphere->add_option("--radius", o.sphere.radius, "[m]")->capture_default_str();
  sphere->add_option("--z0", o.sphere.z0, "elevation at the top [m]")->capture_default_str();
  output(sphere);

  CLI::App* hills =
      generate->add_subcommand("gaussian-hills", "sum of Gaussian hills on a flat base");
  add_shape_options(*hills, o.hills.shape);
  hills->add_option("--hill", o.hill_specs, "X,Y,HEIGHT,SIGMA in metres (repeatable)")
      ->delimiter(',')
      ->expected(4)
      ->allow_extra_args(false);
  hills->add_option("--z0", o.hills.z0, "base elevation [m]")->capture_default_str();
  output(hills);

  CLI::App* bowl = generate->add_subcommand("bowl", "paraboloid bowl");
  add_shape_options(*bowl, o.bowl.shape);
  bowl->add_option("--curvature", o.bowl.curvature, "second derivative at the centre [1/m]")
      ->capture_default_str();
  bowl->add_option("--z0", o.bowl.z0, "[m]")->capture_default_str();
  output(bowl);

  CLI::App* ey = generate->add_subcommand(
      "eldershaw-yim", "plateau with a cliff and nine sharp peaks (Eldershaw-Yim test terrain)");
  add_shape_options(*ey, o.eldershaw_yim.shape);
  ey->add_option("--plateau-height", o.eldershaw_yim.plateau_height, "[m]")->capture_default_str();
  ey->add_option("--peak-height", o.eldershaw_yim.peak_height, "[m]")->capture_default_str();
  ey->add_option("--roughness", o.eldershaw_yim.roughness, "standard deviation [m]")
      ->capture_default_str();
  ey->add_option("--seed", o.eldershaw_yim.seed, "random seed")
      ->check(kWholeNumber)
      ->capture_default_str();
  output(ey);

  generate->callback([generate, &o]() {
    const std::vector<std::string> extras = generate->remaining();
    const std::string kinds =
        "fractal, plane, cylinder, sphere-cap, gaussian-hills, bowl, eldershaw-yim";
    if (generate->get_subcommands().empty()) {
      throw InputError(extras.empty() ? "terrain generate needs a KIND: " + kinds
                                      : "unknown terrain kind '" + talus::printable(extras[0]) +
                                            "' (choose " + kinds + ")");
    }
    if (!extras.empty()) {
      throw InputError("terrain generate: unexpected argument '" + talus::printable(extras[0]) +
                       "' (see --help)");
    }
    CLI::App* kind = generate->get_subcommands().front();
    if (const std::vector<std::string> unknown = kind->remaining(); !unknown.empty()) {
      throw InputError("terrain generate " + kind->get_name() + ": unexpected argument '" +
                       talus::printable(unknown[0]) + "' (see --help)");
    }
    const std::string name = kind->get_name();
    talus::require_regular_output(o.output, "-o");  // before the generator's work
    ElevationGrid grid;
    if (name == "fractal") grid = generate_fractal_terrain(o.fractal);
    if (name == "plane") grid = generate_plane(o.plane);
    if (name == "cylinder") {
      o.cylinder.crest = !o.dip;
      grid = generate_cylinder(o.cylinder);
    }
    if (name == "sphere-cap") grid = generate_sphere_cap(o.sphere);
    if (name == "gaussian-hills") {
      for (const auto& spec : o.hill_specs) {
        o.hills.hills.push_back({Vec2(spec.at(0), spec.at(1)), spec.at(2), spec.at(3)});
      }
      grid = generate_gaussian_hills(o.hills);
    }
    if (name == "bowl") grid = generate_bowl(o.bowl);
    if (name == "eldershaw-yim") grid = generate_eldershaw_yim(o.eldershaw_yim);
    write_esri_ascii(grid, o.output);
  });
}

/// How a command reads its DEM besides its path: --reproject and --band, declared once for
/// every command that takes a terrain (load_terrain).
void add_raster_options(CLI::App& command, std::string& reproject, int& band) {
  command.add_option("--reproject", reproject, ex::kReprojectHelp)
      ->check(CLI::IsMember({std::string("none"), std::string("auto")}))
      ->capture_default_str();
  command.add_option("--band", band, ex::kBandHelp)->check(CLI::Range(1, 65535));
}

/// The inputs shared by `talus limits` and `talus profile`: terrain, path,
/// vehicle and the optional smoothing of the terrain fit.
template <typename Request>
void add_path_input_options(CLI::App& command, Request& request) {
  command.add_option("--terrain", request.terrain, ex::kTerrainHelp)->required();
  add_raster_options(command, request.reproject, request.band);
  command
      .add_option("--path", request.path,
                  "path CSV: header `x,y`, then one way point per line in the terrain's "
                  "coordinates [m]; the path is the interpolating cubic B-spline through them "
                  "(chord-length parameters) lifted onto the terrain")
      ->required();
  command.add_option("--vehicle", request.vehicle, "vehicle YAML (see data/vehicles/README.md)")
      ->required();
  command.add_option("--smoothing", request.smoothing,
                     "curvature weight lambda > 0 of the smoothing fit; without it the surface "
                     "interpolates every node");
}

}  // namespace

/// Throws InputError if `args` (a command line without the program name)
/// names a command or an option that `app` does not have.
void check_command_line(CLI::App& app, const std::vector<std::string>& args) {
  CLI::App* current = &app;
  std::string path = "talus";
  for (const std::string& arg : args) {
    if (arg.rfind("--", 0) == 0) {
      const std::string name = arg.substr(0, arg.find('='));
      if (current->get_option_no_throw(name) == nullptr) {
        throw InputError("`" + path + "` has no option " + talus::printable(name) + " (see talus " +
                         path.substr(std::min<std::size_t>(path.size(), 6)) + " --help)");
      }
    } else {
      for (CLI::App* sub : current->get_subcommands([](CLI::App*) { return true; })) {
        if (sub->get_name() != arg) continue;
        current = sub;
        path += " " + arg;
        break;
      }
    }
  }
}

int run_cli(const std::vector<std::string>& args, bool check_only);

/// `talus sweep`: runs the cases in worker processes that call run_cli().
void add_sweep_command(CLI::App& app, ex::SweepRequest& request) {
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "run a parameter sweep: CONFIG.yaml names a job (plan, profile, navigate, baseline NAME, "
      "noop) and "
      "a design over its parameters (grid, list or seeded random samples); each case runs in "
      "its own worker process and its result is appended to DIR/results.jsonl as it ends "
      "(every input parameter, status, the job's key figures, seconds, attempts, host, rank). "
      "DIR also gets results.csv (one row per case, design order), report.md with a figure "
      "per swept parameter, and cases/ID/ with each case's files. Rerunning on DIR resumes: "
      "finished case ids are skipped. A worker that crashes or exceeds the case time limit is "
      "retried (config `retries`, default 2), then recorded as failed. Exit code 0 when every "
      "case has a result (some may be failed or error: see results.csv), 1 on a bad config "
      "(one line on stderr, before any case runs). Under mpirun each rank runs every K-th "
      "case and writes its own results file; rank 0 writes results.csv");
  sweep->add_option("CONFIG", request.config, "sweep configuration (YAML)")->required();
  sweep->add_option("--out", request.output_dir, "output folder (created if needed)")->required();
  sweep->add_option("--jobs", request.jobs, "worker processes at a time; 0 = the core count")
      ->capture_default_str();
  sweep->add_flag("--resume", request.resume,
                  "resume the sweep in DIR (also the default when DIR has results)");
  sweep->add_flag("--dry-run", request.dry_run, "list the cases (id, parameters) and stop");
  sweep->add_flag("!--quiet", request.progress,
                  "no progress on stderr (a rewritten line on a terminal, else a line per case)");
  sweep->add_option("--case-time-limit", request.case_time_limit,
                    "seconds a case may run before its worker is killed (overrides the "
                    "config's case_time_limit, default 600)");
  sweep->callback([&request]() {
    request.run_command = [](const std::vector<std::string>& args) { return run_cli(args, false); };
    request.check_command = [](const std::vector<std::string>& args) { run_cli(args, true); };
    std::cout << ex::sweep(request) << "\n";
  });
}

int run_cli(const std::vector<std::string>& args, bool check_only) {
  CLI::App app{
      "Talus: time-optimal trajectory planning of ground vehicles over rough terrain.\n"
      "Units are SI; x east, y north, z up (see README, Conventions)."};
  app.name("talus");
  app.require_subcommand(1);

  CLI::App* terrain = app.add_subcommand("terrain", "inspect, generate and fit terrains");
  terrain->require_subcommand(1);

  std::string info_path, info_reproject = "none";
  int info_band = 0;
  CLI::App* info = terrain->add_subcommand(
      "info",
      "print JSON: ncols, nrows, cellsize, xmin, xmax, ymin, ymax (node domain: the "
      "centres of the edge cells), zmin, zmax, voids, crs {label, epsg, name, wkt} (null when "
      "the file has none), driver (esri-ascii or GDAL's driver name), reprojected, source_crs");
  info->add_option("FILE", info_path, ex::kTerrainHelp)->required();
  add_raster_options(*info, info_reproject, info_band);
  info->callback([&]() {
    std::cout << ex::terrain_info(info_path, info_reproject, info_band).dump(2) << "\n";
  });

  ex::TerrainFitRequest fit_request;
  std::string fill;
  CLI::App* fit = terrain->add_subcommand(
      "fit",
      "fit a bicubic B-patch and print JSON: max_node_residual, rms_residual [m], "
      "fit_seconds, patches");
  fit->add_option("FILE", fit_request.path, ex::kTerrainHelp)->required();
  add_raster_options(*fit, fit_request.reproject, fit_request.band);
  fit->add_option("--smoothing", fit_request.smoothing,
                  "curvature weight lambda > 0 (dimensionless) of the smoothing fit; without it "
                  "the surface interpolates every node");
  fit->add_option("--fill", fill, "fill NODATA nodes before fitting")
      ->check(CLI::IsMember({"nearest"}));
  fit->callback([&]() {
    fit_request.fill_nearest = (fill == "nearest");
    std::cout << ex::terrain_fit(fit_request).dump(2) << "\n";
  });

  ex::TraversabilityRequest traversability_request;
  CLI::App* traversability = terrain->add_subcommand(
      "traversability",
      "speed limits of a vehicle's straight pass over every node of a DEM, in --headings "
      "equally spaced headings (2 pi k / N, counter-clockwise from east): writes OUT.tif, a "
      "float32 GeoTIFF in the DEM's CRS and grid with bands speed_limit_heading_000 ... [m/s; "
      "inf = nothing limits it, 0 = no speed admissible], speed_limit_min [m/s], "
      "binding_constraint (what sets the minimum: 0 none, 1 sliding, 2 tipover, 3 contact, 4 "
      "max_speed, 5 pitchover, 6 drive, 7 brake) and untraversable (1 where no heading admits "
      "any speed), NODATA -9999 where the DEM has none; and OUT.png, a preview of "
      "speed_limit_min (red 0 to green the largest, dark red untraversable); prints a JSON "
      "summary. On bad input: one line on stderr, nothing written");
  traversability->add_option("--terrain", traversability_request.terrain, ex::kTerrainHelp)
      ->required();
  traversability
      ->add_option("--vehicle", traversability_request.vehicle,
                   "vehicle YAML (see data/vehicles/README.md)")
      ->required();
  traversability
      ->add_option("--headings", traversability_request.headings, "number of headings, 1 to 360")
      ->capture_default_str();
  traversability->add_option("--smoothing", traversability_request.smoothing,
                             "curvature weight lambda > 0 of the smoothing fit; without it the "
                             "surface interpolates every node (NODATA filled by the nearest "
                             "node for the fit, NODATA in the output)");
  add_raster_options(*traversability, traversability_request.reproject,
                     traversability_request.band);
  traversability->add_option("-o,--output", traversability_request.output, "output GeoTIFF")
      ->required();
  traversability->callback(
      [&]() { std::cout << ex::terrain_traversability(traversability_request).dump(2) << "\n"; });

  GenerateOptions generate_options;
  add_generate_commands(*terrain, generate_options);

  ex::LimitsRequest limits_request;
  CLI::App* limits = app.add_subcommand(
      "limits",
      "speed limits of a vehicle along a path on a terrain: writes CSV columns "
      "s,x,y,z,v_min,v_max,binding,k_t,k_q,k_r,kappa_n,kappa_g (SI units; v_max `inf` where "
      "nothing limits it, 0 where no speed is admissible; binding = sliding, tipover, contact, "
      "max_speed or none) and prints a JSON summary: stations, length_m, min_v_max, "
      "untraversable_stations, binding_counts, seconds");
  add_path_input_options(*limits, limits_request);
  limits->add_option(
      "--stations", limits_request.stations,
      "number of stations (2 to 10000000), equally spaced in the curve parameter; default: "
      "one per metre of the way points' polyline, ceil(length) + 1, clamped to "
      "[100, 100000]");
  limits->add_option("-o,--output", limits_request.output, "output .csv file")->required();
  limits->callback([&]() { std::cout << ex::limits(limits_request).dump(2) << "\n"; });

  ex::ProfileRequest profile_request;
  int exit_code = 0;  // set by commands whose outcome is not an error (profile: 2 = infeasible)
  CLI::App* profile = app.add_subcommand(
      "profile",
      "time-optimal velocity profile of a vehicle along a path on a terrain, from speed v0 to "
      "v1 (TOPP-RA reachability analysis; every constraint holds at every station). Writes CSV "
      "columns s,x,y,z,v,a,t,v_max,binding (SI units: s arc length [m], v speed [m/s], a = "
      "s'' of the step that starts there [m/s^2], t time of arrival [s]; v_max `inf` where "
      "nothing limits it, 0 where no speed is admissible; binding = what sets v_max, as in "
      "`talus limits`) and prints one JSON object: status (ok | infeasible), travel_time [s] "
      "(null when infeasible), stations, length_m, switching_points [{station, s, from, to}] "
      "(accelerate | decelerate | limit), solve_seconds (the solver alone), limits_seconds, "
      "merged_stations, peak_speed, message, infeasible_station, infeasible_s, "
      "infeasible_binding (null when ok), start_speed, end_speed, fit, smoothing, output, "
      "seconds. Exit code 0 when a profile exists; 2 when the path is infeasible (the JSON is "
      "still printed and OUT.csv still written, with s,x,y,z,v_max,binding as usual and v = 0, "
      "a = 0, t = inf at every station); 1 on bad input, including a start or end speed above "
      "the speed limit there (one line on stderr, nothing written)");
  add_path_input_options(*profile, profile_request);
  profile->add_option("--v0", profile_request.start_speed, "speed at the start [m/s], >= 0")
      ->capture_default_str();
  profile->add_option("--v1", profile_request.end_speed, "speed at the end [m/s], >= 0")
      ->capture_default_str();
  profile->add_option("--stations", profile_request.stations,
                      "number of stations (2 to 10000000), equally spaced in the curve "
                      "parameter; default: " +
                          ex::default_profile_stations_text());
  profile->add_option("-o,--output", profile_request.output, "output .csv file")->required();
  profile->callback([&]() {
    const ex::ProfileOutcome outcome = ex::profile(profile_request);
    std::cout << outcome.summary.dump(2) << "\n";
    if (!outcome.feasible) exit_code = ex::kInfeasibleExitCode;
  });

  ex::PlanRequest plan_request;
  CLI::App* plan = app.add_subcommand(
      "plan",
      "plan a time-optimal trajectory for a vehicle from a start to a goal on a terrain. "
      "--stage global runs the minimum-time search over a lattice on the fitted surface (edge "
      "cost J = integral of ds / v_max, the travel time at the speed limit) and returns up to "
      "--candidates distinct corridors. --stage full (the default) then optimises each "
      "candidate locally: a clamped cubic B-spline with --control-points control points, start "
      "and goal fixed, minimising the travel time of its exact time-optimal velocity profile "
      "(from --v0 to --v1) with --solver (ipopt by default, with the exact adjoint gradient), "
      "or with --formulation simultaneous one smooth Ipopt NLP in the control points and the "
      "squared speeds at the stations (it can start from a fit without an admissible profile), "
      "and keeps the best. Both stages write, in --out "
      "DIR (created if needed): candidates.csv (columns candidate,x,y: the lattice vertices of "
      "each candidate from the start node to the goal node, candidate 0 the best), "
      "fields.csv (x,y,cost_from_start,cost_to_goal [s] at every lattice node, `inf` = not "
      "reachable, `nan` = not computed; skipped above 4000000 nodes) and summary.json, and "
      "print the same JSON: status (ok | unreachable | infeasible), message, candidates "
      "[{cost_seconds, length_m, vertices}], nodes, edges_evaluated, expanded, "
      "reachable_nodes, search_seconds, start_node, goal_node ([x, y] of the snapped lattice "
      "nodes), lattice_spacing, connectivity, ... --stage full also writes trajectory.csv "
      "(s,x,y,z,v,a,t,v_max,binding of the best trajectory, profile recomputed at "
      "--station-spacing, as "
      "`talus profile`), optima.csv (candidate,s,x,y,v: every optimised candidate's profile, "
      "at most about 2000 rows each), plan.png and profile.png (gnuplot scripts and data "
      "beside them), and adds travel_time [s] (the best), global_travel_time (the best "
      "candidate's initial B-spline fit, same stations), improvement_percent, optima "
      "[{travel_time, initial_time, solver, solver_status, formulation, converged, phase, "
      "nlp_travel_time, iterations, evaluations, "
      "optimality (projected-gradient norm [s/m]), ...}] and seconds {fit, global, local, "
      "profile, plots, total}. --time-limit SECONDS bounds the whole plan: on it the status is "
      "time_limit and the best feasible trajectory found by then is returned (message and "
      "not_optimised say which candidates were cut short or never optimised; if the global "
      "search is cut before it found a route there is no trajectory). Exit code 0 when a "
      "result exists (also with status time_limit); 2 when the goal is "
      "unreachable (also from a start or goal on untraversable terrain: the message names it), "
      "(full) every candidate's profile is infeasible, or the time limit left no "
      "trajectory (summary still written and printed); 1 on bad input: a start or goal off the "
      "map or on NODATA, a vehicle without max_speed, a malformed X,Y, an unknown "
      "solver (one line on stderr, nothing written)");
  plan->add_option("--terrain", plan_request.terrain, ex::kTerrainHelp)->required();
  add_raster_options(*plan, plan_request.reproject, plan_request.band);
  plan->add_flag("--rasters", plan_request.rasters,
                 "also write cost_to_go.tif (float32 GeoTIFF on the lattice in the DEM's CRS: "
                 "bands cost_from_start, cost_to_goal [s; inf = not reachable, NODATA = not "
                 "computed] and unreachable (1/0)) and trajectory.geojson (the best "
                 "trajectory as a LineString and every candidate's lattice path, per RFC 7946: "
                 "WGS 84 longitude, latitude, with each point's x, y in the DEM's CRS kept as "
                 "the property projected_coordinates; a DEM without a CRS keeps its x, y, "
                 "noted in coordinates_note)");
  plan->add_option("--start", plan_request.start, "start X,Y in the terrain's frame [m]")
      ->required();
  plan->add_option("--goal", plan_request.goal, "goal X,Y in the terrain's frame [m]")->required();
  plan->add_option("--vehicle", plan_request.vehicle,
                   "vehicle YAML with a finite max_speed (see data/vehicles/README.md)")
      ->required();
  plan->add_option("--stage", plan_request.stage,
                   "full = lattice search + local optimisation of each candidate; global = the "
                   "lattice search only")
      ->capture_default_str()
      ->check(CLI::IsMember({std::string(ex::kPlanStageFull), std::string(ex::kPlanStageGlobal)}));
  ex::add_parameter_options(*plan, talus::planner_parameters(), plan_request.planner);
  plan->add_option("--smoothing", plan_request.smoothing,
                   "curvature weight lambda > 0 of the smoothing fit; without it the surface "
                   "interpolates every node");
  plan->add_option("--surface-degree", plan_request.surface_degree,
                   "degree of the interpolating B-patch: 3 (bicubic) or 5 (biquintic: "
                   "curvature with continuous derivatives, so the simultaneous NLP and --polish "
                   "converge far more often on rough ground; not with --smoothing)")
      ->capture_default_str();
  plan->add_option("--v0", plan_request.start_speed, "speed at the start [m/s], >= 0, --stage full")
      ->capture_default_str();
  plan->add_option("--v1", plan_request.end_speed, "speed at the goal [m/s], >= 0, --stage full")
      ->capture_default_str();
  plan->add_option("--start-heading", plan_request.start_heading,
                   "heading the path leaves the start with [rad], counter-clockwise from east; "
                   "kept exactly by the local stage (the global stage's corridors do not see "
                   "it). Default: free");
  plan->add_option("--goal-heading", plan_request.goal_heading,
                   "heading the path arrives at the goal with [rad], counter-clockwise from "
                   "east; as --start-heading. Default: free");
  plan->add_option("--out", plan_request.output_dir, "output folder (created if needed)")
      ->required();
  plan->add_flag("!--quiet", plan_request.progress,
                 "no progress line on stderr (it is shown only when stderr is a terminal: the "
                 "stage, candidate k of n, elapsed and estimated remaining time)");
  plan->add_flag("!--no-figures", plan_request.figures,
                 "skip plan.png and profile.png (and their gnuplot files), e.g. in sweeps");
  plan->callback([&]() {
    const ex::PlanOutcome outcome = ex::plan(plan_request);
    std::cout << outcome.summary.dump(2) << "\n";
    if (!outcome.reachable) exit_code = ex::kUnreachableExitCode;
  });

  ex::SimulateRequest simulate_request;
  CLI::App* simulate = app.add_subcommand(
      "simulate",
      "drive a planned trajectory (the trajectory.csv of `talus plan`) with the rigid-body "
      "vehicle simulation (4 spring-damper wheels, brush tyres, CVODE BDF; curvature steering "
      "law and speed PI) and report the margins it kept (peak lateral load ratio, minimum normal "
      "load, "
      "peak slip) and any failure (rollover, side_slip, loss_of_contact, stall). Writes "
      "DIR/trace.csv and DIR/summary.json; exit code 2 when the goal was not reached");
  simulate->add_option("--terrain", simulate_request.terrain, ex::kTerrainHelp)->required();
  add_raster_options(*simulate, simulate_request.reproject, simulate_request.band);
  simulate
      ->add_option("--vehicle", simulate_request.vehicle,
                   "vehicle YAML with a body (mass, ...; data/vehicles/README.md)")
      ->required();
  simulate
      ->add_option("--trajectory", simulate_request.trajectory,
                   "trajectory CSV naming the columns x, y, v (trajectory.csv of talus plan)")
      ->required();
  simulate
      ->add_option("--speed-scale", simulate_request.speed_scale,
                   "drive at this multiple of the planned speed (> 0)")
      ->capture_default_str();
  simulate
      ->add_option("--steering-law", simulate_request.steering_law,
                   "the tracker's steering: curvature (reference curvature with lateral, course "
                   "and yaw-rate feedback) or pure_pursuit")
      ->check(CLI::IsMember({std::string("curvature"), std::string("pure_pursuit")}))
      ->capture_default_str();
  simulate->add_option("--smoothing", simulate_request.smoothing,
                       "lambda of the smoothing fit (use the plan's); default interpolating fit");
  simulate
      ->add_option("--trace-interval", simulate_request.trace_interval,
                   "trace.csv sample interval [s]")
      ->capture_default_str();
  simulate->add_flag("!--quiet", simulate_request.progress,
                     "no progress line on stderr (shown only when stderr is a terminal)");
  simulate->add_option("--out", simulate_request.output_dir, "output folder (created if needed)")
      ->required();
  simulate->callback([&]() {
    const ex::SimulateOutcome outcome = ex::simulate(simulate_request);
    std::cout << outcome.summary.dump(2) << "\n";
    if (!outcome.reached) exit_code = ex::kSimulateNotReachedExitCode;
  });

  ex::NavigateRequest navigate_request;
  CLI::App* navigate = app.add_subcommand(
      "navigate",
      "the layered scheme of Iagnemma, Shimoda & Shiller (IROS 2008): a time-optimal plan on "
      "coarse map data (every --coarse-factor-th node of the terrain), its trajectory as "
      "waypoints with their profile speeds, and potential-field navigation of the simulated "
      "vehicle through them on the fine terrain, with the model-based lookahead (near-optimal) "
      "or, with --no-lookahead, without (standard). Writes in --out DIR: trace.csv (t,x,y,z,"
      "roll,pitch,yaw,v,kappa,slip_angle,desired_v,lookahead_cap), waypoints.csv (x,y,v), the "
      "paper's figures 7-9 (navigation_map.png, navigation_speed.png, navigation_angles.png; "
      "--no-figures skips them) and summary.json (status reached | failed | timeout | no_plan, "
      "failure, navigation_time, "
      "optimal_time, time_increase, ...), and prints the summary. Exit code 0 when the goal was "
      "reached, 2 when not (outputs written), 1 on bad input (one line on stderr, nothing "
      "written)");
  navigate->add_option("--terrain", navigate_request.terrain, ex::kTerrainHelp)->required();
  add_raster_options(*navigate, navigate_request.reproject, navigate_request.band);
  navigate
      ->add_option("--vehicle", navigate_request.vehicle,
                   "vehicle YAML with a body (mass, ...) and a finite max_speed, e.g. "
                   "data/vehicles/iagnemma_ugv.yaml")
      ->required();
  navigate->add_option("--start", navigate_request.start, "start X,Y [m]")->required();
  navigate->add_option("--goal", navigate_request.goal, "goal X,Y [m]")->required();
  navigate
      ->add_option("--coarse-factor", navigate_request.coarse_factor,
                   "the plan's map keeps every K-th node of the terrain (>= 1)")
      ->capture_default_str();
  navigate->add_flag("!--no-lookahead", navigate_request.lookahead,
                     "the standard potential field, without the model-based lookahead");
  navigate->add_flag("--detect-hazards", navigate_request.detect_hazards,
                     "also avoid the hazards the vehicle's sensor sees on the fine map (nodes "
                     "steeper than atan(min(mu, b/h)) or with a 3x3 relief above the wheel "
                     "radius, within 3 m); off by default: with the paper's hazard gains the "
                     "field then turns away from its waypoints");
  navigate
      ->add_option("--time-limit", navigate_request.time_limit,
                   "simulated time limit of the navigation [s]")
      ->capture_default_str();
  navigate->add_option("--seed", navigate_request.seed, "the field's randomisation")
      ->capture_default_str();
  navigate
      ->add_option("--trace-interval", navigate_request.trace_interval,
                   "trace.csv sample interval [s]")
      ->capture_default_str();
  navigate->add_flag("!--quiet", navigate_request.progress,
                     "no progress line on stderr (shown only when stderr is a terminal)");
  navigate->add_flag("!--no-figures", navigate_request.figures,
                     "skip navigation_map.png, navigation_speed.png and navigation_angles.png");
  navigate->add_option("--out", navigate_request.output_dir, "output folder (created if needed)")
      ->required();
  navigate->callback([&]() {
    const ex::NavigateOutcome outcome = ex::navigate(navigate_request);
    std::cout << outcome.summary.dump(2) << "\n";
    if (!outcome.reached()) exit_code = ex::kNavigateNotReachedExitCode;
  });

  CLI::App* baseline = app.add_subcommand(
      "baseline",
      "kinematic baseline planners of the literature (`talus baseline NAME`, one "
      "subcommand per registered baseline)");
  baseline->require_subcommand(1);
  // One subcommand per registry entry: the shared query flags, then the
  // baseline's own options as --KEY (flags for booleans), passed on as text.
  struct BaselineFlags {
    ex::BaselineRequest request;
    std::map<std::string, std::string> values;
    std::map<std::string, bool> flags;
  };
  std::list<BaselineFlags> baseline_flags;  // stable addresses for CLI11's bindings
  const BaselineRegistry& baselines = planner_registry();
  for (const std::string& name : baselines.names()) {
    const BaselineEntry& entry = baselines.entry(name);
    BaselineFlags& f = baseline_flags.emplace_back();
    f.request.baseline = entry.name;
    CLI::App* sub = baseline->add_subcommand(
        entry.name, entry.summary + ". " + ex::baseline_output_help(entry.name));
    sub->add_option("--terrain", f.request.terrain, ex::kTerrainHelp)->required();
    add_raster_options(*sub, f.request.reproject, f.request.band);
    sub->add_option("--start", f.request.start,
                    "start configuration X,Y,THETA: position [m] in the terrain's frame, "
                    "heading [rad] counter-clockwise from east")
        ->required();
    sub->add_option("--goal", f.request.goal, "goal configuration X,Y,THETA [m, m, rad]")
        ->required();
    sub->add_option("--vehicle", f.request.vehicle, ex::kBaselineVehicleHelp);
    for (const BaselineOptionSpec& spec : entry.options) {
      const std::string flag = "--" + spec.key;
      if (spec.flag) {
        sub->add_flag(flag, f.flags[spec.key], spec.help);
        continue;
      }
      std::string& value = f.values[spec.key];
      value = spec.default_value;
      CLI::Option* option = sub->add_option(flag, value, spec.help);
      if (spec.required) option->required();
      if (!spec.default_value.empty()) option->capture_default_str();
    }
    sub->add_option("--out", f.request.output_dir, "output folder (created if needed)")->required();
    sub->callback([&f, &exit_code]() {
      for (const auto& [key, value] : f.values) f.request.options[key] = value;
      for (const auto& [key, on] : f.flags) f.request.options[key] = on ? "true" : "false";
      const ex::BaselineOutcome outcome = ex::run_baseline(f.request);
      if (!outcome.summary.is_null()) std::cout << outcome.summary.dump(2) << "\n";
      if (!outcome.found) exit_code = ex::kBaselineNoPathExitCode;
    });
  }

  ex::PlacementRequest placement_request;
  CLI::App* placement = app.add_subcommand("placement", ex::kPlacementHelp);
  placement->add_option("--terrain", placement_request.terrain, ex::kTerrainHelp)->required();
  placement
      ->add_option("--robot", placement_request.robot,
                   "robot YAML (type wheeled or articulated_chassis, data/robots/README.md)")
      ->required();
  placement
      ->add_option("--configs", placement_request.configs,
                   "configurations CSV with the header x,y,theta")
      ->required();
  placement->add_option("-o,--output", placement_request.output, "output .csv file")->required();
  add_raster_options(*placement, placement_request.reproject, placement_request.band);
  placement->callback([&]() { std::cout << ex::run_placement(placement_request).dump(2) << "\n"; });

  std::string experiment_name, out_dir = "talus-out", data_dir;
  bool quick = false;
  CLI::App* experiment = app.add_subcommand(
      "experiment", "run a paper-reproduction experiment (`talus experiment list` lists them)");
  experiment->add_option("NAME", experiment_name, "experiment name, or `list`")->required();
  experiment->add_option("--out", out_dir, "results go to OUT/NAME/")->capture_default_str();
  experiment->add_option("--data", data_dir, "folder with the bundled terrain/ DEMs");
  experiment->add_flag("--quick", quick, "smaller problem sizes (smoke runs)");
  bool experiment_quiet = false;
  experiment->add_flag("--quiet", experiment_quiet,
                       "no progress on stderr (a progress line when stderr is a terminal, and "
                       "one line per finished case)");
  experiment->callback([&]() {
    const std::vector<ex::Experiment> experiments = ex::all_experiments();
    if (experiment_name == "list") {
      for (const ex::Experiment& e : experiments)
        std::cout << e.name << "\t" << e.description << "\n";
      return;
    }
    for (const ex::Experiment& e : experiments) {
      if (e.name != experiment_name) continue;
      ex::ExperimentContext context;
      const std::filesystem::path folder = std::filesystem::path(out_dir) / e.name;
      context.data_dir = ex::find_data_dir(data_dir);
      context.quick = quick;
      context.progress =
          std::make_shared<talus::ProgressLine>("experiment " + e.name, !experiment_quiet);
      context.run_command = [](const std::vector<std::string>& args) {
        return run_cli(args, false);
      };
      context.check_command = [](const std::vector<std::string>& args) { run_cli(args, true); };
      talus::OutputFolder out(folder);
      context.output_dir = out.staging();
      e.run(context);
      context.summary->write(context.output_dir / "summary.json", e.name, quick);
      out.commit();
      std::cout << "wrote " << (folder / "report.md").string() << "\n";
      return;
    }
    throw InputError("unknown experiment '" + experiment_name + "' (run `talus experiment list`)");
  });

  ex::SweepRequest sweep_request;
  add_sweep_command(app, sweep_request);

  if (check_only) {
    check_command_line(app, args);
    return 0;
  }
  std::vector<const char*> argv = {"talus"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "talus: error: " << talus::printable(e.what(), 600) << " (see --help)\n";
    return 1;
  } catch (const talus::Error& e) {
    std::cerr << "talus: error: " << talus::printable(e.what(), 600) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "talus: error: out of memory (a larger input or option than this machine "
                 "holds; see the memory budget in the README)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "talus: error: " << talus::printable(e.what(), 600) << "\n";
    return 1;
  }
  return exit_code;
}

int main(int argc, char** argv) {
  talus::exit_cleanly_on_signals();
  return run_cli(std::vector<std::string>(argv + 1, argv + argc), false);
}
