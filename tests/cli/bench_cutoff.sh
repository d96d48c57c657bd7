#!/bin/bash
# label: bench
# earc-bench run --cutoff: a method that solved none of its trials at a
# robot count is not run at the larger counts of that suite (here coupled
# is made to crash in every trial by EARC_BENCH_FAULT), and the run says
# so; other methods run everywhere, also with two workers (a count waits
# for the smaller count's last trials). Without --cutoff everything runs.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
fail() { echo "FAIL: $*"; sed 's/^/  run: /' "$WORK/out" 2>/dev/null | tail -30; exit 1; }
count() {  # count RESULTS METHOD ROBOTS
  "$PY" -c 'import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); print(c.execute("SELECT count(*) FROM trials WHERE method=? AND robots=?", (sys.argv[2], int(sys.argv[3]))).fetchone()[0])' "$@"
}

RUN=(run --suites mobile --robots 2,4 --methods arc,coupled --trials 2 --time-limit 5 --seed 3)
EARC_BENCH_FAULT=coupled:crash "$BENCH" "${RUN[@]}" --cutoff --jobs 2 --results "$WORK/cut.sqlite" > "$WORK/out" 2>&1 ||
  fail "run with --cutoff exited $?"
grep -q "cut off: coupled on mobile from 4 robots (solved 0 of 2 at 2)" "$WORK/out" || fail "no cut-off note"
[ "$(count "$WORK/cut.sqlite" coupled 2)" -eq 2 ] || fail "coupled at 2 robots should have run twice"
[ "$(count "$WORK/cut.sqlite" coupled 4)" -eq 0 ] || fail "coupled at 4 robots ran despite --cutoff"
[ "$(count "$WORK/cut.sqlite" arc 4)" -eq 2 ] || fail "arc at 4 robots was cut too"

EARC_BENCH_FAULT=coupled:crash "$BENCH" "${RUN[@]}" --results "$WORK/all.sqlite" > "$WORK/out" 2>&1 ||
  fail "run without --cutoff exited $?"
[ "$(count "$WORK/all.sqlite" coupled 4)" -eq 2 ] || fail "without --cutoff coupled at 4 robots did not run"
grep -q "cut off" "$WORK/out" && fail "cut-off note without --cutoff"
echo "ok"
