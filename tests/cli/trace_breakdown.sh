#!/bin/bash
# label: unsanitized
# tools/plots/trace_breakdown.py: sums attempts per subproblem size and
# solver, and its what-if bounds subtract exactly the attempts they name
# (hand-made traces with known times); it reads what earc-plan --trace
# writes; bad input is one line naming the file, exit 2.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-plan earc-scenario
needPython
TB="$SRC/tools/plots/trace_breakdown.py"

# One plan: a 2-robot subproblem (database failed 0.1 s, decoupled solved
# 0.2 s), a 3-robot one (decoupled failed 0.3 s, coupled solved 0.05 s),
# a 4-robot one (decoupled solved 0.01 s), a 5-robot one (decoupled solved
# 0.02 s), a 6-robot one (coupled solved 0.1 s); planning took 1 s.
mkdir -p "$WORK/a" "$WORK/b"
"$PY" - "$WORK" <<'PYEOF' || fail "could not write the traces"
import json, os, sys
w = sys.argv[1]
def sub(robots, attempts):
    return {"type": "subproblem", "robots": list(range(robots)),
            "attempts": [{"solver": s, "ok": ok, "time_s": t} for s, ok, t in attempts]}
events = [{"type": "conflict", "robots": [0, 1]},
          sub(2, [("database", False, 0.1), ("decoupled", True, 0.2)]),
          sub(3, [("decoupled", False, 0.3), ("coupled", True, 0.05)]),
          sub(4, [("decoupled", True, 0.01)]),
          sub(5, [("decoupled", True, 0.02)]),
          sub(6, [("coupled", True, 0.1)])]
for d, t in (("a", 1.0), ("b", 2.0)):
    json.dump({"format": "earc.trace.v1", "events": events}, open(os.path.join(w, d, "s1.trace.json"), "w"))
    json.dump({"stats": {"planning_time_s": t}}, open(os.path.join(w, d, "s1.solution.json"), "w"))
# Only in b: not paired, so not counted.
json.dump({"format": "earc.trace.v1", "events": []}, open(os.path.join(w, "b", "s2.trace.json"), "w"))
json.dump({"stats": {"planning_time_s": 9.0}}, open(os.path.join(w, "b", "s2.solution.json"), "w"))
PYEOF
"$PY" "$TB" one="$WORK/a" two="$WORK/b" > "$WORK/out.md" 2> "$WORK/err" || fail "exited $?: $(cat "$WORK/err")"
has() { grep -qF -- "$1" "$WORK/out.md" || fail "no line with '$1' in: $(cat "$WORK/out.md")"; }
has "1 scenarios in every run"
# Columns in the hierarchy's order: database, decoupled, coupled.
has "| run | robots | subproblems | database attempts (solved / failed) | database s (solved / failed) | decoupled"
has "| one | 2 | 1 | 0 / 1 | 0.000 / 0.100 | 1 / 0 | 0.200 / 0.000 | 0 / 0 | 0.000 / 0.000 |"
has "| one | 3 | 1 | 0 / 0 | 0.000 / 0.000 | 0 / 1 | 0.000 / 0.300 | 1 / 0 | 0.050 / 0.000 |"
has "| one | 4 | 1 | 0 / 0 | 0.000 / 0.000 | 1 / 0 | 0.010 / 0.000 | 0 / 0 | 0.000 / 0.000 |"
has "| one | 5+ | 2 | 0 / 0 | 0.000 / 0.000 | 1 / 0 | 0.020 / 0.000 | 1 / 0 | 0.100 / 0.000 |"
has "| one | as measured | 1.0000 | 1.00 | 1.00 |"
has "| one | without failed database attempts | 0.9000 | 0.90 | 0.90 |"
has "| one | without any failed attempt | 0.6000 | 0.60 | 0.60 |"
has "| one | 2-4 robot subproblems free | 0.3400 | 0.34 | 0.34 |"
has "| two | as measured | 2.0000 | 2.00 | 2.00 |"
has "| two | 2-4 robot subproblems free | 1.3400 | 1.34 | 1.34 |"
"$PY" "$TB" one="$WORK/a" --cap 7 > "$WORK/out.md" || fail "--cap 7 exited $?"
has "| one | 5 | 1 |"
has "| one | 6 | 1 |"

# What earc-plan writes.
mkdir -p "$WORK/real"
"$BUILD/earc-scenario" generate --family mobile --robots 8 --obstacles --seed 3 -o "$WORK/m.json" > /dev/null ||
  fail "generate exited $?"
"$BUILD/earc-plan" plan "$WORK/m.json" -o "$WORK/real/m.solution.json" --trace "$WORK/real/m.trace.json" -q ||
  fail "plan exited $?"
"$PY" "$TB" arc="$WORK/real" > "$WORK/out.md" 2> "$WORK/err" || fail "real trace: exited $?: $(cat "$WORK/err")"
measured=$("$PY" -c 'import json,sys; print("%.4f" % json.load(open(sys.argv[1]))["stats"]["planning_time_s"])' \
  "$WORK/real/m.solution.json")
has "| arc | as measured | $measured | 1.00 | 1.00 |"

# Bad input: one line naming the file, exit 2.
refused() {  # WHAT NAMED ARGS...
  local what=$1 named=$2
  shift 2
  "$PY" "$TB" "$@" > /dev/null 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "$what: not one line: $(cat "$WORK/err")"
  grep -qF -- "$named" "$WORK/err" || fail "$what: does not name $named: $(cat "$WORK/err")"
}
mkdir -p "$WORK/bad"
cp "$WORK/a/s1.solution.json" "$WORK/bad/"
echo '{"format": "earc.trace.v1", "events": [' > "$WORK/bad/s1.trace.json"
refused "malformed JSON" "$WORK/bad/s1.trace.json" x="$WORK/bad"
echo '{"format": "earc.trace.v1", "events": [{"type": "subproblem", "robots": [0, 1],
  "attempts": [{"solver": "decoupled", "ok": true, "time_s": NaN}]}]}' > "$WORK/bad/s1.trace.json"
refused "NaN time" "events[0].attempts[0].time_s" x="$WORK/bad"
echo '{"format": "other", "events": []}' > "$WORK/bad/s1.trace.json"
refused "foreign JSON" "$WORK/bad/s1.trace.json" x="$WORK/bad"
cp "$WORK/a/s1.trace.json" "$WORK/bad/s1.trace.json"
rm "$WORK/bad/s1.solution.json"
refused "no solution" "s1.solution.json" x="$WORK/bad"
refused "no NAME=" "$WORK/a" "$WORK/a"
refused "not a directory" "$WORK/none" x="$WORK/none"
mkdir -p "$WORK/c" && cp "$WORK/b/s2."* "$WORK/c/"
refused "nothing paired" "no scenario is in every run" one="$WORK/a" three="$WORK/c"
echo "ok"
