#!/bin/bash
# earc-db build: the same seed gives the same rows with 1 or 2 threads, for
# mobile robots (2-4 per problem) and for arm pairs of every class of the
# default layout; the result verifies and inspect lists its classes; the
# kind comes from --scenario when --kind is not given.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
DB="$BUILD/earc-db"
needPython
needBuilt earc-db
# Rows without what legitimately differs between runs (clock readings).
rows() {
  "$PY" - "$1" <<'PY'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
for l in lines[1:]:
    r = json.loads(l)
    for k in ("created_at", "solve_time_s"):
        r.pop(k)
    print(json.dumps(r, sort_keys=True))
PY
}

for kind in mobile arms; do
  "$DB" build --db "$WORK/$kind-1.db" --kind $kind --count 40 --seed 7 --threads 1 > "$WORK/$kind-1.out" 2>&1 \
    || fail "$kind build with 1 thread exited $?: $(cat "$WORK/$kind-1.out")"
  "$DB" build --db "$WORK/$kind-2.db" --kind $kind --count 40 --seed 7 --threads 2 > "$WORK/$kind-2.out" 2>&1 \
    || fail "$kind build with 2 threads exited $?"
  grep -q "built .*: [1-9][0-9]* entries from 40 problems" "$WORK/$kind-2.out" || fail "no build summary: $(cat "$WORK/$kind-2.out")"
  for t in 1 2; do "$DB" export --db "$WORK/$kind-$t.db" -o "$WORK/$kind-$t.jsonl" > /dev/null || fail "export"; done
  rows "$WORK/$kind-1.jsonl" > "$WORK/$kind-1.rows"
  rows "$WORK/$kind-2.jsonl" > "$WORK/$kind-2.rows"
  [ -s "$WORK/$kind-1.rows" ] || fail "$kind build stored nothing"
  cmp -s "$WORK/$kind-1.rows" "$WORK/$kind-2.rows" || fail "$kind rows differ between 1 and 2 threads"
  # -q: the same rows, and nothing printed.
  "$DB" build --db "$WORK/$kind-q.db" --kind $kind --count 40 --seed 7 -q > "$WORK/$kind-q.out" 2>&1 \
    || fail "$kind build -q exited $?: $(cat "$WORK/$kind-q.out")"
  [ -s "$WORK/$kind-q.out" ] && fail "$kind build -q printed: $(cat "$WORK/$kind-q.out")"
  "$DB" export --db "$WORK/$kind-q.db" -o "$WORK/$kind-q.jsonl" > /dev/null || fail "export"
  rows "$WORK/$kind-q.jsonl" > "$WORK/$kind-q.rows"
  cmp -s "$WORK/$kind-1.rows" "$WORK/$kind-q.rows" || fail "$kind rows differ with -q"
  "$DB" verify --db "$WORK/$kind-2.db" > "$WORK/verify.out" || fail "$kind database does not verify: $(cat "$WORK/verify.out")"
done

# Every robot count of the mobile mix and both arm classes of the default layout.
"$DB" inspect --db "$WORK/mobile-2.db" > "$WORK/inspect.out" || fail "inspect exited $?"
for n in 2 3 4; do grep -Eq "^mobile +$n " "$WORK/inspect.out" || fail "no mobile x$n class: $(cat "$WORK/inspect.out")"; done
"$DB" inspect --db "$WORK/arms-2.db" > "$WORK/inspect.out" || fail "inspect exited $?"
grep -q "dx=4.000,dy=0.000,dth=3.142" "$WORK/inspect.out" || fail "no facing-pair class: $(cat "$WORK/inspect.out")"
grep -q "dx=0.000,dy=-3.000,dth=0.000" "$WORK/inspect.out" || fail "no neighbour class: $(cat "$WORK/inspect.out")"

# Without --kind, a --scenario's robots say which kind to build for; a
# scenario with both kinds needs --kind (one line, exit 2, no file made).
needBuilt earc-scenario
"$BUILD/earc-scenario" generate --family arms -n 4 --seed 2 -o "$WORK/a4.json" > /dev/null || fail "generate arms"
"$DB" build --db "$WORK/from-arms.db" --scenario "$WORK/a4.json" --count 10 --threads 1 -q || fail "build from arms: exit $?"
"$DB" inspect --db "$WORK/from-arms.db" > "$WORK/inspect.out" || fail "inspect exited $?"
grep -Eq "^manipulator +2 " "$WORK/inspect.out" || fail "an arm scenario did not give an arm database: $(cat "$WORK/inspect.out")"
grep -q "^mobile" "$WORK/inspect.out" && fail "an arm scenario gave mobile rows: $(cat "$WORK/inspect.out")"
"$PY" - "$SRC/tests/data/scenarios/swap-discs.json" "$SRC/tests/data/scenarios/arm-fold.json" "$WORK/mixed.json" <<'PY'
import json, sys
mixed = json.load(open(sys.argv[1]))
arm = json.load(open(sys.argv[2]))["robots"][0]
arm.update(base=[8, 2, 0], start=[1.57, 0, 0, 0], goal=[1.57, 0.5, 0.5, 0])
mixed["robots"].append(arm)
mixed["resolution"]["joint"] = 0.1
json.dump(mixed, open(sys.argv[3], "w"))
PY
"$DB" build --db "$WORK/mixed.db" --scenario "$WORK/mixed.json" --count 5 > "$WORK/out" 2> "$WORK/err"
rc=$?
[ $rc -eq 2 ] || fail "a scenario with both kinds: exit $rc, not 2"
[ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$WORK/mixed.json: \$.robots: holds mobile robots and arms: say which with --kind" \
  "$WORK/err" || fail "a scenario with both kinds: $(cat "$WORK/err")"
[ -e "$WORK/mixed.db" ] && fail "a refused build made a file"
"$DB" build --db "$WORK/mixed.db" --scenario "$WORK/mixed.json" --kind mobile --count 5 --threads 1 -q ||
  fail "--kind mobile with a mixed scenario: exit $?"
# The database holds pairs of arms with equal joint counts only (a key
# and a path blob of one dimension for both): a layout without two such
# arms that reach each other is refused in one line that names the file
# and each arm's joint count (exit 2, no file made); one with such a pair
# and other arms is built for that pair's class.
armLayout() {  # armLayout OUT NAME:X:Y:JOINTS...
  "$PY" - "$@" <<'PY'
import json, sys
robots = []
for spec in sys.argv[2:]:
    name, x, y, n = spec.split(":")
    n = int(n)
    robots.append({"name": name, "type": "manipulator", "base": [float(x), float(y), 0], "links": [0.5] * n,
                   "link_radius": 0.05, "start": [0] * n, "goal": [0.5] * n})
json.dump({"format": "earc.scenario.v1", "name": "layout", "workspace": {"min": [0, 0], "max": [10, 10]},
           "obstacles": [], "robots": robots}, open(sys.argv[1], "w"))
PY
}
armLayout "$WORK/unequal.json" a:4:4:3 b:6:4:4 c:5:5.8:2
refusedInOneLine "unequal.json: \$.robots: no two arms have the same number of joints ('a': 3 joints, 'b': 4, 'c': 2)" \
  "$DB" build --db "$WORK/unequal.db" --scenario "$WORK/unequal.json" --count 5
[ -e "$WORK/unequal.db" ] && fail "a refused build made a file"
armLayout "$WORK/apart.json" a:1:5:3 b:8:5:3 c:5:2:2
refusedInOneLine "apart.json: \$.robots: no two arms with the same number of joints can reach each other ('a': 3 joints" \
  "$DB" build --db "$WORK/apart.db" --scenario "$WORK/apart.json" --count 5
[ -e "$WORK/apart.db" ] && fail "a refused build made a file"
armLayout "$WORK/one-pair.json" a:4:4:3 b:6:4:3 c:5:5.8:2
"$DB" build --db "$WORK/one-pair.db" --scenario "$WORK/one-pair.json" --count 5 --threads 1 -q ||
  fail "a layout with one pair of equal arms: exit $?"
"$DB" inspect --db "$WORK/one-pair.db" > "$WORK/inspect.out" || fail "inspect exited $?"
[ "$(grep -Ec "^manipulator +2 " "$WORK/inspect.out")" -eq 1 ] ||
  fail "a layout with one pair of equal arms did not give its one class: $(cat "$WORK/inspect.out")"
# The pairs of unequal joint counts left out of that build (a-c and b-c
# reach each other) are counted in the summary, naming the first; -q
# prints nothing; a layout of equal arms has no such line.
"$DB" build --db "$WORK/one-pair-2.db" --scenario "$WORK/one-pair.json" --count 5 --threads 1 \
  > "$WORK/build.out" 2> /dev/null || fail "a layout with one pair of equal arms: exit $?"
grep -qxF "left out 2 arm pairs within reach whose joint counts differ (e.g. 'a': 3 joints, 'c': 2); an arm database holds pairs of arms with equal joint counts only" \
  "$WORK/build.out" || fail "the summary does not count the pairs left out: $(cat "$WORK/build.out")"
"$DB" build --db "$WORK/from-arms-2.db" --scenario "$WORK/a4.json" --count 5 --threads 1 \
  > "$WORK/build.out" 2> /dev/null || fail "build from arms: exit $?"
grep -q "left out" "$WORK/build.out" && fail "equal arms: the summary speaks of pairs left out: $(cat "$WORK/build.out")"
"$DB" build --db "$WORK/one-pair-q.db" --scenario "$WORK/one-pair.json" --count 5 --threads 1 -q \
  > "$WORK/build.out" 2>&1 || fail "a layout with one pair of equal arms, -q: exit $?"
[ -s "$WORK/build.out" ] && fail "build -q printed: $(cat "$WORK/build.out")"
# A footprint option says mobile, whatever the scenario holds; with
# --kind arms it would be ignored, so it is refused.
"$DB" build --db "$WORK/discs.db" --scenario "$WORK/a4.json" --shape disc --radius 0.3 --count 5 --threads 1 -q ||
  fail "--shape with an arm scenario: exit $?"
"$DB" inspect --db "$WORK/discs.db" > "$WORK/inspect.out" || fail "inspect exited $?"
grep -Eq "^mobile +2 .*mobile:disc:r=0.3" "$WORK/inspect.out" || fail "--shape disc did not build discs: $(cat "$WORK/inspect.out")"
# A footprint option beside a scenario of mobile robots builds for that
# footprint: said in a warning when none of the scenario's robots has it
# (the database would answer none of them), not when they do.
"$DB" build --db "$WORK/other-boxes.db" --scenario "$SRC/tests/data/scenarios/swap-discs.json" --size 0.7x0.5 \
  --count 5 --threads 1 -q > "$WORK/out" 2> "$WORK/err" || fail "--size beside a disc scenario: exit $?"
grep -qF "warning: $SRC/tests/data/scenarios/swap-discs.json: none of its mobile robots has the footprint given (mobile:box:0.7x0.5)" \
  "$WORK/err" || fail "--size beside a disc scenario, no warning: $(cat "$WORK/err")"
"$DB" build --db "$WORK/same-discs.db" --scenario "$SRC/tests/data/scenarios/swap-discs.json" --shape disc --radius 0.3 \
  --count 5 --threads 1 -q > "$WORK/out" 2> "$WORK/err" || fail "--shape disc beside a disc scenario: exit $?"
[ -s "$WORK/err" ] && fail "the scenario's own footprint given again warned: $(cat "$WORK/err")"
# A footprint too large for any query: an error, not "built 0 entries".
"$DB" build --db "$WORK/huge.db" --shape disc --radius 1e300 --count 5 > "$WORK/out" 2> "$WORK/err"
[ $? -eq 2 ] && grep -qF -- "--radius: none of 5 problems could be made" "$WORK/err" ||
  fail "--radius 1e300: $(cat "$WORK/out" "$WORK/err")"
[ -e "$WORK/huge.db" ] && fail "a build that made nothing left its new file"
# --size alone sizes the default box.
"$DB" build --db "$WORK/boxes.db" --size 0.8x0.4 --count 5 --threads 1 -q || fail "--size without --shape: exit $?"
"$DB" inspect --db "$WORK/boxes.db" > "$WORK/inspect.out" || fail "inspect exited $?"
grep -Eq "^mobile +2 .*mobile:box:0.8x0.4" "$WORK/inspect.out" || fail "--size did not build 0.8x0.4 boxes: $(cat "$WORK/inspect.out")"
"$DB" build --db "$WORK/refused.db" --kind arms --shape disc --count 5 > "$WORK/out" 2> "$WORK/err"
[ $? -eq 2 ] && grep -qF -- "--shape: is for mobile robots, not --kind arms" "$WORK/err" ||
  fail "--kind arms --shape disc: $(cat "$WORK/err")"
[ -e "$WORK/refused.db" ] && fail "a refused build made a file"

# A different seed gives different rows.
"$DB" build --db "$WORK/other.db" --count 40 --seed 8 > /dev/null 2>&1 || fail "build --seed 8"
"$DB" export --db "$WORK/other.db" -o "$WORK/other.jsonl" > /dev/null || fail "export"
rows "$WORK/other.jsonl" > "$WORK/other.rows"
cmp -s "$WORK/mobile-1.rows" "$WORK/other.rows" && fail "seeds 7 and 8 gave the same rows"
echo "ok"
