#!/usr/bin/python3
"""Where a method's planning time goes, from earc-plan traces (Markdown).

    /usr/bin/python3 tools/plots/trace_breakdown.py NAME=DIR [NAME=DIR ...]
        [--cap N]

Each DIR holds, for every scenario planned, X.trace.json (earc-plan plan
--trace) and X.solution.json (its -o); runs are paired by X, and only the
scenarios every run has are counted. The first run is the base of the
ratios.

Prints two tables:
- per run and subproblem size (robots, sizes from --cap up pooled):
  subproblems, then each solver's attempts (in the hierarchy's order) (solved / failed) and summed
  seconds (solved / failed);
- what-if bounds per run against the base: planning time as measured; less
  the time of failed database attempts; less every failed attempt of any
  solver (as if each subproblem had gone straight to the solver that
  solved it); less all the solver time of subproblems of 2 to 4 robots (as
  if a database answered each of them at once). Each as the ratio of
  medians and the median of paired ratios. The bounds leave everything
  else as it was: later conflicts could differ if the answers did.

An attempt's time_s leaves out the roadmaps built when that solver first
asked for them (the attempt's roadmap_build_s, since 59e46e5): every plan
needs them whichever solver asks, so every bound keeps them. Traces made
before 59e46e5 had them inside time_s, so their bounds take a little more
away; compare runs traced by builds on the same side of that commit.

Every error is one line naming the file, with exit status 2.
"""
import argparse
import glob
import json
import math
import os
import statistics
import sys

TRACE_FORMAT = "earc.trace.v1"
HIERARCHY = ["database", "repair", "decoupled", "coupled"]


def fail(msg):
    print("trace_breakdown.py: " + msg, file=sys.stderr)
    sys.exit(2)


def load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: %s" % (path, e))


def number(x, path, field):
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x < 0:
        fail("%s: %s: expected a non-negative number, got %r" % (path, field, x))
    return float(x)


def read_plan(trace_path, solution_path):
    """(planning time, [(robots, [(solver, ok, seconds)])]) of one plan."""
    trace = load_json(trace_path)
    if not isinstance(trace, dict) or trace.get("format") != TRACE_FORMAT:
        fail("%s: format: not an %s trace" % (trace_path, TRACE_FORMAT))
    events = trace.get("events")
    if not isinstance(events, list):
        fail("%s: events: expected a list" % trace_path)
    subproblems = []
    for i, e in enumerate(events):
        if not isinstance(e, dict) or e.get("type") != "subproblem":
            continue
        robots, attempts = e.get("robots"), e.get("attempts")
        if not isinstance(robots, list) or not robots or not isinstance(attempts, list):
            fail("%s: events[%d]: a subproblem needs robots and attempts lists" % (trace_path, i))
        tried = []
        for j, a in enumerate(attempts):
            field = "events[%d].attempts[%d]" % (i, j)
            if not isinstance(a, dict) or not isinstance(a.get("solver"), str) or not isinstance(a.get("ok"), bool):
                fail("%s: %s: needs solver and ok" % (trace_path, field))
            tried.append((a["solver"], a["ok"], number(a.get("time_s"), trace_path, field + ".time_s")))
        subproblems.append((len(robots), tried))
    solution = load_json(solution_path)
    stats = solution.get("stats") if isinstance(solution, dict) else None
    if not isinstance(stats, dict):
        fail("%s: stats: missing" % solution_path)
    return number(stats.get("planning_time_s"), solution_path, "stats.planning_time_s"), subproblems


def read_run(spec):
    name, sep, directory = spec.partition("=")
    if not sep or not name or not directory:
        fail("%s: expected NAME=DIR" % spec)
    if not os.path.isdir(directory):
        fail("%s: not a directory" % directory)
    plans = {}
    for trace_path in sorted(glob.glob(os.path.join(directory, "*.trace.json"))):
        stem = os.path.basename(trace_path)[: -len(".trace.json")]
        solution_path = os.path.join(directory, stem + ".solution.json")
        if not os.path.exists(solution_path):
            fail("%s: no %s beside it" % (trace_path, stem + ".solution.json"))
        plans[stem] = read_plan(trace_path, solution_path)
    if not plans:
        fail("%s: no *.trace.json in it" % directory)
    return name, plans


def size_label(n, cap):
    return "%d+" % cap if n >= cap else str(n)


def per_size_table(runs, names, cap):
    seen = []
    for _, plans in runs:
        for stem in names:
            for _, tried in plans[stem][1]:
                for solver, _, _ in tried:
                    if solver not in seen:
                        seen.append(solver)
    # ARC's hierarchy order, then any other solver as first seen.
    solvers = [s for s in HIERARCHY if s in seen] + [s for s in seen if s not in HIERARCHY]
    head = "| run | robots | subproblems | " + " | ".join(
        "%s attempts (solved / failed) | %s s (solved / failed)" % (s, s) for s in solvers) + " |"
    print(head)
    print("|:---|---:|---:|" + "---:|---:|" * len(solvers))
    for run_name, plans in runs:
        sizes = {}
        for stem in names:
            for n, tried in plans[stem][1]:
                row = sizes.setdefault(min(n, cap), {"count": 0})
                row["count"] += 1
                for solver, ok, seconds in tried:
                    c = row.setdefault(solver, [0, 0, 0.0, 0.0])
                    c[0 if ok else 1] += 1
                    c[2 if ok else 3] += seconds
        for n in sorted(sizes):
            row = sizes[n]
            cells = []
            for s in solvers:
                c = row.get(s, [0, 0, 0.0, 0.0])
                cells.append("%d / %d | %.3f / %.3f" % tuple(c))
            print("| %s | %s | %d | %s |" % (run_name, size_label(n, cap), row["count"], " | ".join(cells)))


def bounds_table(runs, names):
    def spent(subproblems, keep):
        return sum(seconds for n, tried in subproblems for solver, ok, seconds in tried if keep(n, solver, ok))

    variants = [
        ("as measured", lambda n, s, ok: False),
        ("without failed database attempts", lambda n, s, ok: s == "database" and not ok),
        ("without any failed attempt", lambda n, s, ok: not ok),
        ("2-4 robot subproblems free", lambda n, s, ok: 2 <= n <= 4),
    ]
    base = [runs[0][1][stem][0] for stem in names]
    base_median = statistics.median(base)
    print("| run | planning time | median (s) | / %s medians | paired |" % runs[0][0])
    print("|:---|:---|---:|---:|---:|")
    for run_name, plans in runs:
        for label, drop in variants:
            times = [max(plans[stem][0] - spent(plans[stem][1], drop), 0.0) for stem in names]
            med = statistics.median(times)
            paired = statistics.median(t / b if b > 0 else math.inf for t, b in zip(times, base))
            ratio = med / base_median if base_median > 0 else math.inf
            print("| %s | %s | %.4f | %.2f | %.2f |" % (run_name, label, med, ratio, paired))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", metavar="NAME=DIR")
    ap.add_argument("--cap", type=int, default=5, help="pool subproblems of this many robots and more (default 5)")
    args = ap.parse_args()
    if args.cap < 2:
        fail("--cap: must be at least 2")
    runs = [read_run(spec) for spec in args.runs]
    names = sorted(set.intersection(*(set(plans) for _, plans in runs)))
    if not names:
        fail("no scenario is in every run (runs pair X.trace.json by X)")
    print("%d scenarios in every run\n" % len(names))
    per_size_table(runs, names, args.cap)
    print()
    bounds_table(runs, names)


if __name__ == "__main__":
    main()
