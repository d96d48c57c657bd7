#!/usr/bin/python3
"""Figures from an earc-bench results database (PNG and SVG).

    /usr/bin/python3 tools/plots/plot_results.py --results FILE.sqlite -o DIR
        [--seed S] [--time-limit S]

Writes, per suite, time_<suite> (median planning time of solved trials
against robot count per method, the band spanning the quartiles, log scale;
a cell where some trials failed drawn hollow and labelled "k/n", one where
all failed an x on the time limit's dotted line; each method with its own
marker, its points moved a little aside so that equal times both show)
and success_<suite> (success rate per robot count and method), and
databases (construction time per method against robot count; a database
that serves every robot count, like E-ARC's, is a horizontal line), and,
when the results hold crowd suites, crowds (per map: time to the first
solution and success against robot count per method, and sum of costs
over the lower bound; tools/plots/crowd_figure.py).
Trials under different time limits are different experiments: a suite run
under several gets a pair of figures per limit, time_<suite>-tl<limit>
and success_<suite>-tl<limit> (as `earc-bench table` gives it a table per
limit). --seed and --time-limit take only the trials of that run seed or
time limit, as table's do. A method whose trials ran with planner
arguments (earc-bench run --method-arg) is named with them, "E-ARC
--db-k=5", as table names it. Nothing is drawn at random, and the SVGs carry
no date and fixed ids: the same file gives the same figures, byte for
byte.
A row with a value no run writes (a planning time that is not a number,
or is negative or beyond its solved trial's time limit; a robot count
outside 2..1024; an unknown suite or method; ...) refuses the file, as
earc-bench's reader does (src/bench/results_db.cpp, which `earc-bench
plot` runs before this script). Every error is one line naming the file:
exit status 2 for a missing, foreign or newer results file, a row no run
writes and an output path that is not a directory, 1 when drawing or
writing fails.
"""
import argparse
import collections
import json
import math
import os
import shlex
import sqlite3
import sys
import urllib.parse

try:
    import matplotlib

    matplotlib.use("Agg")
    # SVG element ids are random unless salted, and an SVG carries the date
    # it was drawn: neither, so that figures of the same results are the
    # same files.
    matplotlib.rcParams["svg.hashsalt"] = "earc-bench"
    import matplotlib.pyplot as plt
    import numpy as np

    import crowd_figure
except ImportError as e:
    print("plot_results.py: needs matplotlib and numpy (%s)" % e, file=sys.stderr)
    sys.exit(1)

APPLICATION_ID = 0x45424E43  # "EBNC", include/earc/bench/results_db.hpp
SCHEMA_VERSION = 9  # kResultsSchemaVersion there
# A solved trial's planning time may be this much over its limit (the
# planners poll their deadline): kSolvedTimeLimitSlack in results_db.hpp.
TIME_LIMIT_SLACK = 1.01
MAX_ROBOTS = 1024  # kMaxResultsRobots there
# allSuites() then kFilesSuite (earc-bench run FILE...): suites.hpp.
CROWD_SUITES = ["crowd-empty-16-16", "crowd-random-32-32-20", "crowd-room-32-32-4", "crowd-warehouse-10-20-10-2-1"]
SUITES = ["mobile", "mobile-obst", "arms", "arms-obst", "movingai-random", "movingai-den520d"] + CROWD_SUITES + ["files"]
METHODS = ["earc", "arc", "lightning", "prioritized", "coupled", "lacam"]
LABELS = {"earc": "E-ARC", "arc": "ARC", "lightning": "Lightning", "prioritized": "Prioritized",
          "coupled": "Coupled RRT-Connect", "lacam": "LaCAM"}
# Line style and marker per suite: databases of one method for several
# suites share its colour.
SUITE_STYLES = {"mobile": ("-", "o"), "mobile-obst": ("--", "^"), "arms": (":", "s"), "arms-obst": ("-.", "D"),
                "movingai-random": ((0, (5, 1)), "v"), "movingai-den520d": ((0, (1, 1, 3, 1)), "P"),
                "files": ((0, (3, 1, 1, 1, 1, 1)), "X")}
COLORS = {"earc": "tab:red", "arc": "tab:blue", "lightning": "tab:green", "prioritized": "tab:purple",
          "coupled": "tab:orange", "lacam": "tab:brown"}
# Marker per method in the time figures, and how far apart (in octaves of
# the robot count) the methods' points of one count are drawn: E-ARC and
# ARC often take the same time, and one point hid the other.
MARKERS = {"earc": "o", "arc": "s", "lightning": "^", "prioritized": "D", "coupled": "v", "lacam": "P"}
DODGE_OCTAVES = 0.05


# One trial as the figures need it; args: the planner arguments it ran
# with (earc-bench run --method-arg), a tuple, () for none; the cost
# columns (schema 9) for the crowd figure, None where a trial has none.
Trial = collections.namedtuple("Trial", "suite time_limit robots method success planning_time args sum_of_costs "
                               "lower_bound refine_first_time refine_first_sum_of_costs refine_final_sum_of_costs",
                               defaults=(None,) * 5)
# Read without a check of their own: whole numbers of 0 or more, or None.
COST_COLUMNS = ["sum_of_costs", "lower_bound", "refine_first_time_s", "refine_first_sum_of_costs",
                "refine_final_sum_of_costs"]


def ordered(values, order):
    known = [v for v in order if v in values]
    return known + sorted(v for v in values if v not in order)


class BadInput(Exception):
    """Bad input: one line naming the file, exit status 2."""


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def is_int(v):
    return isinstance(v, int) and not isinstance(v, bool)


def is_seed(v):
    return isinstance(v, str) and v.isascii() and v.isdigit() and str(int(v)) == v and int(v) < 2 ** 64


def one_of(names, what):
    return (lambda v: v in names, "is not %s (%s)" % (what, ", ".join(names)))


# What each column read must hold and what a value that does not is told:
# as earc-bench's reader (CheckedResultRow in src/bench/results_db.cpp)
# checks the same columns.
SECONDS = (lambda v: v is None or (is_number(v) and v >= 0), "is not a number of seconds (0 or more)")
ROBOTS = "a robot count from 2 to %d" % MAX_ROBOTS
TRIAL_COLUMNS = {"suite": one_of(SUITES, "a suite earc-bench runs"),
                 "robots": (lambda v: is_int(v) and 2 <= v <= MAX_ROBOTS, "is not " + ROBOTS),
                 "method": one_of(METHODS, "a method earc-bench runs"),
                 "seed": (is_seed, "is not a seed (a whole number from 0 to 2^64-1 as decimal text)"),
                 "time_limit_s": (lambda v: is_number(v) and v > 0, "is not a number of seconds above 0"),
                 "success": (lambda v: is_int(v) and v in (0, 1), "is not 0 or 1"),
                 "planning_time_s": SECONDS}
DATABASE_COLUMNS = {"method": one_of(["earc", "lightning"], "a method with a database"),
                    "suite": one_of(SUITES, "a suite earc-bench runs"),
                    "robots": (lambda v: is_int(v) and (v == 0 or 2 <= v <= MAX_ROBOTS),
                               "is not 0 (every robot count) or " + ROBOTS),
                    "construction_time_s": SECONDS}


def shown(v):
    """A value as earc-bench's messages show it."""
    if v is None:
        return "NULL"
    if isinstance(v, float):
        return "%g" % v
    if isinstance(v, bytes):
        return "a blob"
    return repr(v) if isinstance(v, str) else str(v)


def planner_args(v):
    """The planner_args column as a tuple, or None when it holds what no
    run writes: NULL (none) or a JSON array of at least one non-empty
    string (earc-bench checks more: CheckedResultRow::plannerArgs)."""
    if v is None:
        return ()
    try:
        args = json.loads(v) if isinstance(v, str) else None
    except ValueError:
        return None
    if not isinstance(args, list) or not args or not all(isinstance(a, str) and a for a in args):
        return None
    return tuple(args)


def label(method, rows):
    """A method as the legend names it: with the planner arguments its
    trials ran with, as `earc-bench table` names it ("E-ARC --db-k=5")."""
    args = {t.args for t in rows if t.method == method}
    name = LABELS.get(method, method)
    if len(args) != 1 or not next(iter(args)):
        return name
    return "%s %s" % (name, shlex.join(next(iter(args))))


def check_row(path, table, row, columns):
    """Refuses the file (BadInput) for a value no run writes."""
    def bad(column, why):
        raise BadInput("%s: %s row id %s, column %s: %s" % (path, table, row["id"], column, why))
    for column, (ok, says) in columns.items():
        if not ok(row[column]):
            bad(column, "%s %s" % (shown(row[column]), says))
    if table == "trials" and row["success"] and row["planning_time_s"] is not None \
            and row["planning_time_s"] > row["time_limit_s"] * TIME_LIMIT_SLACK:
        bad("planning_time_s", "%s s of a solved trial is beyond its time limit of %s s"
            % (shown(row["planning_time_s"]), shown(row["time_limit_s"])))


def own_wal_header(path):
    """Whether the file starts with an SQLite header in WAL mode (bytes 18
    and 19 are 2) carrying the results database's application_id."""
    try:
        with open(path, "rb") as f:
            h = f.read(100)
    except OSError:
        return False
    return (len(h) == 100 and h[:16] == b"SQLite format 3\0" and h[18] == 2 and h[19] == 2
            and int.from_bytes(h[68:72], "big") == APPLICATION_ID)


def load(path, seed, time_limit):
    if not os.path.exists(path):
        raise BadInput("%s: no such file" % path)
    if not os.path.isfile(path):
        raise BadInput("%s: not a regular file" % path)
    # Our own file in WAL mode (its header says so) opens read-write under
    # query_only: SQLite lets only a read-write connection remove the -wal
    # and -shm files when it closes last, and a read-only one leaves them
    # beside the file. Any other file opens read-only, so that a foreign
    # file's WAL is never copied into it. As earc-bench's own reads do.
    mode = "rw" if own_wal_header(path) else "ro"
    try:
        # A URI, so that the mode applies; quoted, so that '?', '#' or '%'
        # in its name stay part of the name.
        con = sqlite3.connect("file:%s?mode=%s" % (urllib.parse.quote(os.path.abspath(path)), mode), uri=True)
        con.execute("PRAGMA query_only = ON")
    except sqlite3.Error as e:
        raise BadInput("%s: cannot open the results database: %s" % (path, e))
    try:
        try:
            app = con.execute("PRAGMA application_id").fetchone()[0]
            version = con.execute("PRAGMA user_version").fetchone()[0]
        except sqlite3.DatabaseError as e:
            raise BadInput("%s: not an SQLite file (expected an earc-bench results database): %s" % (path, e))
        if app != APPLICATION_ID:
            raise BadInput("%s: not an earc-bench results database (application_id %d)" % (path, app))
        if version > SCHEMA_VERSION:
            raise BadInput("%s: results schema version %d is newer than this program's %d; use a newer earc-bench"
                           % (path, version, SCHEMA_VERSION))
        if version < 1:
            raise BadInput("%s: results database without a schema version" % path)
        try:
            con.row_factory = sqlite3.Row
            # Schema 5 added planner_args; older files ran with none.
            args_column = "planner_args" if version >= 5 else "NULL AS planner_args"
            # Schema 9 added the lower bound and the refine columns.
            cost_columns = ", ".join(c if version >= 9 or c == "sum_of_costs" else "NULL AS " + c
                                     for c in COST_COLUMNS)
            rows = con.execute("SELECT id, %s, %s, %s FROM trials ORDER BY id"
                               % (", ".join(TRIAL_COLUMNS), args_column, cost_columns)).fetchall()
            db_rows = con.execute("SELECT id, %s FROM databases ORDER BY id"
                                  % ", ".join(DATABASE_COLUMNS)).fetchall()
        except sqlite3.DatabaseError as e:
            raise BadInput("%s: cannot read the results: %s" % (path, e))
    finally:
        con.close()
    trials = []
    first_of_method = {}  # method: (row id, its planner arguments)
    for r in rows:
        check_row(path, "trials", r, TRIAL_COLUMNS)
        args = planner_args(r["planner_args"])
        if args is None:
            raise BadInput("%s: trials row id %s, column planner_args: %s is not a JSON array of planner arguments "
                           "(strings)" % (path, r["id"], shown(r["planner_args"])))
        first = first_of_method.setdefault(r["method"], (r["id"], args, r["planner_args"]))
        if first[1] != args:
            raise BadInput("%s: trials row id %s, column planner_args: %s beside %s of method %s in row id %s: a "
                           "results file holds one set of planner arguments per method"
                           % (path, r["id"], shown(r["planner_args"]), shown(first[2]), r["method"], first[0]))
        if (seed is None or r["seed"] == str(seed)) and (time_limit is None or r["time_limit_s"] == time_limit):
            trials.append(Trial(r["suite"], r["time_limit_s"], r["robots"], r["method"], bool(r["success"]),
                                r["planning_time_s"], args, *(r[c] for c in COST_COLUMNS)))
    dbs = []
    for r in db_rows:
        check_row(path, "databases", r, DATABASE_COLUMNS)
        dbs.append(tuple(r[c] for c in DATABASE_COLUMNS))
    return trials, dbs


def save(fig, out, name):
    for ext in ("png", "svg"):
        # No date in the SVG (its metadata), so that it is the same file
        # every time.
        metadata = {"Date": None} if ext == "svg" else None
        fig.savefig(os.path.join(out, "%s.%s" % (name, ext)), dpi=150, bbox_inches="tight", metadata=metadata)
    plt.close(fig)
    return name


def experiments(trials):
    """The figures' experiments: (name suffix, title, trials) per suite and
    time limit, suites in their order and limits ascending. A suite run
    under several limits gets "-tl<limit>" and ", time limit <limit> s",
    as `earc-bench table` heads its tables and `export` names its logs."""
    out = []
    for suite in ordered({t.suite for t in trials}, SUITES):
        limits = sorted({t.time_limit for t in trials if t.suite == suite})
        for limit in limits:
            rows = [t for t in trials if t.suite == suite and t.time_limit == limit]
            if len(limits) == 1:
                out.append((suite, suite, rows))
            else:
                out.append(("%s-tl%g" % (suite, limit), "%s, time limit %g s" % (suite, limit), rows))
    return out


def time_cells(rows, method):
    """One method's cells of a time figure, by robot count: (robots, solved
    trials, trials, (q1, median, q3) of the solved trials' planning times or
    None when none solved)."""
    cells = []
    for n in sorted({t.robots for t in rows if t.method == method}):
        cell = [t for t in rows if t.method == method and t.robots == n]
        times = [t.planning_time for t in cell if t.success and t.planning_time is not None]
        quartiles = tuple(float(q) for q in np.percentile(times, [25, 50, 75])) if times else None
        cells.append((n, len(times), len(cell), quartiles))
    return cells


def plot_times(rows, name, title, out):
    """The median over the solved trials only would understate a method
    that failed some: a cell where not every trial solved is drawn hollow
    and labelled "k/n", one where none solved is an x on the time limit's
    line."""
    fig, ax = plt.subplots(figsize=(6, 4))
    limit = max(t.time_limit for t in rows)
    drawn = partial = unsolved = False
    # Labels of the x marks already put at a robot count: the next one goes
    # above them, as the marks of methods that all failed nearly coincide.
    stacked = {}
    methods = ordered({t.method for t in rows}, METHODS)
    for place, method in enumerate(methods):
        color = COLORS.get(method)
        marker = MARKERS.get(method, "o")
        # Each method's points moved a little aside, in order, so that
        # methods of equal times show side by side.
        shift = 2 ** ((place - (len(methods) - 1) / 2) * DODGE_OCTAVES)
        cells = time_cells(rows, method)
        solved = [(n, k, total, q) for n, k, total, q in cells if q]
        if solved:
            xs = [n * shift for n, _, _, _ in solved]
            lo, med, hi = ([max(q[i], 1e-4) for _, _, _, q in solved] for i in range(3))
            ax.plot(xs, med, marker=marker, label=label(method, rows), color=color)
            ax.fill_between(xs, lo, hi, alpha=0.2, color=color)
            drawn = True
        for n, k, total, q in cells:
            if k == total:
                continue
            y = max(q[1], 1e-4) if q else limit
            if q:
                ax.plot([n * shift], [y], marker=marker, markerfacecolor="white", markeredgecolor=color, color=color)
                partial = True
            else:
                ax.plot([n * shift], [y], marker="x", markersize=8, color=color, linestyle="none")
                unsolved = True
            # Left of the point at the last robot count, so as not to run off the axes.
            last = n == max(t.robots for t in rows)
            rise = 4
            if not q:
                rise += 8 * stacked.get(n, 0)
                stacked[n] = stacked.get(n, 0) + 1
            ax.annotate("%d/%d" % (k, total), (n * shift, y), textcoords="offset points", xytext=(-6 if last else 6, rise),
                        ha="right" if last else "left", fontsize="x-small", color=color)
    ax.axhline(limit, color="0.4", linestyle=":", linewidth=1, label="time limit %g s" % limit)
    if partial:
        ax.plot([], [], marker="o", markerfacecolor="white", markeredgecolor="0.3", color="0.3", linestyle="none",
                label="k/n: k of n trials solved")
    if unsolved:
        ax.plot([], [], marker="x", color="0.3", linestyle="none", label="none solved")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    counts = sorted({t.robots for t in rows})
    if counts:
        ax.set_xticks(counts)
        ax.set_xticklabels([str(n) for n in counts])
    ax.set_xlabel("robots")
    ax.set_ylabel("planning time of solved trials (s)")
    trials = sorted({total for method in {t.method for t in rows} for _, _, total, _ in time_cells(rows, method)})
    note = "%s trials per cell" % "/".join(str(n) for n in trials)
    if "time limit" not in title:  # a suite under several limits has it in its title
        note += ", time limit %g s" % limit
    ax.set_title("%s: median and quartiles\n(%s)" % (title, note), fontsize="medium")
    ax.grid(True, which="both", alpha=0.3)
    if drawn or partial or unsolved:
        ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return save(fig, out, "time_%s" % name)


def plot_success(rows, name, title, out):
    counts = sorted({t.robots for t in rows})
    methods = ordered({t.method for t in rows}, METHODS)
    fig, ax = plt.subplots(figsize=(6, 4))
    width = 0.8 / max(1, len(methods))
    for i, method in enumerate(methods):
        rates = []
        for n in counts:
            cell = [t for t in rows if t.method == method and t.robots == n]
            rates.append(100.0 * sum(t.success for t in cell) / len(cell) if cell else np.nan)
        xs = np.arange(len(counts)) + (i - (len(methods) - 1) / 2) * width
        ax.bar(xs, rates, width, label=label(method, rows), color=COLORS.get(method))
        # A bar of height 0 is invisible: mark trials that all failed.
        for x, rate in zip(xs, rates):
            if rate == 0:
                ax.text(x, 1, "0", ha="center", va="bottom", fontsize="x-small", color=COLORS.get(method))
    ax.set_xticks(np.arange(len(counts)))
    ax.set_xticklabels([str(n) for n in counts])
    ax.set_ylim(0, 105)
    ax.set_xlabel("robots")
    ax.set_ylabel("solved (%)")
    ax.set_title("%s: success rate" % title)
    if methods:
        ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return save(fig, out, "success_%s" % name)


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
    except BadInput as e:
        print("plot_results.py: %s" % e, file=sys.stderr)
        return 2
    if os.path.exists(a.output) and not os.path.isdir(a.output):
        print("plot_results.py: %s: -o: exists and is not a directory" % a.output, file=sys.stderr)
        return 2
    try:
        os.makedirs(a.output, exist_ok=True)
    except OSError as e:
        print("plot_results.py: %s: -o: cannot create the directory: %s" % (a.output, e.strerror or e),
              file=sys.stderr)
        return 2
    written = []
    try:
        for name, title, rows in experiments(trials):
            written.append(plot_times(rows, name, title, a.output))
            written.append(plot_success(rows, name, title, a.output))
        written.append(plot_databases(dbs, a.output))
        crowds = [t for t in trials if t.suite in CROWD_SUITES]
        if crowds:
            written.append(crowd_figure.plot_crowds(crowds, a.output, save, ordered(set(CROWD_SUITES), CROWD_SUITES),
                                                    ordered({t.method for t in crowds}, METHODS),
                                                    lambda m: label(m, crowds), COLORS, MARKERS))
    except OSError as e:
        print("plot_results.py: %s: cannot write a figure: %s" % (e.filename or a.output, e.strerror or e),
              file=sys.stderr)
        return 1
    except Exception as e:  # one line, never a traceback
        print("plot_results.py: %s: drawing the figures failed: %s: %s" % (a.results, type(e).__name__, e),
              file=sys.stderr)
        return 1
    for name in written:
        print(os.path.join(a.output, name + ".{png,svg}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
