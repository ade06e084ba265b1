"""Every registered kinematic baseline, listed and run by name through the
bindings: the same path, bit for bit, as `talus baseline NAME`."""
import csv
import json

import numpy as np
import pytest

import talus

# A robot file for each registered baseline; a new baseline must be added here
# (relative to data/robots; the Iagnemma navigator drives a vehicle file).
ROBOTS = {"hait": "marsokhod_chassis.yaml", "dacre-wright": "dacre_wright_six_wheel.yaml",
          "eldershaw-yim": "eldershaw_spider.yaml",
          "iagnemma": "../vehicles/iagnemma_ugv.yaml", "talus": "../vehicles/iagnemma_ugv.yaml"}
START, GOAL = (2.0, 3.0, 0.0), (10.0, 9.0, 1.5)


@pytest.fixture(scope="module")
def bump_asc(tmp_path_factory):
    """12 m x 12 m at 0.25 m with a gentle 0.3 m bump in the middle."""
    h = 0.25
    x = h * np.arange(49)
    X, Y = np.meshgrid(x, x)
    z = 0.3 * np.exp(-((X - 6.0) ** 2 + (Y - 6.0) ** 2) / 2.0)
    path = tmp_path_factory.mktemp("baselines") / "bump.asc"
    talus.write_esri_ascii(talus.ElevationGrid.from_array(z, h, 0.0, 0.0), str(path))
    return path


def test_the_registry_lists_every_baseline_with_its_options():
    assert sorted(talus.baseline_names()) == sorted(ROBOTS)
    for name in talus.baseline_names():
        entry = talus.baseline(name)
        assert entry.name == name and entry.summary
        keys = [o.key for o in entry.options]
        assert "budget" in keys and "robot" in keys
    with pytest.raises(talus.InputError, match="registered: hait"):
        talus.baseline("nope")


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_each_baseline_finds_the_cli_path_bit_for_bit(name, bump_asc, data_dir, cli, tmp_path):
    robot = str(data_dir / "robots" / ROBOTS[name])
    terrain = talus.RuledTerrain(talus.read_esri_ascii(str(bump_asc)))
    result = talus.run_baseline(name, terrain, START, GOAL, {"robot": robot})
    assert result.found(), result.brief_report()
    assert str(result.status) == "found"
    if name == "iagnemma":
        # The driven path: its first pose is the resting vehicle's c.g. over
        # the start (off it by h sin(slope) on a slope) and heading.
        assert np.allclose(result.path[0], START, atol=0.01)
    else:
        assert np.array_equal(result.path[0], START)
    out = tmp_path / "out"
    code, stdout, err = cli("baseline", name, "--terrain", bump_asc, "--robot", robot,
                            "--start", ",".join(map(repr, START)),
                            "--goal", ",".join(map(repr, GOAL)), "--out", out)
    assert code == 0, err
    summary = json.loads(stdout)
    assert summary["status"] == "found" and summary["length_m"] == result.length_m
    with open(out / "path.csv") as f:
        rows = list(csv.DictReader(f))
    cli_path = np.array([[float(r[k]) for k in ("x", "y", "theta")] for r in rows])
    assert np.array_equal(result.path, cli_path)


def test_a_configured_planner_reports_its_settings_and_plans_again(bump_asc, data_dir):
    planner = talus.make_baseline("hait", {"robot": str(data_dir / "robots" / ROBOTS["hait"]),
                                           "smooth": True, "budget": 100000})
    settings = {(section, key): value for section, key, value in planner.settings()}
    assert settings[("options", "smooth")] is True
    terrain = talus.RuledTerrain(talus.read_esri_ascii(str(bump_asc)))
    a, b = planner.plan(terrain, START, GOAL), planner.plan(terrain, START, GOAL)
    assert a.found() and np.array_equal(a.path, b.path)  # deterministic


def test_a_bad_option_is_a_baseline_option_error_naming_its_key(data_dir):
    robot = str(data_dir / "robots" / ROBOTS["hait"])
    with pytest.raises(talus.BaselineOptionError) as raised:
        talus.make_baseline("hait", {"robot": robot, "budget": "lots"})
    assert raised.value.key == "budget"
    assert str(raised.value) == "option budget: " + raised.value.reason
    with pytest.raises(talus.InputError, match="unknown"):
        talus.make_baseline("hait", {"robot": robot, "speed": 3})
    terrain = talus.RuledTerrain(talus.ElevationGrid(9, 9, 0.5, 0.0, 0.0))
    with pytest.raises(talus.InputError):  # the start is off the map
        talus.run_baseline("hait", terrain, (-5.0, 0.0, 0.0), (2.0, 2.0, 0.0), {"robot": robot})


def test_a_straight_path_is_driven_in_the_analytic_rest_to_rest_time(rover, plane_asc):
    """On level ground the rover accelerates at max_accel 3 and brakes at max_decel 6 (both
    within mu g): over L = 10 m the peak speed is sqrt(2 L a d / (a + d)) and the time
    v (1/a + 1/d)."""
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(plane_asc("p.asc", 31, 11, 1.0,
                                                                           0.0, 0.0, 0.0))))
    vehicle = talus.load_vehicle(str(rover))
    a, d, length = 3.0, 6.0, 10.0
    peak = np.sqrt(2 * length * a * d / (a + d))
    expected = peak / a + peak / d
    poses = np.array([[5.0 + x, 5.0, 0.0] for x in np.linspace(0.0, length, 21)])
    driven = talus.driven_path_time(surface, vehicle, poses)
    assert driven.status == "ok" and driven.pieces == 1
    assert driven.travel_time == pytest.approx(expected, rel=1e-3)
    assert driven.length == pytest.approx(length, rel=1e-9)
    assert talus.polyline_travel_time(surface, vehicle, poses[:, :2]) == pytest.approx(expected,
                                                                                       rel=1e-3)
    sideways = poses.copy()
    sideways[:, 2] = np.pi / 2   # facing north while moving east: no driving direction
    assert talus.driven_path_time(surface, vehicle, sideways).status == "not_tangent"
