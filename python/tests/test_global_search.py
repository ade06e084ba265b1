"""The global search through the bindings with a workspace: the same candidates as a
search without one, edge costs kept between searches of one surface and vehicle
(a later search computes none), excluded regions, and the surface kept alive."""
import gc
import weakref

import numpy as np

import talus

START, GOAL = (557000.0, 4373500.0), (557800.0, 4374200.0)  # about 1.07 km on West Bijou


def same(a, b):
    assert a.status == b.status
    assert [c.cost_seconds for c in a.candidates] == [c.cost_seconds for c in b.candidates]
    assert all((x.vertices == y.vertices).all() for x, y in zip(a.candidates, b.candidates))


def test_a_workspace_keeps_the_edge_costs_and_changes_no_result(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    vehicle = talus.load_vehicle(str(rover))
    options = talus.GlobalSearchOptions()
    workspace = talus.GlobalSearchWorkspace()
    first = talus.global_search(surface, vehicle, START, GOAL, options, workspace)
    assert first.status == talus.GlobalSearchStatus.OK
    assert first.edges_evaluated > 0 and workspace.lattices() == 1
    same(first, talus.global_search(surface, vehicle, START, GOAL, options))

    middle = first.candidates[0].vertices[len(first.candidates[0].vertices) // 2]
    options.excluded = [talus.ExcludedRegion(tuple(middle), 100.0)]
    again = talus.global_search(surface, vehicle, START, GOAL, options, workspace)
    assert again.edges_evaluated == 0
    same(again, talus.global_search(surface, vehicle, START, GOAL, options))
    assert not (again.candidates[0].vertices.shape == first.candidates[0].vertices.shape
                and (again.candidates[0].vertices == first.candidates[0].vertices).all())

    # The workspace holds its own copy of the surface (shared coefficients): the
    # caller's object can go, and a search on a copy of it still reuses the lattice.
    kept = talus.PlanningProblem(surface, vehicle, START, GOAL).surface
    probe = weakref.ref(surface)
    del surface
    gc.collect()
    assert probe() is None
    reused = talus.global_search(kept, vehicle, START, GOAL, options, workspace)
    assert reused.edges_evaluated == 0
    same(reused, again)
    workspace.clear()
    assert workspace.lattices() == 0


def test_the_turn_limit_reuses_the_edge_costs_and_keeps_the_steering_limit(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    vehicle = talus.load_vehicle(str(rover))
    vehicle.half_wheelbase = 1.0
    vehicle.max_steering = 0.5  # kappa_max = tan(0.5) / 2 = 0.27 1/m
    options = talus.GlobalSearchOptions()
    assert options.turn_limit
    workspace = talus.GlobalSearchWorkspace()
    limited = talus.global_search(surface, vehicle, START, GOAL, options, workspace)
    options.turn_limit = False
    free = talus.global_search(surface, vehicle, START, GOAL, options, workspace)
    assert limited.status == free.status == talus.GlobalSearchStatus.OK
    assert free.edges_evaluated == 0  # the same lattice: only the graph over it differs
    assert limited.candidates[0].cost_seconds >= free.candidates[0].cost_seconds * (1 - 1e-12)


def test_a_spent_budget_on_a_tile_size_map_returns_the_route_levels_candidates():
    """Under a time budget the coarse-to-fine search runs a route level to its end first."""
    x = np.arange(600.0)
    surface = talus.BPatch.interpolate(
        talus.ElevationGrid.from_array(np.tile(0.05 * x, (600, 1)), 1.0, 0.0, 0.0))
    vehicle = talus.Vehicle.from_dict({"model": "point_mass", "friction": 0.7, "cg_height": 0.5,
                                       "half_track": 0.6, "max_speed": 10.0})
    problem = talus.PlanningProblem(surface, vehicle, (10.0, 10.0), (590.0, 590.0))
    planner = talus.PlannerOptions(resolution="multi", time_limit=1e-9)
    result = talus.plan(problem, planner)
    search = result.global_search
    assert result.status == talus.PlannerStatus.TIME_LIMIT
    assert search.coarse_candidates and search.route_nodes == 120 * 120
    assert search.resolution == "multi" and search.spacing == 5.0
    assert result.best() is not None and result.best().feasible()
