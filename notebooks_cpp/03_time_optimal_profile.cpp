// Notebook 03 — the exact time-optimal velocity profile along a given path:
// the fastest way to drive it from rest to rest without breaking any
// constraint, where it switches between full drive, full braking and riding
// the limit, and how its travel time converges with the station spacing.
//
//   build/notebooks_cpp/03_time_optimal_profile [--quick] [--out DIR] [--data DIR]
#include <algorithm>
#include <cmath>

#include "notebook.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/profile_convergence.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"

using namespace talus;
using namespace talus::notebooks;

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "03_time_optimal_profile", "03 · The time-optimal velocity profile");
    const Vehicle rover = load_vehicle(nb.data("vehicles/rover.yaml"));
    const ElevationGrid grid = west_bijou_at_rover_scale(nb);
    const BPatch terrain = BPatch::fit_smoothing(grid, 1.0);
    const Curve2 curve = Curve2::interpolate(rover_path_points());

    nb.section("The profile");
    nb.say(
        "The path and rover of notebook 02. Along a fixed path the state is one number, "
        "the speed ṡ, and the control one number, s̈. At each station the limits say which "
        "(ṡ², s̈) are admissible; the solver (reachability analysis, TOPP-RA) finds the "
        "profile that is as fast as possible everywhere: it accelerates at the largest "
        "admissible s̈, brakes at the smallest exactly early enough for the next slow "
        "spot, and rides the limit curve in between. `evaluate_trajectory` is the one rule "
        "every part of Talus uses to turn a curve into a travel time.");
    TrajectoryOptions options;                          // rest to rest
    options.station_spacing = nb.quick() ? 0.25 : 0.0;  // 0 = the scale-aware default
    const Trajectory trajectory = evaluate_trajectory(terrain, rover, curve, options);
    if (!trajectory.feasible()) throw Error("no profile: " + trajectory.message);
    const TimeOptimalProfile& p = trajectory.profile;

    Series v{"v(s), time-optimal", {}, {}, "lines lw 2.5 lc rgb '#2c7fb8'"};
    Series v_max{"v_{max}(s)", {}, {}, "lines lw 1.5 lc rgb '#d73027'"};
    Series a{"s̈(s)", {}, {}, "steps lw 1.5 lc rgb 'black'"};
    Series switches{"switching points", {}, {}, "points pt 7 ps 1.2 lc rgb 'black'"};
    double lower_bound = 0.0, peak = 0.0;  // J = time at the speed limit, same quadrature
    for (std::size_t k = 0; k < p.s.size(); ++k) {
      v.x.push_back(p.s[k]), v.y.push_back(p.v[k]);
      v_max.x.push_back(p.s[k]), v_max.y.push_back(std::min(p.v_max[k], rover.max_speed));
      a.x.push_back(p.s[k]), a.y.push_back(p.a[k]);
      peak = std::max(peak, p.v[k]);
      if (k > 0) lower_bound += 2.0 * (p.s[k] - p.s[k - 1]) / (p.v_max[k - 1] + p.v_max[k]);
    }
    for (const SwitchingPoint& sp : p.switching_points) {
      switches.x.push_back(sp.s), switches.y.push_back(p.v[sp.station]);
    }
    nb.figure("The profile under its limit", nb.plot("profile", "Time-optimal profile", "s [m]",
                                                     "speed [m/s]", {v_max, v, switches}));
    nb.figure("Its acceleration",
              nb.plot("acceleration", "s̈ of the time-optimal profile", "s [m]", "s̈ [m/s²]", {a}));
    nb.say("Travel time " + num("%.2f", p.travel_time) + " s over " +
           num("%.1f", trajectory.length()) + " m (" + std::to_string(p.s.size()) +
           " stations), peak " + num("%.2f", peak) + " m/s, " +
           std::to_string(p.switching_points.size()) +
           " switching points. Driving at v_max everywhere would take J = ∫ ds / v_max = " +
           num("%.2f", lower_bound) +
           " s — the global search's cost (notebook 04) — but no vehicle can: it must start and "
           "stop, and brake before each slow spot.");

    Table first({"s [m]", "from", "to"});
    for (std::size_t k = 0; k < std::min<std::size_t>(p.switching_points.size(), 6); ++k) {
      const SwitchingPoint& sp = p.switching_points[k];
      first.row(
          {num("%.2f", sp.s), std::string(to_string(sp.from)), std::string(to_string(sp.to))});
    }
    nb.table(first);

    const ProfileVerification verdict = verify_profile(*trajectory.limits, p);
    nb.check(verdict.status == VerificationStatus::kPass,
             "an independent check re-evaluates the vehicle at every station: v ≤ v_max, every "
             "step's s̈ admissible at both ends, times consistent (" +
                 std::string(to_string(verdict.status)) + ")");
    nb.check(p.v.front() == 0.0 && p.v.back() == 0.0, "it starts and ends at rest");
    nb.check(p.travel_time > lower_bound,
             "it is slower than J = ∫ ds / v_max, the time at the limit (" +
                 num("%.2f", p.travel_time) + " s > " + num("%.2f", lower_bound) + " s)");

    nb.section("Convergence in the station spacing");
    nb.say(
        "The limits are sampled at stations, and the profile is exact for those samples; "
        "the error in the travel time is first order in the spacing. Doubling the station "
        "count should roughly halve it.");
    ProfileConvergenceOptions study;
    study.station_counts =
        nb.quick() ? std::vector<std::size_t>{100, 200, 400, 800, 1600}
                   : std::vector<std::size_t>{100, 200, 400, 800, 1600, 3200, 6400, 12800};
    const SurfacePath path(terrain, curve);
    const ProfileConvergence c = profile_convergence(rover, path, study);
    Table levels({"stations", "spacing [m]", "travel time [s]", "vs finest"});
    Series error{"|relative error|", {}, {}, "linespoints lw 2 pt 7 lc rgb '#2c7fb8'"};
    bool shrinking = true;
    for (std::size_t k = 0; k < c.levels.size(); ++k) {
      const ConvergenceLevel& l = c.levels[k];
      levels.row({std::to_string(l.stations), num("%.3f", l.mean_spacing),
                  num("%.4f", l.travel_time), num("%+.3f", 100.0 * l.error) + " %"});
      if (k + 1 < c.levels.size()) {
        error.x.push_back(l.mean_spacing), error.y.push_back(std::abs(l.error));
        if (k > 0) shrinking = shrinking && std::abs(l.error) < std::abs(c.levels[k - 1].error);
      }
    }
    nb.table(levels);
    nb.figure(
        "Relative error against the finest level",
        nb.plot("convergence", "Travel-time error against the station spacing",
                "mean station spacing [m]", "|T / T_{finest} − 1|", {error}, "set logscale xy\n"));
    nb.check(c.status == ConvergenceStatus::kOk && shrinking,
             "the error against the finest level shrinks at every doubling");
    const double second = std::abs(c.levels[c.levels.size() - 2].error);
    nb.check(second < 0.01, "one level before the finest, the travel time is within 1 % (" +
                                num("%.3f", 100.0 * second) + " %)");
    return nb.finish();
  });
}
