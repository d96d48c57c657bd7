#!/bin/bash
# label: slow
# `earc-plan validate` and shared/tools/check_solution.py agree, violation by
# violation (type, instant, robots, in order), on random scenarios mixing
# discs, boxes and arms among box and circle obstacles, with random-walk
# paths that break every rule now and then (steps, limits, headings that
# jump by 2 pi). Robots whose start or goal is invalid are dropped so most
# cases get past the scenario check. EARC_RANDOM_CASES sets the number of
# cases (default 60). Skipped (77) without the checker or numpy.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
TOOLS="$SRC/../shared/tools"
PLAN="$BUILD/earc-plan"
CASES=${EARC_RANDOM_CASES:-60}
[ -f "$TOOLS/check_solution.py" ] || { echo "skipped: no checker at $TOOLS (../shared is missing)"; exit 77; }
"$PY" -c "import numpy" 2>/dev/null || { echo "skipped: $PY has no numpy"; exit 77; }
[ -x "$PLAN" ] || { echo "FAIL: $PLAN not built"; exit 1; }

cat > "$WORK/gen.py" <<'PY'
import json, math, random, sys
tools, out, seed = sys.argv[1], sys.argv[2], int(sys.argv[3])
sys.path.insert(0, tools)
import check_solution as cs

rng = random.Random(seed)
W = 12.0
obstacles = []
for i in range(rng.randint(0, 6)):
    c = [rng.uniform(0, W), rng.uniform(0, W)]
    if rng.random() < 0.5:
        obstacles.append({"type": "box", "center": c, "size": [rng.uniform(0.2, 2), rng.uniform(0.2, 2)],
                          "angle": rng.uniform(-4, 4)})
    else:
        obstacles.append({"type": "circle", "center": c, "radius": rng.uniform(0.1, 1)})
robots, paths = [], []
T = rng.randint(1, 40)
for i in range(rng.randint(2, 8)):
    kind = rng.choice(["disc", "box", "arm"])
    if kind == "arm":
        n = rng.randint(1, 5)
        q = [rng.uniform(-1, 1) for _ in range(n)]
        r = {"name": "a%d" % i, "type": "manipulator",
             "base": [rng.uniform(2, W - 2), rng.uniform(2, W - 2), rng.uniform(-3, 3)],
             "links": [rng.uniform(0.3, 1.2) for _ in range(n)], "link_radius": rng.choice([0, 0.05, 0.1]),
             "joint_limits": [[-rng.uniform(1, 3.2), rng.uniform(1, 3.2)] for _ in range(n)]}
        step = lambda q: [x + rng.uniform(-0.15, 0.15) for x in q]
    else:
        shape = ({"type": "disc", "radius": rng.uniform(0.1, 0.6)} if kind == "disc"
                 else {"type": "box", "size": [rng.uniform(0.2, 1.5), rng.uniform(0.2, 1)]})
        q = [rng.uniform(0.5, W - 0.5), rng.uniform(0.5, W - 0.5), rng.uniform(-3.14, 3.14)]
        r = {"name": "m%d" % i, "type": "mobile", "shape": shape}
        def step(q):
            h = q[2] + rng.uniform(-0.4, 0.4) + (rng.choice([-1, 1]) * 2 * math.pi if rng.random() < 0.1 else 0)
            return [q[0] + rng.uniform(-0.3, 0.3), q[1] + rng.uniform(-0.3, 0.3), h]
    states = [q]
    for t in range(rng.randint(0, T)):
        states.append(step(states[-1]))
    r["start"], r["goal"] = states[0], states[-1]
    robots.append(r)
    paths.append({"robot": r["name"], "states": states})

scen = {"format": "earc.scenario.v1", "name": "random-%d" % seed,
        "workspace": {"min": [0, 0], "max": [W, W]},
        "resolution": {"translation": 0.3, "rotation": 0.35, "joint": 0.14},
        "obstacles": obstacles, "robots": robots}
# Drop robots the scenario check names until it passes (or none are left).
while robots:
    try:
        cs.validate_scenario(cs.parse_scenario(scen))
        break
    except cs.InvalidScenario as e:
        bad = set(e.violations[0]["robots"][-1:])
        robots[:] = [r for r in robots if r["name"] not in bad]
        paths[:] = [p for p in paths if p["robot"] not in bad]
sol = {"format": "earc.solution.v1", "scenario": scen["name"], "solved": True, "paths": paths}
json.dump(scen, open(out + "/scenario.json", "w"))
json.dump(sol, open(out + "/solution.json", "w"))
PY

cat > "$WORK/compare.py" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
if a.get("malformed") or b.get("malformed"):
    sys.exit(0 if bool(a.get("malformed")) == bool(b.get("malformed")) else 1)
key = lambda v: (v["type"], v["t"], tuple(v["robots"]))
ka = [key(v) for v in a["violations"]]
kb = [key(v) for v in b["violations"]][:len(ka)]
same = (a["valid"] == b["valid"] and a["violation_count"] == b["violation_count"] and ka == kb
        and a["makespan"] == b["makespan"] and a["sum_of_costs"] == b["sum_of_costs"]
        and abs(a["total_distance"] - b["total_distance"]) <= 1e-9 * max(1.0, b["total_distance"]))
if not same:
    print("  violations %s vs %s" % (a["violation_count"], b["violation_count"]))
    for x, y in zip(ka, kb):
        if x != y:
            print("  first difference: %s vs %s" % (x, y))
            break
sys.exit(0 if same else 1)
PY

failures=0
checked=0
for seed in $(seq 1 "$CASES"); do
  "$PY" "$WORK/gen.py" "$TOOLS" "$WORK" "$seed" || { echo "FAIL: generator, seed $seed"; exit 1; }
  "$PLAN" validate "$WORK/scenario.json" "$WORK/solution.json" --json > "$WORK/mine.json" 2>/dev/null
  mine=$?
  "$PY" "$TOOLS/check_solution.py" "$WORK/scenario.json" "$WORK/solution.json" --json > "$WORK/ref.json"
  ref=$?
  [ $mine -ne 2 ] && checked=$((checked + 1))
  if [ $mine -ne $ref ] || ! "$PY" "$WORK/compare.py" "$WORK/mine.json" "$WORK/ref.json"; then
    failures=$((failures + 1))
    echo "DISAGREE on seed $seed: exit $mine (earc-plan) vs $ref (checker)"
    cp "$WORK/scenario.json" "$BUILD/random-disagreement-$seed.scenario.json"
    cp "$WORK/solution.json" "$BUILD/random-disagreement-$seed.solution.json"
  fi
done
echo "$CASES random cases ($checked past the scenario check), $failures disagreement(s)"
[ $failures -eq 0 ]
