#!/bin/bash
# earc-plan plan --refine: the prioritized plan of a dataset scenario (16
# robots among obstacles), refined for two seconds, is no costlier than the
# plan made without it (--deterministic: the same first plan), validates by
# earc-plan validate and by the independent checker when ../shared is
# there, and its stats say what refinement did. A value that is not a
# finite number >= 0 is refused in one line.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
failShowsOutput
needBuilt earc-plan
command -v jq > /dev/null || { echo "skipped: no jq"; exit 77; }
PLAN="$BUILD/earc-plan"
cd "$WORK" || exit 1
S="$SRC/datasets/mobile-obst-16-s1.json"

"$PLAN" plan "$S" -o plain.json --method prioritized -q > out 2> err || fail "plain plan (exit $?)"
"$PLAN" plan "$S" -o refined.json --method prioritized --refine 2 > out 2> err || fail "refined plan (exit $?)"
grep -q "sum of costs [0-9]* (first plan: [0-9]* and [0-9]*; refined for [0-9.]* s)" out ||
  fail "the summary does not say what --refine changed"
"$PLAN" validate "$S" refined.json > out 2> err || fail "the refined plan does not validate"
CHECKER="$SRC/../shared/tools/check_solution.py"
if [ -f "$CHECKER" ] && "$PY" -c "import numpy" 2> /dev/null; then
  "$PY" "$CHECKER" "$S" refined.json > out 2> err || fail "check_solution.py rejects the refined plan"
fi

st() { jq -c "$1" refined.json; }
[ "$(st '.stats.refine | has("rejected")')" = false ] || fail "the refined plan was rejected: $(st .stats.refine)"
[ "$(st .stats.refine.first_sum_of_costs)" = "$(jq .stats.sum_of_costs plain.json)" ] ||
  fail "refinement did not start from the plan made without it"
[ "$(st .stats.refine.final_sum_of_costs)" = "$(st .stats.sum_of_costs)" ] || fail "final_sum_of_costs is not the plan's"
[ "$(st .stats.refine.final_makespan)" = "$(st .stats.makespan)" ] || fail "final_makespan is not the plan's"
[ "$(st '.stats.sum_of_costs < .stats.refine.first_sum_of_costs')" = true ] ||
  fail "two seconds of refinement saved nothing: $(st .stats.refine)"
[ "$(st '.stats.makespan <= .stats.refine.first_makespan')" = true ] || fail "the makespan grew"
[ "$(st '.stats.refine.first_s == .stats.planning_time_s')" = true ] || fail "first_s is not the planning time"
[ "$(st '.stats.refine.final_s >= .stats.refine.first_s')" = true ] || fail "final_s before first_s"
[ "$(st '.stats.refine.seconds_spent < 4')" = true ] || fail "refined for $(st .stats.refine.seconds_spent) s of 2"
[ "$(st '.stats.refine.history | length >= 2')" = true ] || fail "no improvement in the history"
[ "$(st '.stats.refine.history[-1][1] == .stats.sum_of_costs')" = true ] || fail "the history does not end at the plan"
[ "$(st '.stats.refine | (.shortcut_improvements + .lns_improvements + (if .retimed_steps > 0 then 1 else 0 end)) == (.history | length) - 1')" = true ] ||
  fail "improvements counted do not match the history"
[ "$(jq '.stats | has("refine")' plain.json)" = false ] || fail "stats refine without --refine"

for bad in -1 nan inf x; do
  refusedInOneLine "--refine" "$PLAN" plan "$S" -o bad.json --refine "$bad"
done
[ ! -e bad.json ] || fail "a refused --refine wrote a solution"
echo "ok: --refine 2 took the sum of costs from $(st .stats.refine.first_sum_of_costs) to $(st .stats.sum_of_costs)"
