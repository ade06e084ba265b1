"""The vehicle simulation from Python: a planned trajectory driven by the tracker."""
import json

import numpy as np
import pytest

import talus

from conftest import number_text


@pytest.fixture(scope="module")
def straight_plan(tmp_path_factory, data_dir):
    """A straight 12 m plan on a level plane with the simulated UGV, its surface and vehicle."""
    folder = tmp_path_factory.mktemp("plane")
    z = np.zeros((21, 41))
    terrain = folder / "plane.asc"
    talus.write_esri_ascii(talus.ElevationGrid.from_array(z, 0.5, 0.0, 0.0), str(terrain))
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(terrain)))
    vehicle_path = data_dir / "vehicles" / "iagnemma_ugv.yaml"
    vehicle = talus.load_vehicle(str(vehicle_path))
    curve = talus.Curve2.interpolate(np.array([[4.0, 5.0], [10.0, 5.0], [16.0, 5.0]]))
    trajectory = talus.evaluate_trajectory(surface, vehicle, curve)
    assert trajectory.feasible()
    return terrain, vehicle_path, surface, vehicle, trajectory


def test_the_reference_is_the_trajectorys_stations_and_speeds(straight_plan):
    _, _, _, _, trajectory = straight_plan
    reference = talus.reference_trajectory(trajectory)
    points = reference.points
    assert points.shape[1] == 2 and len(points) == len(reference.speed) >= 2
    np.testing.assert_allclose(points[0], [4.0, 5.0], atol=1e-9)
    np.testing.assert_allclose(points[-1], [16.0, 5.0], atol=1e-9)
    np.testing.assert_allclose(reference.speed, trajectory.profile.v[:len(reference.speed)])


def test_a_straight_plan_is_driven_to_the_goal_on_schedule(straight_plan):
    _, _, surface, vehicle, trajectory = straight_plan
    reference = talus.reference_trajectory(trajectory)
    result = talus.track_trajectory(surface, vehicle, reference)
    assert result.status == "reached_goal" and result.reached(), result.brief_report()
    assert result.progress > 0.95
    assert result.path_length == pytest.approx(12.0, rel=1e-6)
    # Straight on level ground: no side slip, no roll, the path kept to a centimetre, the
    # schedule within the tracker's lag (the trace starts at the planned start speed, rest).
    assert result.max_cross_track < 0.01
    assert result.margins["peak_side_slip"] < 0.01
    assert result.margins["peak_roll"] < 0.01
    assert result.travel_time == pytest.approx(result.planned_time, rel=0.1)
    trace = result.trace
    lengths = {len(a) for a in trace.values()}
    assert len(lengths) == 1 and lengths.pop() > 10
    assert np.all(np.diff(trace["t"]) >= 0) and trace["t"][-1] == result.travel_time
    assert trace["x"][-1] > 15.0 and abs(trace["y"][-1] - 5.0) < 0.01


def test_the_drive_is_the_clis_drive_bit_for_bit(straight_plan, cli, tmp_path):
    terrain, vehicle_path, surface, vehicle, trajectory = straight_plan
    reference = talus.reference_trajectory(trajectory)
    csv = tmp_path / "trajectory.csv"
    rows = ["x,y,v"] + [",".join(number_text(c) for c in (*p, v))
                        for p, v in zip(reference.points, reference.speed)]
    csv.write_text("\n".join(rows) + "\n")
    code, _, err = cli("simulate", "--terrain", terrain, "--vehicle", vehicle_path,
                       "--trajectory", csv, "--speed-scale", 1.05, "--out", tmp_path / "out",
                       "--quiet")
    assert code == 0, err
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    result = talus.track_trajectory(surface, vehicle, reference, talus.TrackingOptions(1.05))
    assert summary["status"] == result.status
    assert summary["travel_time"] == result.travel_time
    assert summary["margins"]["peak_side_slip"] == result.margins["peak_side_slip"]


def test_the_speed_scale_limit_brackets_its_largest_reaching_drive(straight_plan):
    _, _, surface, vehicle, trajectory = straight_plan
    options = talus.SpeedScaleLimitOptions()
    options.tolerance = 0.1
    limit = talus.find_speed_scale_limit(surface, vehicle, trajectory, options)
    assert limit.status in ("bracketed", "reaches_highest")
    passed = [d.speed_scale for d in limit.drives
              if d.kept_schedule(options.schedule_tolerance)]
    assert limit.largest_reaching_scale == max(passed)
    if limit.status == "bracketed":
        assert limit.smallest_failing_scale - limit.largest_reaching_scale <= 0.1 + 1e-12
        assert limit.bounding_reason() != ""


def test_bad_input_raises_input_error(straight_plan):
    _, _, surface, vehicle, _ = straight_plan
    with pytest.raises(talus.InputError):
        talus.ReferenceTrajectory(np.array([[1.0, 1.0]]), [1.0])
    reference = talus.ReferenceTrajectory(np.array([[4.0, 5.0], [6.0, 5.0]]), [1.0, 1.0])
    with pytest.raises(talus.InputError):
        talus.track_trajectory(surface, vehicle, reference, talus.TrackingOptions(-1.0))
    with pytest.raises(talus.InputError):
        talus.TrackingOptions().steering_law = "telepathy"
