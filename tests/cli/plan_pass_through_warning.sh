#!/bin/bash
# A scenario whose resolution lets a robot step through an obstacle
# between two checked instants: earc-plan plan and validate say so in one
# warning line naming the file (validate --json in "warnings"), the plan
# is still made and valid under the contract; a scenario of the generated
# suites gets no warning.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needBuilt earc-plan
DATASETS=$(cd "$(dirname "$0")/../../datasets" && pwd)
cat > "$WORK/wall.json" <<'JSON'
{"format": "earc.scenario.v1", "name": "wall", "workspace": {"min": [0, 0], "max": [10, 10]},
 "resolution": {"translation": 1.0, "rotation": 0.05, "joint": 0.05},
 "obstacles": [{"type": "box", "center": [5, 5], "size": [0.05, 10]}],
 "robots": [{"name": "d0", "type": "mobile", "shape": {"type": "disc", "radius": 0.1},
             "start": [4.3, 5, 0], "goal": [5.7, 5, 0]}]}
JSON
"$BUILD/earc-plan" plan "$WORK/wall.json" -o "$WORK/wall.sol.json" --method arc -q 2> "$WORK/err" ||
  fail "plan exited $?: $(cat "$WORK/err")"
[ "$(grep -c 'warning' "$WORK/err")" -eq 1 ] || fail "plan: not one warning: $(cat "$WORK/err")"
grep -qF "earc-plan: warning: $WORK/wall.json: resolution: robot 'd0' can move 0.5" "$WORK/err" ||
  fail "plan's warning does not name the file, the field and the robot: $(cat "$WORK/err")"
"$BUILD/earc-plan" validate "$WORK/wall.json" "$WORK/wall.sol.json" > "$WORK/out" 2> "$WORK/err" ||
  fail "validate exited $?: $(cat "$WORK/out" "$WORK/err")"
grep -q '^VALID' "$WORK/out" || fail "validate: $(cat "$WORK/out")"
grep -qF "$WORK/wall.json: resolution: robot 'd0'" "$WORK/err" || fail "validate gave no warning: $(cat "$WORK/err")"
"$BUILD/earc-plan" validate --json "$WORK/wall.json" "$WORK/wall.sol.json" > "$WORK/out" 2> "$WORK/err" ||
  fail "validate --json exited $?"
grep -qF "\"warnings\":[\"$WORK/wall.json: resolution: robot" "$WORK/out" ||
  fail "validate --json has no warning naming the file: $(cat "$WORK/out")"
[ -s "$WORK/err" ] && fail "validate --json wrote to stderr: $(cat "$WORK/err")"

"$BUILD/earc-plan" plan "$DATASETS/mobile-4-s1.json" -o "$WORK/m.sol.json" --method arc -q 2> "$WORK/err" ||
  fail "plan of mobile-4-s1 exited $?: $(cat "$WORK/err")"
[ -s "$WORK/err" ] && fail "plan of mobile-4-s1 warned: $(cat "$WORK/err")"
"$BUILD/earc-plan" validate --json "$DATASETS/mobile-4-s1.json" "$WORK/m.sol.json" > "$WORK/out" ||
  fail "validate of mobile-4-s1"
grep -qF '"warnings":[]' "$WORK/out" || fail "validate --json of mobile-4-s1: $(cat "$WORK/out")"
echo "ok: a resolution that steps through an obstacle is warned of, once, naming the file"
