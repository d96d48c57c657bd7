#!/bin/bash
# label: bench
# Ctrl-C while earc-bench builds a Lightning database: the build is
# stopped, and the run says it was interrupted, not that the build failed
# (it said "building ... failed (SIGKILL): ; its Lightning trials will
# fail"). Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
failShowsOutput
cd "$WORK" || exit 1

# 400 problems of up to 2 s each: minutes of building, far more than the wait.
"$BENCH" run --suites mobile-obst --robots 16 --methods lightning --trials 1 --time-limit 5 --seed 3 \
  --lightning-problems 400 --lightning-problem-time-limit 2 --results r.sqlite > out 2> err &
pid=$!
for _ in $(seq 1 300); do
  grep -q "building Lightning database" out err 2>/dev/null && break
  kill -0 $pid 2>/dev/null || fail "the run ended before its Lightning build"
  sleep 0.1
done
grep -q "building Lightning database" out err || fail "no Lightning build started"
sleep 0.5
kill -INT $pid
endsWithin $pid 30 "the run, after SIGINT,"
wait $pid
status=$?
[ $status -ne 0 ] || fail "an interrupted run exited 0"
grep -qi "interrupted" out err || fail "the run did not say it was interrupted"
grep -q "failed" err && fail "an interrupted build was reported as failed: $(cat err)"
echo "ok: an interrupted Lightning build is said as an interruption"
