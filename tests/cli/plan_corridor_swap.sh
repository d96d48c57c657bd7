#!/bin/bash
# Four box robots swap ends through corridors one map cell wide
# (tests/data/scenarios/corridor-swap-4.json, from a MovingAI-style maze).
# Once a conflict's subproblem is the whole problem, ARC's retries must get
# further each time: with the decoupled solver's priority orders and
# expansion cap fixed, every retry repeated the same failed searches and
# ARC and E-ARC failed for the whole time limit, where whole-problem
# prioritized planning solves it in under a second.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-plan
fail() { echo "FAIL: $*"; tail -n 5 "$WORK/out" 2>/dev/null; exit 1; }
SCEN="$SRC/tests/data/scenarios/corridor-swap-4.json"
cd "$WORK" || exit 1

for method in arc earc; do
  db=()
  [ $method = earc ] && db=(--db e.db)
  "$BUILD/earc-plan" plan "$SCEN" -o $method.json --method $method "${db[@]}" --seed 1 --time-limit 120 > out 2>&1 ||
    fail "$method did not solve the corridor swap (exit $?)"
  "$BUILD/earc-plan" validate "$SCEN" $method.json > out 2>&1 || fail "$method's solution does not validate"
done
echo "ok: ARC and E-ARC solve the 4-robot corridor swap"
