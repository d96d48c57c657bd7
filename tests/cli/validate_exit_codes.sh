#!/bin/bash
# `earc-plan validate`: exit 0 and one VALID line for a valid solution,
# exit 1 with INVALID and the first violations for an invalid one, exit 2
# for bad input; --json prints one object either way.
set -u
PLAN="$1/earc-plan"
DATA="$2/tests/data"
fail() { echo "FAIL: $*"; exit 1; }
OUT=$(mktemp)
trap 'rm -f "$OUT"' EXIT

"$PLAN" validate "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" > "$OUT" 2>&1
rc=$?
[ $rc -eq 0 ] || fail "valid solution: exit $rc"
[ "$(wc -l < "$OUT")" -eq 1 ] || fail "valid solution: expected one line, got: $(cat "$OUT")"
grep -qx "VALID: robots 2, makespan 3, sum_of_costs 4, total_distance 4" "$OUT" || fail "valid line: $(cat "$OUT")"

"$PLAN" validate "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__midpoint-swap.json" > "$OUT" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "midpoint swap: exit $rc"
head -1 "$OUT" | grep -q "^INVALID: 1 violation(s)" || fail "invalid header: $(cat "$OUT")"
grep -q "t=0.5 *robot-robot *m0 overlaps m1 by 0.6" "$OUT" || fail "violation line: $(cat "$OUT")"

"$PLAN" validate "$DATA/scenarios/arm-fold.json" "$DATA/solutions/arm-fold__self-collision.json" > "$OUT" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "self-collision: exit $rc"
grep -q "^  \.\.\. 15 more$" "$OUT" || fail "25 violations, 10 listed: $(cat "$OUT")"

"$PLAN" validate "$DATA/scenarios/open-disc.json" "$DATA/solutions/open-disc__wrong-goal.json" --json > "$OUT" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "--json invalid: exit $rc"
/usr/bin/python3 - "$OUT" <<'PY' || fail "--json output: $(cat "$OUT")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["valid"] is False and r["violation_count"] == 1, r
v = r["violations"][0]
assert v["type"] == "goal" and v["t"] == 11 and v["robots"] == ["d0"], v
assert r["makespan"] == 11 and r["robots"] == 1, r
PY

"$PLAN" validate "$DATA/bad/malformed.json" "$DATA/solutions/swap-discs__valid.json" > "$OUT" 2>&1
rc=$?
[ $rc -eq 2 ] || fail "malformed scenario: exit $rc"

"$PLAN" validate "$DATA/scenarios/swap-discs.json" "$DATA/no-such-file.json" > "$OUT" 2>&1
rc=$?
[ $rc -eq 2 ] || fail "missing solution file: exit $rc"
grep -q "no-such-file.json: cannot open file" "$OUT" || fail "missing file message: $(cat "$OUT")"

"$PLAN" validate "$DATA/scenarios/swap-discs.json" > "$OUT" 2>&1
rc=$?
[ $rc -ne 0 ] || fail "missing argument accepted"
echo "ok"
