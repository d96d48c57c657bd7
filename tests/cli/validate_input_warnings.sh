#!/bin/bash
# Unknown keys are read past (the contract) but warned of, one line each
# on stderr naming the file and the JSON path, with a near miss suggested:
# by earc-plan plan (with -q too, as the pass-through warning), validate
# (--json: in "warnings", nothing on stderr), render and view, by
# earc-db build --scenario (with -q too) and by earc-bench. An angle
# beyond a full turn is warned of as likely degrees, an obstacle outside
# the workspace as unreachable. Refused input gets its one error line and
# no warnings (a misspelt required key named, an empty robot name
# refused); the project's own files get none.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
failShowsOutput
needBuilt earc-plan earc-db
PLAN="$BUILD/earc-plan"
cd "$WORK" || exit 1
cat > s.json <<'JSON'
{"format": "earc.scenario.v1", "name": "typos", "workspace": {"min": [0, 0], "max": [10, 10]},
 "resolution": {"translaton": 0.5, "rotation": 0.5},
 "obstacles": [{"type": "box", "center": [5, 5], "size": [1, 1], "angel": 0.3}],
 "robots": [{"name": "d0", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},
             "start": [1, 1, 0], "goal": [9, 1, 0]},
            {"name": "d1", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},
             "start": [1, 9, 0], "goal": [9, 9, 0], "base": [0, 0, 0]}]}
JSON
cat > want <<'EOF'
earc-plan: warning: s.json: $.resolution.translaton: unknown key, ignored (did you mean "translation"?)
earc-plan: warning: s.json: $.obstacles[0].angel: unknown key, ignored (did you mean "angle"?)
earc-plan: warning: s.json: $.robots[1].base: a manipulator's key, ignored on a mobile robot
EOF

"$PLAN" plan s.json -o sol.json --method arc -q > out 2> err || fail "plan exited $?"
diff want err > /dev/null || fail "plan -q: not the warnings wanted: $(diff want err)"
[ -s out ] && fail "plan -q wrote on stdout"

# A solution's unknown key is its own warning, after the scenario's.
"$PY" -c 'import json; d = json.load(open("sol.json")); d["comment"] = "by hand"; json.dump(d, open("sol2.json", "w"))'
"$PLAN" validate s.json sol2.json > out 2> err || fail "validate exited $?"
grep -q '^VALID' out || fail "validate: not VALID"
{ cat want; echo 'earc-plan: warning: sol2.json: $.comment: unknown key, ignored'; } > want2
diff want2 err > /dev/null || fail "validate: not the warnings wanted: $(diff want2 err)"

"$PLAN" validate --json s.json sol2.json > out 2> err || fail "validate --json exited $?"
[ -s err ] && fail "validate --json wrote on stderr"
"$PY" - out <<'EOF' || fail "validate --json's warnings"
import json, sys
w = json.load(open(sys.argv[1]))["warnings"]
assert w == ['s.json: $.resolution.translaton: unknown key, ignored (did you mean "translation"?)',
             's.json: $.obstacles[0].angel: unknown key, ignored (did you mean "angle"?)',
             "s.json: $.robots[1].base: a manipulator's key, ignored on a mobile robot",
             "sol2.json: $.comment: unknown key, ignored"], w
EOF

"$PLAN" render s.json -o s.svg > out 2> err || fail "render exited $?"
diff want err > /dev/null || fail "render: not the warnings wanted: $(diff want err)"
"$PLAN" view s.json sol2.json -o s.html > out 2> err || fail "view exited $?"
diff want2 err > /dev/null || fail "view: not the warnings wanted: $(diff want2 err)"

"$BUILD/earc-db" build --db e.db --scenario s.json --count 1 --seed 1 -q > out 2> err || fail "earc-db build exited $?"
sed 's/^earc-plan:/earc-db:/' want > want-db
diff want-db err > /dev/null || fail "earc-db build -q: not the warnings wanted: $(diff want-db err)"

if [ -x "$BUILD/earc-bench" ]; then
  "$BUILD/earc-bench" lightning-db --scenario s.json --count 1 --problem-time-limit 1 -o l.db > out 2> err ||
    fail "earc-bench lightning-db exited $?"
  sed 's/^earc-plan:/earc-bench:/' want > want-bench
  diff want-bench err > /dev/null || fail "earc-bench: not the warnings wanted: $(diff want-bench err)"
fi

# Degrees where radians are meant: read, with a warning.
"$PY" -c 'import json; d = json.load(open("s.json")); d["robots"][0]["goal"][2] = 90; json.dump(d, open("deg.json", "w"))'
"$PLAN" render deg.json -o deg.svg > out 2> err || fail "render deg.json exited $?"
grep -qxF 'earc-plan: warning: deg.json: $.robots[0].goal[2]: heading 90 is more than a full turn: angles are in radians, and this looks like degrees (90 degrees is 1.5708 rad)' err ||
  fail "render: no warning of degrees: $(cat err)"

# An obstacle that no robot can reach, outside the workspace.
"$PY" -c 'import json; d = json.load(open("s.json")); d["obstacles"][0]["center"] = [50, 50]; json.dump(d, open("far.json", "w"))'
"$PLAN" render far.json -o far.svg > out 2> err || fail "render far.json exited $?"
grep -qF 'earc-plan: warning: far.json: $.obstacles[0]: obstacle entirely outside the workspace [0, 10] x [0, 10]' err ||
  fail "render: no warning of the obstacle outside: $(cat err)"

# Refused: one line, no warnings, and the misspelt key named.
"$PY" -c 'import json; d = json.load(open("s.json")); r = d["robots"][0]; r["gaol"] = r.pop("goal"); json.dump(d, open("gaol.json", "w"))'
refusedInOneLine 'gaol.json: $.robots[0].goal: missing required field "goal" (found "gaol")' "$PLAN" plan gaol.json -o x.json
"$PY" -c 'import json; d = json.load(open("s.json")); d["robots"][0]["name"] = ""; json.dump(d, open("noname.json", "w"))'
refusedInOneLine 'noname.json: $.robots[0].name: empty robot name' "$PLAN" plan noname.json -o x.json

# The project's own files: no warnings.
for f in "$SRC"/datasets/*.json; do
  "$PLAN" render "$f" -o d.svg > out 2> err || fail "render $f exited $?"
  [ -s err ] && fail "$(basename "$f") warned: $(cat err)"
done
for sol in "$SRC"/tests/data/solutions/*.json; do
  name=$(basename "$sol" .json)
  "$PLAN" validate "$SRC/tests/data/scenarios/${name%%__*}.json" "$sol" > out 2> err
  [ -s err ] && fail "$name warned: $(cat err)"
done
echo "ok: unknown keys are warned of, one line each, by every reader"
