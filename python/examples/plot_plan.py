#!/usr/bin/env python3
"""Plans a scenario of mobile robots with earc and plots each robot's route.

    PYTHONPATH=build/python python3 python/examples/plot_plan.py \
        datasets/mobile-obst-16-s1.json plan.png [--method arc] [--seed 1]
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402
import numpy as np  # noqa: E402

import earc  # noqa: E402


def box_corners(center, size, angle):
    """The four corners of a box obstacle."""
    c, s = np.cos(angle), np.sin(angle)
    half = np.array(size) / 2
    corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * half
    return corners @ np.array([[c, s], [-s, c]]) + np.array(center)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario")
    ap.add_argument("output", help="image file to write (PNG, SVG, PDF)")
    ap.add_argument("--method", default="arc")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--time-limit", type=float, default=60.0)
    args = ap.parse_args()

    scenario = earc.load_scenario(args.scenario)
    result = earc.plan(scenario, args.method, seed=args.seed, time_limit=args.time_limit)
    if not result.success:
        raise SystemExit(f"not solved: {', '.join(result.failures)}")
    doc = scenario.to_dict()
    if any(r["type"] != "mobile" for r in doc["robots"]):
        raise SystemExit("this example plots mobile robots only")

    fig, ax = plt.subplots(figsize=(8, 8))
    for o in doc["obstacles"]:
        if o["type"] == "box":
            ax.add_patch(Polygon(box_corners(o["center"], o["size"], o["angle"]), color="0.6"))
        else:
            ax.add_patch(Circle(o["center"], o["radius"], color="0.6"))
    colors = plt.cm.tab20(np.linspace(0, 1, max(len(result.paths), 2)))
    for (times, q), color, name in zip(result.paths, colors, result.robots):
        ax.plot(q[:, 0], q[:, 1], color=color, lw=1.2, label=name)
        ax.plot(*q[0, :2], "o", color=color, ms=5)
        ax.plot(*q[-1, :2], "s", color=color, ms=5)
    lo, hi = doc["workspace"]["min"], doc["workspace"]["max"]
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    st = result.stats
    ax.set_title(f"{scenario.name}: {args.method}, makespan {st['makespan']}, sum of costs {st['sum_of_costs']}")
    if len(result.paths) <= 16:
        ax.legend(fontsize=7, loc="upper right")
    fig.savefig(args.output, dpi=120, bbox_inches="tight")
    print(f"{args.output}: {len(result.paths)} robots, makespan {st['makespan']}")


if __name__ == "__main__":
    main()
