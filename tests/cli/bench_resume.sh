#!/bin/bash
# label: bench
# An interrupted run resumes: the benchmark is killed with SIGKILL after a
# few trials finished; its planners must not outlive it, the results
# database must pass integrity_check, and the same command must then run
# only the trials that are missing. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
count() {
  "$PY" -c 'import sqlite3,sys
try:
    c = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
    print(c.execute("SELECT count(*) FROM trials").fetchone()[0])
except Exception:
    print(0)' "$WORK/r.sqlite"
}

RUN=(run --suites mobile --robots 2 --methods arc,prioritized --trials 30 --time-limit 10 --seed 3
     --results "$WORK/r.sqlite")
"$BENCH" "${RUN[@]}" > "$WORK/first.out" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ "$(count)" -ge 3 ] && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.2
done
kill -0 $pid 2>/dev/null || fail "the run ended before it could be interrupted: $(tail -3 "$WORK/first.out")"
{ kill -KILL $pid; wait $pid; } 2>/dev/null
before=$(count)
[ "$before" -ge 3 ] && [ "$before" -lt 60 ] || fail "$before trials recorded before the kill"
sleep 0.5
# PR_SET_PDEATHSIG: no planner of the killed run is left.
if ps -eo args= | grep -F "$WORK/r.sqlite.work" | grep -v grep > /dev/null; then
  fail "a child of the killed benchmark is still running"
fi

"$BENCH" "${RUN[@]}" > "$WORK/second.out" 2>&1 || fail "the resumed run exited $?: $(tail -3 "$WORK/second.out")"
grep -q "($before already recorded)" "$WORK/second.out" || fail "the resumed run did not skip $before trials: $(head -2 "$WORK/second.out")"
"$PY" - "$WORK/r.sqlite" <<'PYEOF' || fail "results database after the resume"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
assert con.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
rows = con.execute("SELECT method, trial FROM trials").fetchall()
assert len(rows) == 60 and len(set(rows)) == 60, rows
PYEOF
echo "ok: killed after $before trials, resumed to 60"
