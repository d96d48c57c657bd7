#!/bin/bash
# label: slow
# 128 robots x 5000 steps: `earc-plan validate` finishes in seconds and
# agrees with the independent checker (verdict and violation count) on a
# valid solution and on one where a robot drifts into its neighbour.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
CHECKER="$SRC/../shared/tools/check_solution.py"
LIMIT_S=${EARC_VALIDATE_LARGE_LIMIT_S:-20}
"$PY" -c "import json" 2>/dev/null || { echo "skipped: no $PY to generate the case"; exit 77; }

"$PY" - "$WORK" <<'PY'
import json, math, sys
out = sys.argv[1]
N, T = 128, 5000
robots, paths = [], []
for i in range(N):
    x = 1.0 + 0.7 * i   # neighbours 0.7 apart: bounding discs close, bodies apart
    if i % 2 == 0:
        shape = {"type": "disc", "radius": 0.3}
    else:
        shape = {"type": "box", "size": [0.4, 0.4]}
    states = []
    for t in range(T + 1):
        s = t / T
        y = 1.0 + 24.0 * (s if i % 3 else 1.0 - s)
        states.append([x, y, (0.04 * t) % (2 * math.pi) - math.pi if i % 2 else 0.0])
    robots.append({"name": "r%d" % i, "type": "mobile", "shape": shape,
                   "start": states[0], "goal": states[-1]})
    paths.append({"robot": "r%d" % i, "states": states})
scen = {"format": "earc.scenario.v1", "name": "large",
        "workspace": {"min": [0, 0], "max": [92, 26]},
        "resolution": {"translation": 0.05, "rotation": 0.05},
        "obstacles": [{"type": "circle", "center": [91, 13], "radius": 0.5}], "robots": robots}
sol = {"format": "earc.solution.v1", "scenario": "large", "solved": True, "paths": paths}
json.dump(scen, open(out + "/scenario.json", "w"))
json.dump(sol, open(out + "/valid.json", "w"))
# r10 drifts 0.2 towards r11 for 100 steps in the middle.
for t in range(2400, 2500):
    paths[10]["states"][t][0] += 0.2 * min(t - 2399, 2500 - t) / 50.0
json.dump(sol, open(out + "/invalid.json", "w"))
PY
[ -s "$WORK/invalid.json" ] || fail "could not generate the case"

for case in valid invalid; do
  start=$(date +%s.%N)
  "$PLAN" validate "$WORK/scenario.json" "$WORK/$case.json" --json > "$WORK/$case.mine" 2> "$WORK/$case.err"
  rc=$?
  secs=$(echo "$(date +%s.%N) - $start" | bc)
  echo "earc-plan validate, $case: exit $rc in ${secs}s"
  want=0; [ $case = invalid ] && want=1
  [ $rc -eq $want ] || fail "$case: exit $rc, expected $want: $(head -c 300 "$WORK/$case.mine" "$WORK/$case.err")"
  (( $(echo "$secs < $LIMIT_S" | bc) )) || fail "$case took ${secs}s (limit ${LIMIT_S}s)"
done

if [ -f "$CHECKER" ] && "$PY" -c "import numpy" 2>/dev/null; then
  for case in valid invalid; do
    "$PY" "$CHECKER" "$WORK/scenario.json" "$WORK/$case.json" --json > "$WORK/$case.ref"
    rc=$?
    "$PY" - "$WORK/$case.mine" "$WORK/$case.ref" <<'PY' || fail "$case: the checker (exit $rc) disagrees"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
print("  %s: valid %s/%s, violations %s/%s" % (sys.argv[1].rsplit("/", 1)[1], a["valid"], b["valid"],
      a["violation_count"], b["violation_count"]))
assert a["valid"] == b["valid"] and a["violation_count"] == b["violation_count"]
PY
  done
else
  echo "note: independent checker not available; agreement not checked"
fi
echo "ok"
