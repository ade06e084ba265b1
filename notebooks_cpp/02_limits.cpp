// Notebook 02 — what bounds a vehicle's speed and acceleration at each
// station of a path: the speed limit v_max(s), the constraint that sets it,
// and the admissible range of s̈ at a given speed.
//
//   build/notebooks_cpp/02_limits [--quick] [--out DIR] [--data DIR]
#include <algorithm>
#include <cmath>
#include <numbers>

#include "notebook.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/limit_summary.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/trajectory.hpp"

using namespace talus;
using namespace talus::notebooks;

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "02_limits", "02 · Speed limits and acceleration bounds");
    const Vehicle rover = load_vehicle(nb.data("vehicles/rover.yaml"));
    nb.say(
        "The vehicle is the bundled rover (`data/vehicles/rover.yaml`), a point mass with "
        "friction μ = " +
        num("%.2f", rover.friction) + ", centre of mass h = " + num("%.2f", rover.cg_height) +
        " m above the ground and b = " + num("%.2f", rover.half_track) +
        " m from the wheel line, top speed " + num("%.0f", rover.max_speed) +
        " m/s. Along a path it must keep three things true at every station: the wheels "
        "stay on the ground (*contact*), the friction force stays inside μ times the load "
        "(*sliding*), and the lateral force does not tip it over (*tip-over*, |f_q| ≤ (b/h) "
        "R). Each gives an interval of admissible ṡ²; v_max is the top of their "
        "intersection.");

    nb.section("A check against a closed form: a flat circle");
    // On level ground the load is g and the lateral force v² κ_g, so sliding
    // allows v² κ_g ≤ μ g, and tip-over v² κ_g ≤ (b/h) g. The rover has
    // b/h = 1.2 > μ = 0.7: it slides before it tips.
    const double radius = 10.0;
    ElevationGrid flat(61, 61, 1.0, -30.0, -30.0);  // z = 0 everywhere
    const BPatch plane = BPatch::interpolate(flat);
    std::vector<Vec2> ring;
    for (int k = 0; k <= 24; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 24.0;
      ring.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    const SurfacePath circle(plane, Curve2::interpolate(ring));
    const VelocityLimits on_circle(rover, circle, 200);
    double worst = 0.0, slowest = INFINITY, fastest = 0.0;
    bool all_sliding = true;
    for (std::size_t k = 0; k < on_circle.size(); ++k) {
      const double v = on_circle.limits(k).v_max, kappa = on_circle.frame(k).kappa_g;
      worst = std::max(worst, std::abs(v - std::sqrt(rover.friction * rover.gravity / kappa)));
      all_sliding = all_sliding && on_circle.limits(k).upper_binding == Constraint::kSliding;
      // The spline's ends are not periodic: judge the roundness away from them.
      if (k >= on_circle.size() / 10 && k <= 9 * on_circle.size() / 10)
        slowest = std::min(slowest, v), fastest = std::max(fastest, v);
    }
    const double closed_form = std::sqrt(rover.friction * rover.gravity * radius);
    nb.say("On a level circle of radius " + num("%.0f", radius) +
           " m (an interpolating cubic through 25 points on it) the closed form is v_max = "
           "√(μ g / κ_g) ≈ √(μ g R) = " +
           num("%.2f", closed_form) +
           " m/s; along the spline, away from its ends, v_max ranges over " + num("%.3f", slowest) +
           " .. " + num("%.3f", fastest) + " m/s.");
    nb.check(worst < 1e-9, "on the level circle v_max = √(μ g / κ_g) at every station (max error " +
                               num("%.1e", worst) + " m/s)");
    nb.check(all_sliding, "and sliding, not tip-over, sets it (b/h = 1.2 > μ = 0.7)");
    nb.check(
        std::abs(slowest / closed_form - 1) < 0.01 && std::abs(fastest / closed_form - 1) < 0.01,
        "the spline is round enough that v_max stays within 1 % of √(μ g R)");

    nb.section("Along a path across the escarpment");
    const ElevationGrid grid = west_bijou_at_rover_scale(nb);
    const BPatch terrain = BPatch::fit_smoothing(grid, 1.0);
    const SurfacePath path(terrain, Curve2::interpolate(rover_path_points()));
    const double spacing = nb.quick() ? 0.25 : default_station_spacing(terrain, rover);
    const VelocityLimits limits(rover, path, station_count(path.length(), spacing));
    nb.say(
        "The West Bijou DEM scaled by 1/25 (1 m cells, slopes unchanged, smoothing fit λ = "
        "1), and a cubic through " +
        std::to_string(rover_path_points().size()) + " way points: " + num("%.1f", path.length()) +
        " m, " + std::to_string(limits.size()) + " stations " + num("%.2f", spacing) + " m apart.");

    // Each constraint's own limit, and the limit of all of them together.
    const LimitProfile study = limit_profile(limits);
    Series all{"v_{max} (all constraints)", {}, {}, "lines lw 3 lc rgb 'black'"};
    Series sliding{"sliding alone", {}, {}, "lines lw 1.5 lc rgb '#1f77b4'"};
    Series tipover{"tip-over alone", {}, {}, "lines lw 1.5 lc rgb '#ff7f0e'"};
    Series contact{"contact alone", {}, {}, "lines lw 1.5 lc rgb '#d62728'"};
    bool is_minimum = true, below_top = true;
    for (const LimitStation& st : study.stations) {
      const double cap = 1.5 * rover.max_speed;  // draw "unlimited" at the top of the plot
      all.x.push_back(st.s), all.y.push_back(st.limits.v_max);
      sliding.x.push_back(st.s), sliding.y.push_back(std::min(st.v_sliding, cap));
      tipover.x.push_back(st.s), tipover.y.push_back(std::min(st.v_tipover, cap));
      contact.x.push_back(st.s), contact.y.push_back(std::min(st.v_contact, cap));
      const double own = std::min({st.v_sliding, st.v_tipover, st.v_contact, rover.max_speed});
      is_minimum = is_minimum && std::abs(own - st.limits.v_max) <= 1e-12 * (1.0 + own);
      below_top = below_top && st.limits.v_max <= rover.max_speed;
    }
    nb.figure("v_max(s) and each constraint's own limit",
              nb.plot("limits", "Speed limits along the path", "s [m]", "speed [m/s]",
                      {contact, tipover, sliding, all}));
    nb.check(below_top, "v_max never exceeds the rover's top speed");
    nb.check(is_minimum,
             "v_max is the smallest of the constraints' own limits at every station "
             "(re-evaluated here from each constraint alone)");

    const LimitSummary summary = summarise_limits(limits);
    Table shares({"what sets v_max", "share of stations"});
    for (const Constraint c :
         {Constraint::kSliding, Constraint::kTipover, Constraint::kContact, Constraint::kMaxSpeed})
      shares.row({std::string(to_string(c)), num("%.1f", 100.0 * summary.upper_share(c)) + " %"});
    nb.table(shares);
    const PathFrame& tight = limits.frame(summary.min_index);
    nb.say("The slowest station, s = " + num("%.1f", tight.s) + " m, allows " +
           num("%.2f", summary.min_v_max) + " m/s (κ_g = " + num("%.3f", tight.kappa_g) +
           " 1/m, a turn of radius " + num("%.1f", 1.0 / std::abs(tight.kappa_g)) +
           " m; κ_n = " + num("%.3f", tight.kappa_n) +
           " 1/m). Turns set the limit on this path; on a crest (κ_n < 0) the load drops and "
           "sliding binds earlier.");

    nb.section("Acceleration bounds");
    // At a speed v the load and the lateral force are fixed; the friction left
    // bounds the traction f_t = s̈ + g k_t, as do the drive and brake limits.
    const std::size_t at = summary.min_index;
    const double v_tight = summary.min_v_max;
    const AccelerationBounds half = limits.acceleration_bounds(at, 0.5 * v_tight);
    const AccelerationBounds top = limits.acceleration_bounds(at, 0.999 * v_tight);
    const AccelerationBounds over = limits.acceleration_bounds(at, 1.05 * v_tight);
    nb.say("At the slowest station and half its v_max, s̈ may range over [" +
           num("%.2f", half.a_min) + ", " + num("%.2f", half.a_max) + "] m/s² (set by " +
           std::string(to_string(half.lower_binding)) + " / " +
           std::string(to_string(half.upper_binding)) + "); just below v_max only [" +
           num("%.2f", top.a_min) + ", " + num("%.2f", top.a_max) +
           "] m/s², because the turn uses up the friction.");
    nb.check(half.feasible && half.a_min < half.a_max && top.feasible &&
                 top.a_max - top.a_min < half.a_max - half.a_min,
             "the admissible s̈ interval narrows as the speed approaches v_max");
    nb.check(!over.feasible, "above v_max no s̈ is admissible at all (" +
                                 std::string(to_string(over.violated)) + " fails)");
    return nb.finish();
  });
}
