#!/usr/bin/env python3
"""Plan a time-optimal trajectory on a bundled DEM with `import talus` and plot it.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/plan.py --out talus-out/python

writes OUT/plan.png: the terrain with the global candidates and the best
trajectory coloured by speed, and the speed profile under its limit. Every
number comes from the library; this script only calls it and draws.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import talus  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--terrain", default=DATA / "terrain" / "west_bijou_escarpment_nasadem25m.asc")
    parser.add_argument("--vehicle", default=DATA / "vehicles" / "rover.yaml")
    parser.add_argument("--start", type=float, nargs=2, default=(557000.0, 4373500.0))
    parser.add_argument("--goal", type=float, nargs=2, default=(557800.0, 4374200.0))
    parser.add_argument("--candidates", type=int, default=2)
    parser.add_argument("--out", type=pathlib.Path, required=True)
    args = parser.parse_args()

    grid = talus.read_esri_ascii(str(args.terrain))
    surface = talus.BPatch.interpolate(grid)
    problem = talus.PlanningProblem(surface, talus.load_vehicle(str(args.vehicle)),
                                    args.start, args.goal)
    options = talus.PlannerOptions()
    options.global_search.candidates = args.candidates
    result = talus.plan(problem, options)
    print(result.brief_report(), end="")
    best = result.best()
    if best is None:
        raise SystemExit(f"no trajectory: {result.message}")

    fig, (ax_map, ax_v) = plt.subplots(1, 2, figsize=(13, 5.5),
                                       gridspec_kw={"width_ratios": [1.2, 1]})
    extent = (grid.x_min, grid.x_max, grid.y_min, grid.y_max)
    image = ax_map.imshow(grid.to_array(), origin="lower", extent=extent, cmap="terrain")
    fig.colorbar(image, ax=ax_map, label="elevation [m]", shrink=0.8)
    for k, candidate in enumerate(result.global_search.candidates):
        v = candidate.vertices
        ax_map.plot(v[:, 0], v[:, 1], "--", lw=1, color="0.3",
                    label="global candidates" if k == 0 else None)
    points, speed = best.limits.points, best.profile.v
    path = ax_map.scatter(points[:, 0], points[:, 1], c=speed, s=2, cmap="plasma")
    fig.colorbar(path, ax=ax_map, label="speed [m/s]", shrink=0.8)
    ax_map.plot(*args.start, "o", color="white", mec="black", label="start")
    ax_map.plot(*args.goal, "*", ms=12, color="white", mec="black", label="goal")
    pad = 0.25 * max(np.ptp(points[:, 0]), np.ptp(points[:, 1]))
    ax_map.set_xlim(points[:, 0].min() - pad, points[:, 0].max() + pad)
    ax_map.set_ylim(points[:, 1].min() - pad, points[:, 1].max() + pad)
    ax_map.set_xlabel("x [m]")
    ax_map.set_ylabel("y [m]")
    ax_map.set_aspect("equal")
    ax_map.ticklabel_format(useOffset=False, style="plain")
    ax_map.legend(loc="lower right", fontsize=8)
    ax_map.set_title(f"best trajectory {result.travel_time():.2f} s "
                     f"(global {result.global_travel_time():.2f} s)")

    p = best.profile
    v_max = np.where(np.isfinite(p.v_max), p.v_max, np.nan)
    ax_v.plot(p.s, np.minimum(v_max, 1.5 * p.v.max()), color="0.5", lw=1, label="speed limit")
    ax_v.plot(p.s, p.v, color="C3", label="time-optimal speed")
    for sp in p.switching_points:
        ax_v.axvline(sp.s, color="0.85", lw=0.8, zorder=0)
    ax_v.set_xlabel("arc length s [m]")
    ax_v.set_ylabel("speed [m/s]")
    ax_v.legend(fontsize=8)
    ax_v.set_title(f"{len(p.switching_points)} switching points, {best.length():.0f} m")
    fig.tight_layout()
    args.out.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out / "plan.png", dpi=110)
    print(f"wrote {args.out / 'plan.png'}")


if __name__ == "__main__":
    main()
