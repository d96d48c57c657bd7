#!/bin/bash
# label: bench
# Trials that crash, hang or return an invalid solution are failures, and
# the run goes on: a planner child that dies of SIGSEGV and one that never
# returns (test faults, EARC_BENCH_FAULT=METHOD:crash|hang), and a planner
# (a stand-in for earc-plan) whose solution teleports, which must be
# reported loudly. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
BENCH="$BUILD/earc-bench"
PLAN="$BUILD/earc-plan"
PY=/usr/bin/python3
[ -x "$PY" ] || { echo "skipped: no $PY"; exit 77; }
[ -x "$BENCH" ] && [ -x "$PLAN" ] || { echo "FAIL: earc-bench or earc-plan not built in $BUILD"; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
query() {
  "$PY" -c 'import sqlite3,sys
c = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
for r in c.execute(sys.argv[2]): print("|".join("" if v is None else str(v) for v in r))' "$1" "$2"
}
BASE=(run --suites mobile --robots 2 --trials 1 --seed 5)

# A crash.
EARC_BENCH_FAULT=arc:crash "$BENCH" "${BASE[@]}" --methods arc,prioritized --time-limit 10 \
  --results "$WORK/crash.sqlite" > "$WORK/crash.out" 2>&1 || fail "run with a crashing trial exited $?"
got=$(query "$WORK/crash.sqlite" "SELECT method, success, term_signal, failure FROM trials ORDER BY method")
echo "$got" | grep -q "^arc|0|11|crashed: SIGSEGV" || fail "crash not recorded as such: $got"
echo "$got" | grep -q "^prioritized|" || fail "the run stopped at the crash: $got"

# A hang, killed at the time limit plus the margin.
start=$(date +%s)
EARC_BENCH_FAULT=prioritized:hang "$BENCH" "${BASE[@]}" --methods prioritized --time-limit 1 --wall-margin 1 \
  --results "$WORK/hang.sqlite" > "$WORK/hang.out" 2>&1 || fail "run with a hanging trial exited $?"
[ $(( $(date +%s) - start )) -lt 30 ] || fail "the hanging trial was not killed in time"
got=$(query "$WORK/hang.sqlite" "SELECT success, term_signal, failure, wall_time_s < 5 FROM trials")
echo "$got" | grep -q "^0|9|killed at the wall-clock limit (2 s)|1" || fail "hang not recorded as such: $got"

# An invalid solution: every robot jumps from start to goal in one step.
cat > "$WORK/fake-plan" <<FAKE
#!/bin/bash
if [ "\$1" != plan ]; then exec "$PLAN" "\$@"; fi
scenario=\$2; out=""
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
exec "$PY" -c 'import json,sys
s = json.load(open(sys.argv[1]))
paths = [{"robot": r["name"], "states": [r["start"], r["goal"]]} for r in s["robots"]]
json.dump({"format": "earc.solution.v1", "scenario": s["name"], "method": "arc", "solved": True,
           "paths": paths, "stats": {"planning_time_s": 0.01}}, open(sys.argv[2], "w"))' "\$scenario" "\$out"
FAKE
chmod +x "$WORK/fake-plan"
"$BENCH" "${BASE[@]}" --methods arc --time-limit 10 --plan-program "$WORK/fake-plan" \
  --results "$WORK/invalid.sqlite" > "$WORK/invalid.out" 2> "$WORK/invalid.err"
rc=$?
[ $rc -eq 1 ] || fail "a run with an invalid solution exited $rc, not 1"
grep -q "^INVALID SOLUTION: mobile, 2 robots, method arc, trial 0: INVALID" "$WORK/invalid.err" \
  || fail "no loud report: $(cat "$WORK/invalid.err")"
got=$(query "$WORK/invalid.sqlite" "SELECT success, failure FROM trials")
echo "$got" | grep -q "^0|invalid solution: INVALID" || fail "invalid solution not recorded as a failure: $got"
echo "ok: crash, hang and invalid solution are failures"
