"""The planner through the bindings on a bundled DEM: bit for bit what `talus plan`
writes and what the C++ library returns (tests/reference.cpp), results that keep
their surface alive, the progress callback."""
import csv
import gc
import json
import weakref

import numpy as np
import pytest

import talus
from conftest import number_text

START, GOAL = (557000.0, 4373500.0), (557800.0, 4374200.0)  # about 1.07 km on West Bijou
CANDIDATES = 1


@pytest.fixture(scope="module")
def planned(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    problem = talus.PlanningProblem(surface, talus.load_vehicle(str(rover)), START, GOAL)
    options = talus.PlannerOptions()
    options.global_search.candidates = CANDIDATES
    return talus.plan(problem, options)


def test_the_plan_is_the_cli_plan_bit_for_bit(planned, cli, west_bijou, rover, tmp_path):
    out = tmp_path / "plan"
    code, stdout, err = cli("plan", "--terrain", west_bijou, "--vehicle", rover,
                            "--start", ",".join(map(number_text, START)),
                            "--goal", ",".join(map(number_text, GOAL)),
                            "--candidates", CANDIDATES, "--out", out)
    assert code == 0, err
    summary = json.loads(stdout)
    assert planned.status == talus.PlannerStatus.OK, planned.brief_report()
    best = planned.best()
    assert planned.travel_time() == summary["travel_time"]
    assert planned.global_travel_time() == summary["global_travel_time"]
    assert best.length() == summary["length_m"]
    assert np.array_equal(best.path.curve().control_points, summary["best_control_points"])
    assert planned.global_search.nodes == summary["nodes"]
    assert [c.cost_seconds for c in planned.global_search.candidates] == [
        c["cost_seconds"] for c in summary["candidates"]]
    with open(out / "trajectory.csv") as f:
        rows = list(csv.DictReader(f))
    column = {k: np.array([float(r[k]) for r in rows]) for k in ("s", "x", "y", "z", "v", "t")}
    assert np.array_equal(best.profile.s, column["s"])
    assert np.array_equal(best.limits.points, np.stack([column[k] for k in "xyz"], axis=1))
    assert np.array_equal(best.profile.v, column["v"])
    assert np.array_equal(best.profile.t, column["t"])
    assert best.profile.binding == [r["binding"] for r in rows]


def test_the_plan_is_the_cpp_plan_bit_for_bit(planned, reference, west_bijou, rover):
    ref = reference("plan", west_bijou, rover, *map(number_text, (*START, *GOAL)), CANDIDATES)
    assert ref["plan.status"] == str(planned.status) == "ok"
    assert planned.travel_time() == ref["plan.travel_time"]
    assert planned.global_travel_time() == ref["plan.global_travel_time"]
    control = planned.best().path.curve().control_points
    assert np.array_equal(control.ravel(), ref["plan.control_points"])
    for name in ("s", "v", "a", "t", "v_max"):
        assert np.array_equal(getattr(planned.best().profile, name), ref["plan.best." + name])


def test_the_result_reads_like_the_cpp_result(planned):
    assert planned.brief_report().startswith("Talus plan: ok")
    assert planned.best_candidate == 0 and planned.message == ""
    (outcome,) = planned.candidates
    assert outcome.feasible() and outcome.trajectory.travel_time() == planned.travel_time()
    assert outcome.optimization.travel_time <= outcome.optimization.initial_time
    # The optimum agrees at the final stations: it is the point reported.
    assert outcome.reported_attempt == outcome.optimization.best_attempt
    assert planned.travel_time() <= planned.global_travel_time()
    fields = planned.global_search
    assert fields.cost_from_start.shape == (fields.ny, fields.nx)
    assert planned.seconds.total >= planned.seconds.global_search


def test_results_hold_their_surface_so_the_callers_object_can_go(west_bijou, rover):
    grid = talus.read_esri_ascii(str(west_bijou))
    surface = talus.BPatch.interpolate(grid)
    alive = weakref.ref(surface)
    problem = talus.PlanningProblem(surface, talus.load_vehicle(str(rover)), START, GOAL)
    options = talus.PlannerOptions()
    options.global_search.candidates = 1
    options.optimize = False  # the global stage is enough here
    result = talus.plan(problem, options)
    line = talus.Curve2.interpolate(np.array([START, GOAL]))
    trajectory = talus.evaluate_trajectory(surface, problem.vehicle, line)
    path = trajectory.path
    length = trajectory.length()
    del surface, problem
    gc.collect()
    # No keep-alive: the Python surface is gone, the C++ objects hold the same
    # (shared, immutable) coefficients and still read them.
    assert alive() is None
    assert length > 1000.0
    assert result.status == talus.PlannerStatus.OK
    del result, trajectory
    gc.collect()
    assert path.length() == length  # reads the surface


def test_the_progress_callback_sees_the_stages_and_can_stop(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    problem = talus.PlanningProblem(surface, talus.load_vehicle(str(rover)), START, GOAL)
    seen = []
    options = talus.PlannerOptions()
    options.progress = lambda p: seen.append(p.stage) or False
    result = talus.plan(problem, options)
    assert result.status == talus.PlannerStatus.STOPPED and result.best() is None
    assert seen[0] == talus.PlannerStage.GLOBAL_SEARCH
    assert talus.PlannerStage.LOCAL_OPTIMISATION not in seen


def test_bad_input_raises_input_error(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    vehicle = talus.load_vehicle(str(rover))
    with pytest.raises(talus.InputError):
        talus.plan(talus.PlanningProblem(surface, vehicle, (0.0, 0.0), GOAL))
    options = talus.PlannerOptions()
    options.local.solver = "nlopt-bobyqa"
    assert options.local.solver == talus.PathSolver.NLOPT_BOBYQA
    with pytest.raises(talus.InputError, match="snopt"):
        options.local.solver = "snopt"
    options.global_search.connectivity = 12
    with pytest.raises(talus.InputError, match="connectivity"):
        talus.plan(talus.PlanningProblem(surface, vehicle, START, GOAL), options)


def test_start_and_goal_headings_are_kept(rover):
    # Flat ground: the free plan runs due east; with headings the clamped curve's first and
    # last control-point legs lie along them (the end tangents).
    surface = talus.BPatch.interpolate(talus.ElevationGrid(61, 41, 1.0, 0.0, 0.0))
    vehicle = talus.load_vehicle(str(rover))
    problem = talus.PlanningProblem(surface, vehicle, (5.0, 20.0), (55.0, 20.0),
                                    start_heading=0.6, goal_heading=-0.9)
    assert problem.start_heading == 0.6 and problem.goal_heading == -0.9
    options = talus.PlannerOptions()
    options.global_search.candidates = 1
    result = talus.plan(problem, options)
    assert result.status == talus.PlannerStatus.OK, result.brief_report()
    p = result.best().path.curve().control_points
    assert np.arctan2(*(p[1] - p[0])[::-1]) == pytest.approx(0.6, abs=1e-9)
    assert np.arctan2(*(p[-1] - p[-2])[::-1]) == pytest.approx(-0.9, abs=1e-9)
    assert talus.PlanningProblem(surface, vehicle, (5.0, 20.0), (55.0, 20.0)).start_heading is None
    problem.start_heading = float("nan")
    with pytest.raises(talus.InputError):
        talus.plan(problem, options)


def test_planner_options_are_generated_from_the_declared_table():
    described = {p["name"]: p for p in talus.planner_parameters()}
    assert {"candidates", "connectivity", "time_limit", "solver", "more_control_points"} <= set(described)
    assert described["connectivity"]["choices"] == [8, 16, 32]
    assert described["braking_rule"]["cli"] == "--no-braking-rule"
    options = talus.PlannerOptions(candidates=2, connectivity=32, solver="nlopt-lbfgs",
                                   time_limit=5, more_control_points=[8, 24], polish=True)
    # The attributes are the nested C++ members, so both views agree.
    assert options.global_search.candidates == 2 and options.candidates == 2
    assert options.global_search.connectivity == 32
    assert options.time_limit == 5.0
    assert options.more_control_points == [8, 24]
    assert options.parameters()["solver"] == "nlopt-lbfgs"
    defaults = talus.PlannerOptions().parameters()
    assert all(defaults[name] == p["default"] for name, p in described.items())
    with pytest.raises(ValueError, match="connectivity must be 8, 16 or 32, got 12"):
        options.connectivity = 12
    with pytest.raises(ValueError, match=r"candidates must be an integer in \[1, 1000\], got 2.5"):
        talus.PlannerOptions(candidates=2.5)
    with pytest.raises(ValueError, match="has no parameter 'colour'"):
        talus.PlannerOptions(colour=1)
    assert options.connectivity == 32


def test_every_front_end_shows_the_same_declared_parameters(cli, west_bijou, rover, tmp_path):
    described = {p["name"]: p for p in talus.planner_parameters()}
    code, help_text, err = cli("plan", "--help")
    assert code == 0, err
    for p in described.values():
        assert p["cli"] in help_text, p["cli"]
    # A parameter given on the command line is applied and echoed under `options`
    # with every other parameter, each equal to what Python's PlannerOptions holds.
    out = tmp_path / "plan"
    code, stdout, err = cli("plan", "--terrain", west_bijou, "--vehicle", rover,
                            "--start", ",".join(map(number_text, START)),
                            "--goal", ",".join(map(number_text, GOAL)), "--stage", "global",
                            "--feedback-radius", 75, "--connectivity", 8, "--no-turn-limit",
                            "--out", out)
    assert code == 0, err
    echoed = json.loads(stdout)["options"]
    expected = talus.PlannerOptions(feedback_radius=75.0, connectivity=8,
                                    turn_limit=False).parameters()
    expected["time_limit"] = None  # JSON has no inf
    assert echoed == expected


def test_the_certificate_is_reported_per_optimum(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    problem = talus.PlanningProblem(surface, talus.load_vehicle(str(rover)), START, GOAL)
    assert talus.PlannerOptions().certify  # on by default
    result = talus.plan(problem, talus.PlannerOptions(candidates=1))
    assert result.status == talus.PlannerStatus.OK, result.brief_report()
    certificate = result.candidates[0].certificate
    assert certificate is not None and certificate.evaluations > 0
    assert certificate.radius == 0.25 * surface.cellsize
    assert certificate.improvement >= 0.0
    plain = talus.plan(problem, talus.PlannerOptions(candidates=1, certify=False))
    assert result.candidates[0].certificate is not None and plain.candidates[0].certificate is None
    assert result.travel_time() <= plain.travel_time()
