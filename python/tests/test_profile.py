"""Limits and the time-optimal profile through the bindings: bit for bit the C++
results (the helper tests/reference.cpp runs the same case through the library),
and the closed forms the C++ tests use (tests/optimal/test_time_optimal_profile.cpp)."""
import math

import numpy as np
import pytest

import talus
from conftest import number_text

G = 9.81


def vehicle_file(tmp_path, mu, **limits):
    """The C++ tests' vehicle: b/h > mu, so tip-over never binds."""
    text = f"model: point_mass\nfriction: {mu!r}\ncg_height: 0.3\nhalf_track: 1.0\n"
    text += "".join(f"{k}: {v!r}\n" for k, v in limits.items())
    path = tmp_path / "vehicle.yaml"
    path.write_text(text)
    return path


def solve_straight(terrain, vehicle, a, b, v0=0.0, v1=0.0):
    """The C++ tests' solve_straight(), through the bindings."""
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(terrain)))
    path = talus.SurfacePath(surface, talus.Curve2.interpolate(np.array([a, b])))
    limits = talus.VelocityLimits(vehicle, path, talus.station_count(path.length()))
    return surface, limits, talus.TimeOptimalProfileSolver().solve(
        limits, talus.ProfileOptions(v0, v1))


def expect_bit_identical(profile, ref, prefix):
    assert ref[prefix + ".status"] == "ok"
    assert profile.travel_time == ref[prefix + ".travel_time"]
    for name in ("s", "v", "a", "t", "v_max"):
        ours = getattr(profile, name)
        theirs = np.array(ref[prefix + "." + name])
        assert ours.shape == theirs.shape, name
        assert np.array_equal(ours, theirs), name  # == at every station, inf included


def run_case(reference, terrain, vehicle_path, a, b, v0=0.0, v1=0.0):
    vehicle = talus.load_vehicle(str(vehicle_path))
    surface, limits, profile = solve_straight(terrain, vehicle, a, b, v0, v1)
    ref = reference("profile", terrain, vehicle_path, *map(number_text, (*a, *b, v0, v1)))
    expect_bit_identical(profile, ref, "profile")
    trajectory = talus.evaluate_trajectory(surface, vehicle, talus.Curve2.interpolate(
        np.array([a, b])), talus.TrajectoryOptions(v0, v1))
    expect_bit_identical(trajectory.profile, ref, "trajectory")
    assert trajectory.length() == ref["trajectory.length"]
    return surface, limits, profile


def test_flat_straight_line_rest_to_rest_is_the_cpp_result_and_the_closed_form(
        tmp_path, plane_asc, reference):
    terrain = plane_asc("flat.asc", 211, 11, 1.0, 0.0, -5.0, 0.0)
    L, mu = 200.0, 0.7
    _, _, p = run_case(reference, terrain, vehicle_file(tmp_path, mu), (5.0, 0.0), (5.0 + L, 0.0))
    assert p.status == talus.ProfileStatus.OK, p.message
    # Accelerate at mu g to the middle, brake at mu g: exact up to the switch step.
    assert p.travel_time == pytest.approx(2.0 * math.sqrt(L / (mu * G)), rel=1e-7)
    assert p.v[0] == 0.0 and abs(p.v[-1]) < 1e-9
    assert p.switching_points[0].from_ == talus.ControlKind.ACCELERATE
    assert p.switching_points[-1].to == talus.ControlKind.DECELERATE


@pytest.mark.parametrize("up", [True, False])
def test_inclined_plane_up_and_down_is_the_cpp_result_and_the_closed_form(
        tmp_path, plane_asc, reference, up):
    alpha, mu, L = 0.15, 0.8, 150.0
    terrain = plane_asc("plane.asc", 161, 11, 1.0, 0.0, -5.0, math.tan(alpha))
    run = L * math.cos(alpha)
    a, b = ((5.0, 0.0), (5.0 + run, 0.0)) if up else ((5.0 + run, 0.0), (5.0, 0.0))
    _, limits, p = run_case(reference, terrain, vehicle_file(tmp_path, mu), a, b)
    assert p.status == talus.ProfileStatus.OK, p.message
    s = 1.0 if up else -1.0
    acc = G * (mu * math.cos(alpha) - s * math.sin(alpha))
    dec = G * (mu * math.cos(alpha) + s * math.sin(alpha))
    peak = math.sqrt(2.0 * L * acc * dec / (acc + dec))
    assert p.travel_time == pytest.approx(peak / acc + peak / dec, rel=1e-7)
    # The path frame's vertical component along the line: k_t = +-sin(alpha).
    assert np.allclose(limits.k_t, s * math.sin(alpha), atol=1e-12)


def test_drive_brake_and_speed_limits_give_the_trapezoid(tmp_path, plane_asc, reference):
    terrain = plane_asc("flat.asc", 211, 11, 1.0, 0.0, -5.0, 0.0)
    L, A, D, V = 200.0, 2.0, 4.0, 10.0
    vehicle = vehicle_file(tmp_path, 0.9, max_accel=A, max_decel=D, max_speed=V)
    _, _, p = run_case(reference, terrain, vehicle, (5.0, 0.0), (5.0 + L, 0.0), 0.0, 0.0)
    expected = V / A + V / D + (L - V * V / (2 * A) - V * V / (2 * D)) / V  # 23.75 s
    assert p.travel_time == pytest.approx(expected, rel=1e-7)
    assert set(p.binding) == {"max_speed"}


def test_limits_from_geometry_arrays_reproduce_the_path_limits_and_profile(
        tmp_path, plane_asc):
    terrain = plane_asc("plane.asc", 161, 11, 1.0, 0.0, -5.0, 0.2)
    vehicle = talus.load_vehicle(str(vehicle_file(tmp_path, 0.8, max_speed=12.0)))
    _, limits, p = solve_straight(terrain, vehicle, (5.0, 0.0), (150.0, 2.0), 1.0, 0.5)
    again = talus.VelocityLimits.from_geometry(vehicle, limits.s, limits.kappa_n, limits.kappa_g,
                                               limits.k_t, limits.k_q, limits.k_r)
    assert np.array_equal(again.v_max, limits.v_max)
    q = talus.TimeOptimalProfileSolver().solve(again, talus.ProfileOptions(1.0, 0.5))
    assert q.travel_time == p.travel_time
    assert np.array_equal(q.v, p.v) and np.array_equal(q.t, p.t)


def test_speed_limits_on_arrays_of_flat_circles_are_sqrt_mu_g_r():
    vehicle = talus.Vehicle.from_dict(
        {"model": "point_mass", "friction": 0.7, "cg_height": 0.3, "half_track": 1.0})
    radius = np.array([[1.0, 5.0], [20.0, 400.0]])
    out = talus.speed_limits(vehicle, 0.0, 1.0 / radius, 0.0, 0.0, 1.0)
    assert out["v_max"].shape == (2, 2)
    assert np.allclose(out["v_max"], np.sqrt(0.7 * G * radius), rtol=1e-12, atol=0)
    assert out["upper_binding"] == ["sliding"] * 4
    assert out["traversable"].all() and (out["v_min"] == 0).all()
    # Straight and flat: nothing limits the speed.
    straight = talus.speed_limits(vehicle, 0.0, 0.0, 0.0, 0.0, 1.0)
    assert straight["v_max"] == math.inf and straight["upper_binding"] == ["none"]


def test_acceleration_bounds_on_arrays_are_the_drive_and_brake_limits_on_level_ground(rover):
    vehicle = talus.load_vehicle(str(rover))  # max_accel 3, max_decel 6, mu g = 6.87
    out = talus.acceleration_bounds(vehicle, 0.0, 0.0, 0.0, 0.0, 1.0, np.array([0.0, 1.0, 5.0]))
    assert np.array_equal(out["a_max"], [3.0, 3.0, 3.0])
    assert np.array_equal(out["a_min"], [-6.0, -6.0, -6.0])
    assert out["upper_binding"] == ["drive"] * 3 and out["lower_binding"] == ["brake"] * 3


def test_a_start_speed_above_the_limit_is_an_input_error(tmp_path, plane_asc):
    terrain = plane_asc("flat.asc", 211, 11, 1.0, 0.0, -5.0, 0.0)
    vehicle = talus.load_vehicle(str(vehicle_file(tmp_path, 0.7, max_speed=5.0)))
    with pytest.raises(talus.InputError):
        solve_straight(terrain, vehicle, (5.0, 0.0), (50.0, 0.0), 6.0, 0.0)


def test_nan_geometry_negative_speeds_and_non_increasing_stations_are_input_errors():
    # A NaN station gave v_max 15 and "traversable"; each is now refused, naming the array.
    vehicle = talus.Vehicle()
    vehicle.max_speed = 15.0
    with pytest.raises(talus.InputError, match=r"kappa_g\[1\]"):
        talus.speed_limits(vehicle, 0.0, [0.1, float("nan")], 0.0, 0.0, 1.0)
    with pytest.raises(talus.InputError, match=r"speed\[0\]"):
        talus.acceleration_bounds(vehicle, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0)
    with pytest.raises(talus.InputError, match="s must increase strictly"):
        talus.VelocityLimits.from_geometry(vehicle, [0.0, 1.0, 1.0], 0.0, 0.0, 0.0, 0.0, 1.0)
    with pytest.raises(talus.InputError, match=r"points\[1\]"):
        talus.Curve2.interpolate(np.array([[0.0, 0.0], [np.inf, 1.0], [2.0, 0.0]]))
