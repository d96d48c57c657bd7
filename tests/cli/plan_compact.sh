#!/bin/bash
# earc-plan plan --compact: a crowded ARC plan (10 discs of radius 0.5
# among obstacles in a 10 x 10 square, many waits) comes out with a smaller
# sum of costs, the same routes (the same distance travelled), valid by
# earc-plan validate and by the independent checker when ../shared is
# there; the plan before compaction is the one planned without the option
# (--deterministic).
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
failShowsOutput
needBuilt earc-plan
needBuilt earc-scenario
command -v jq > /dev/null || { echo "skipped: no jq"; exit 77; }
PLAN="$BUILD/earc-plan"
cd "$WORK" || exit 1

"$BUILD/earc-scenario" generate -n 10 --obstacles --shape disc --radius 0.5 --workspace 10 --seed 2 -o s.json \
  > out 2> err || fail "generate"
"$PLAN" plan s.json -o plain.json --method arc --deterministic -q > out 2> err || fail "plain plan (exit $?)"
"$PLAN" plan s.json -o compact.json --method arc --deterministic --compact > out 2> err ||
  fail "compacted plan (exit $?)"
grep -q "sum of costs [0-9]* (before --compact: [0-9]* and [0-9]*)" out || fail "the summary does not say what --compact changed"
"$PLAN" validate s.json compact.json > out 2> err || fail "the compacted plan does not validate"
CHECKER="$SRC/../shared/tools/check_solution.py"
if [ -f "$CHECKER" ] && "$PY" -c "import numpy" 2> /dev/null; then
  "$PY" "$CHECKER" s.json compact.json > out 2> err || fail "check_solution.py rejects the compacted plan"
fi

before=$(jq '.stats.sum_of_costs' plain.json)
after=$(jq '.stats.sum_of_costs' compact.json)
[ "$(jq '.stats.compact.sum_of_costs_before' compact.json)" = "$before" ] ||
  fail "compaction did not start from the plan made without it"
[ "$after" -lt "$before" ] || fail "sum of costs $after, not below $before"
[ "$(jq '.stats.makespan <= .stats.compact.makespan_before' compact.json)" = true ] || fail "makespan grew"
[ "$(jq 'has("compact")' <(jq .stats plain.json))" = false ] || fail "stats compact without --compact"
# The same routes, gone along faster or with fewer waits: the same
# distance travelled.
dist() { "$PLAN" validate s.json "$1" --json | jq .total_distance; }
[ "$(jq -n "($(dist plain.json) - $(dist compact.json)) | fabs < 1e-6")" = true ] || fail "a route changed"
echo "ok: --compact took the sum of costs from $before to $after, the routes the same"
