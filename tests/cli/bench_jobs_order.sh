#!/bin/bash
# label: bench
# With several jobs, the trials that run side by side are of one method:
# each method's trials of a cell come in a row. (Side by side, E-ARC's and
# ARC's trials of one scenario started together, and E-ARC's start-up ran
# beside ARC's planning, which flattered E-ARC.) With one job the methods
# take turns trial by trial (bench_quick.sh checks that). Skipped (77)
# without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
"$BENCH" run --suites mobile --robots 2,4 --methods arc,prioritized --trials 4 --time-limit 10 --seed 3 --jobs 2 \
  --results "$WORK/r.sqlite" > "$WORK/out" 2>&1 || { cat "$WORK/out"; fail "run exited $?"; }
"$PY" - "$WORK/r.sqlite" <<'PYEOF' || fail "order of the trials"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
order = [(r, m) for r, m in con.execute("SELECT robots, method FROM trials ORDER BY rowid")]
assert len(order) == 16, order
for robots in (2, 4):
    methods = [m for r, m in order if r == robots]
    # Two workers: the last arc trial may finish after the first
    # prioritized one, no more.
    assert methods[:3] == ["arc"] * 3 and methods[-3:] == ["prioritized"] * 3, order
    assert methods.count("arc") == 4, order
PYEOF
echo ok
