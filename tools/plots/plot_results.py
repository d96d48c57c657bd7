#!/usr/bin/python3
"""Figures from an earc-bench results database (PNG and SVG).

    /usr/bin/python3 tools/plots/plot_results.py --results FILE.sqlite -o DIR
        [--seed S] [--time-limit S]

Writes, per suite, time_<suite> (median planning time of solved trials
against robot count per method, the band spanning the quartiles, log scale)
and success_<suite> (success rate per robot count and method), and
databases (construction time per method against robot count; a database
that serves every robot count, like E-ARC's, is a horizontal line).
Exit status 0, or 2 for a missing or foreign results file.
"""
import argparse
import os
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

APPLICATION_ID = 0x45424E43  # "EBNC", include/earc/bench/results_db.hpp
SUITES = ["mobile", "mobile-obst", "arms", "arms-obst", "movingai-random", "movingai-den520d"]
METHODS = ["earc", "arc", "lightning", "prioritized", "coupled"]
LABELS = {"earc": "E-ARC", "arc": "ARC", "lightning": "Lightning", "prioritized": "Prioritized",
          "coupled": "Coupled RRT-Connect"}
# Line style and marker per suite: databases of one method for several
# suites share its colour.
SUITE_STYLES = {"mobile": ("-", "o"), "mobile-obst": ("--", "^"), "arms": (":", "s"), "arms-obst": ("-.", "D"),
                "movingai-random": ((0, (5, 1)), "v"), "movingai-den520d": ((0, (1, 1, 3, 1)), "P")}
COLORS = {"earc": "tab:red", "arc": "tab:blue", "lightning": "tab:green", "prioritized": "tab:purple",
          "coupled": "tab:orange"}


def ordered(values, order):
    known = [v for v in order if v in values]
    return known + sorted(v for v in values if v not in order)


def load(path, seed, time_limit):
    if not os.path.exists(path):
        raise FileNotFoundError("%s: no such file" % path)
    con = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    app = con.execute("PRAGMA application_id").fetchone()[0]
    if app != APPLICATION_ID:
        raise ValueError("%s: not an earc-bench results database (application_id %d)" % (path, app))
    query = "SELECT suite, robots, method, success, planning_time_s, seed, time_limit_s FROM trials"
    trials = []
    for suite, robots, method, success, t, s, limit in con.execute(query):
        if seed is not None and s != str(seed):
            continue
        if time_limit is not None and limit != time_limit:
            continue
        trials.append((suite, robots, method, bool(success), t))
    dbs = con.execute("SELECT method, suite, robots, construction_time_s FROM databases").fetchall()
    con.close()
    return trials, dbs


def save(fig, out, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, "%s.%s" % (name, ext)), dpi=150, bbox_inches="tight")
    plt.close(fig)
    return name


def plot_times(trials, suite, out):
    rows = [t for t in trials if t[0] == suite]
    fig, ax = plt.subplots(figsize=(6, 4))
    drawn = False
    for method in ordered({t[2] for t in rows}, METHODS):
        xs, med, lo, hi = [], [], [], []
        for n in sorted({t[1] for t in rows if t[2] == method}):
            times = [t[4] for t in rows if t[2] == method and t[1] == n and t[3] and t[4] is not None]
            if not times:
                continue
            q1, q2, q3 = np.percentile(times, [25, 50, 75])
            xs.append(n), med.append(max(q2, 1e-4)), lo.append(max(q1, 1e-4)), hi.append(max(q3, 1e-4))
        if not xs:
            continue
        color = COLORS.get(method)
        ax.plot(xs, med, marker="o", label=LABELS.get(method, method), color=color)
        ax.fill_between(xs, lo, hi, alpha=0.2, color=color)
        drawn = True
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    counts = sorted({t[1] for t in rows})
    if counts:
        ax.set_xticks(counts)
        ax.set_xticklabels([str(n) for n in counts])
    ax.set_xlabel("robots")
    ax.set_ylabel("planning time of solved trials (s)")
    ax.set_title("%s: median and quartiles" % suite)
    ax.grid(True, which="both", alpha=0.3)
    if drawn:
        ax.legend()
    return save(fig, out, "time_%s" % suite)


def plot_success(trials, suite, out):
    rows = [t for t in trials if t[0] == suite]
    counts = sorted({t[1] for t in rows})
    methods = ordered({t[2] for t in rows}, METHODS)
    fig, ax = plt.subplots(figsize=(6, 4))
    width = 0.8 / max(1, len(methods))
    for i, method in enumerate(methods):
        rates = []
        for n in counts:
            cell = [t for t in rows if t[2] == method and t[1] == n]
            rates.append(100.0 * sum(t[3] for t in cell) / len(cell) if cell else np.nan)
        xs = np.arange(len(counts)) + (i - (len(methods) - 1) / 2) * width
        ax.bar(xs, rates, width, label=LABELS.get(method, method), color=COLORS.get(method))
        # A bar of height 0 is invisible: mark trials that all failed.
        for x, rate in zip(xs, rates):
            if rate == 0:
                ax.text(x, 1, "0", ha="center", va="bottom", fontsize="x-small", color=COLORS.get(method))
    ax.set_xticks(np.arange(len(counts)))
    ax.set_xticklabels([str(n) for n in counts])
    ax.set_ylim(0, 105)
    ax.set_xlabel("robots")
    ax.set_ylabel("solved (%)")
    ax.set_title("%s: success rate" % suite)
    if methods:
        ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return save(fig, out, "success_%s" % suite)


def plot_databases(dbs, out):
    fig, ax = plt.subplots(figsize=(6, 4))
    built = [d for d in dbs if d[3] is not None]
    per_size = [d for d in built if d[2] > 0]
    counts = sorted({d[2] for d in per_size}) or [2, 32]
    for method, suite in sorted({(d[0], d[1]) for d in built}):
        series = sorted((d[2], d[3]) for d in built if d[0] == method and d[1] == suite)
        label = "%s (%s)" % (LABELS.get(method, method), suite)
        color = COLORS.get(method)
        line, marker = SUITE_STYLES.get(suite, ("-", "o"))
        if all(n == 0 for n, _ in series):
            # One database for every robot count: a level line, its time in
            # the legend too, since two such lines can lie on each other.
            ax.hlines(series[-1][1], min(counts), max(counts), label="%s, all sizes: %.3g s" % (label, series[-1][1]),
                      colors=color, linestyles=line)
        else:
            ax.plot([n for n, _ in series if n > 0], [max(s, 1e-3) for n, s in series if n > 0], marker=marker,
                    linestyle=line, label=label, color=color)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xticks(counts)
    ax.set_xticklabels([str(n) for n in counts])
    ax.set_xlabel("robots")
    ax.set_ylabel("construction time (s)")
    ax.set_title("database construction")
    ax.grid(True, which="both", alpha=0.3)
    if built:
        ax.legend(fontsize="small")
    return save(fig, out, "databases")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--seed", type=int)
    p.add_argument("--time-limit", type=float)
    a = p.parse_args()
    try:
        trials, dbs = load(a.results, a.seed, a.time_limit)
    except (OSError, ValueError, sqlite3.DatabaseError) as e:
        print("plot_results.py: %s" % e, file=sys.stderr)
        return 2
    os.makedirs(a.output, exist_ok=True)
    written = []
    for suite in ordered({t[0] for t in trials}, SUITES):
        written.append(plot_times(trials, suite, a.output))
        written.append(plot_success(trials, suite, a.output))
    written.append(plot_databases(dbs, a.output))
    for name in written:
        print(os.path.join(a.output, name + ".{png,svg}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
