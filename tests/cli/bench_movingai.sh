#!/bin/bash
# label: bench
# The MovingAI suites end to end: ARC and E-ARC on the random field and on
# den520d (maps compiled into the programs, so run from an empty
# directory), one trial each, every solution solved and valid; when
# ../shared is beside the source, the independent checker agrees. An
# unknown suite is refused with the list of suites. Skipped (77) without
# /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
CHECKER="$SRC/../shared/tools/check_solution.py"
needPython
needBuilt earc-bench earc-plan
fail() { echo "FAIL: $*"; sed 's/^/  run: /' "$WORK/out" 2>/dev/null | tail -30; exit 1; }
cd "$WORK" || exit 1

"$BENCH" run --suites movingai-random,movingai-den520d --robots 4 --methods arc,earc --trials 1 --time-limit 30 \
  --seed 5 --earc-db-count 300 --keep-solutions --results r.sqlite > out 2>&1 || fail "earc-bench run exited $?"
grep -q "INVALID SOLUTION" out && fail "a planner produced an invalid solution"
"$PY" - r.sqlite <<'PYEOF' || fail "results"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
rows = con.execute("SELECT suite, method, success, failure FROM trials ORDER BY suite, method").fetchall()
assert [(r[0], r[1]) for r in rows] == [("movingai-den520d", "arc"), ("movingai-den520d", "earc"),
                                       ("movingai-random", "arc"), ("movingai-random", "earc")], rows
assert all(r[2] == 1 for r in rows), rows
PYEOF

n=0
for sol in r.sqlite.work/solutions/*.json; do
  name=$(basename "$sol" .json)           # SUITE-4-t0-METHOD
  scen=$(ls r.sqlite.work/scenarios/"${name%-*}"-*.json)
  "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert len(d["obstacles"]) > 50, len(d["obstacles"])' "$scen" ||
    fail "$scen has no map obstacles"
  "$BUILD/earc-plan" validate "$scen" "$sol" > /dev/null || fail "earc-plan validate refuses $sol"
  if [ -f "$CHECKER" ] && "$PY" -c "import numpy" 2>/dev/null; then
    "$PY" "$CHECKER" "$scen" "$sol" > check.out || fail "check_solution.py refuses $sol: $(tail -3 check.out)"
  fi
  n=$((n + 1))
done
[ "$n" -eq 4 ] || fail "expected 4 kept solutions, found $n"

"$BENCH" run --help | grep -q "movingai-den520d" || fail "run --help does not list the MovingAI suites"
"$BENCH" run --suites harbour --trials 1 --results bad.sqlite > out 2>&1 && fail "an unknown suite was accepted"
grep -q "movingai-random, movingai-den520d" out || fail "the error does not list the suites: $(cat out)"
echo "ok: 4 MovingAI trials solved and valid"
