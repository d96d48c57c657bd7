"""The crowd suites' figure for plot_results.py: one column per map, time to
the first solution against robot count per method on top (a failed count
an x on the time limit's line), sum of costs over the lower bound below
(the first plan solid, the refined one dashed where trials refined). The
lower bound: each robot's own shortest path on the grid in steps, ignoring
the others (docs/benchmarks-crowds.md)."""
import statistics

import matplotlib.pyplot as plt


def _median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def _cells(rows, method):
    """(robots, solved, trials, median first time, median first ratio,
    median refined ratio) per robot count of one method."""
    out = []
    for n in sorted({t.robots for t in rows if t.method == method}):
        cell = [t for t in rows if t.method == method and t.robots == n]
        ok = [t for t in cell if t.success]
        first_time = [t.refine_first_time if t.refine_first_time is not None else t.planning_time for t in ok]
        ratio, refined = [], []
        for t in ok:
            soc = t.refine_first_sum_of_costs if t.refine_first_sum_of_costs is not None else t.sum_of_costs
            if soc is not None and t.lower_bound:
                ratio.append(soc / t.lower_bound)
            if t.refine_final_sum_of_costs is not None and t.lower_bound:
                refined.append(t.refine_final_sum_of_costs / t.lower_bound)
        out.append((n, len(ok), len(cell), _median(first_time), _median(ratio), _median(refined)))
    return out


def plot_crowds(rows, out, save, suites, methods, label, colors, markers):
    """Draws crowds.{png,svg} into out with save(fig, out, name); returns
    the name."""
    suites = [s for s in suites if any(t.suite == s for t in rows)]
    fig, axes = plt.subplots(2, len(suites), figsize=(4.2 * len(suites), 7), squeeze=False, sharex="col")
    for col, suite in enumerate(suites):
        top, bottom = axes[0][col], axes[1][col]
        srows = [t for t in rows if t.suite == suite]
        limit = max(t.time_limit for t in srows)
        for place, method in enumerate(methods):
            cells = _cells(srows, method)
            if not cells:
                continue
            color, marker = colors.get(method), markers.get(method, "o")
            solved = [c for c in cells if c[3] is not None]
            top.plot([c[0] for c in solved], [max(c[3], 1e-4) for c in solved], marker=marker, color=color,
                     label=label(method))
            failed = [c for c in cells if c[1] < c[2]]
            top.plot([c[0] for c in failed], [limit] * len(failed), marker="x", markersize=8, color=color,
                     linestyle="none")
            # Each method's label a line lower: methods that failed one count
            # share its point.
            for c in failed:
                top.annotate("%d/%d" % (c[1], c[2]), (c[0], limit), textcoords="offset points",
                             xytext=(-4, -10 - 9 * place), ha="right", fontsize="x-small", color=color)
            ratio = [c for c in cells if c[4] is not None]
            bottom.plot([c[0] for c in ratio], [c[4] for c in ratio], marker=marker, color=color, label=label(method))
            refined = [c for c in cells if c[5] is not None]
            if refined:
                bottom.plot([c[0] for c in refined], [c[5] for c in refined], marker=marker, color=color,
                            linestyle="--", markerfacecolor="white", label=label(method) + " refined")
        top.axhline(limit, color="0.4", linestyle=":", linewidth=1)
        top.set_yscale("log")
        top.set_title("%s\n(x: not solved; time limit %g s)" % (suite, limit), fontsize="medium")
        top.set_ylabel("time to first solution (s)")
        bottom.axhline(1.0, color="0.4", linestyle=":", linewidth=1)
        bottom.set_ylabel("sum of costs / lower bound")
        bottom.set_xlabel("robots")
        for ax in (top, bottom):
            ax.grid(True, which="both", alpha=0.3)
        if col == len(suites) - 1:
            top.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.0, 1.0))
            bottom.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    return save(fig, out, "crowds")
