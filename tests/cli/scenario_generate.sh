#!/bin/bash
# earc-scenario generate: the same options give the same file, another seed
# another file; every family writes a scenario that loads; bad options fail.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
GEN="$BUILD/earc-scenario"
PLAN="$BUILD/earc-plan"
needBuilt earc-scenario
needPython
# field FILE EXPR: a Python expression over the scenario document d.
field() { "$PY" -c 'import json, sys; d = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"; }

"$GEN" generate --family mobile --robots 8 --obstacles --seed 3 -o "$WORK/a.json" > /dev/null || fail "mobile generate exited $?"
"$GEN" generate --family mobile --robots 8 --obstacles --seed 3 -o "$WORK/b.json" > /dev/null || fail "second run exited $?"
"$GEN" generate --family mobile --robots 8 --obstacles --seed 4 -o "$WORK/c.json" > /dev/null || fail "seed 4 exited $?"
cmp -s "$WORK/a.json" "$WORK/b.json" || fail "same seed, different files"
cmp -s "$WORK/a.json" "$WORK/c.json" && fail "different seeds, same file"
[ "$(field "$WORK/a.json" 'd["name"]')" = mobile-obst-8-s3 ] || fail "name does not encode family, obstacles, N and seed"
[ "$(field "$WORK/a.json" 'len(d["obstacles"])')" = 12 ] || fail "--obstacles alone did not give 12 boxes"
[ "$(field "$WORK/a.json" 'len(d["robots"])')" = 8 ] || fail "not 8 robots"

"$GEN" generate --family mobile --robots 4 -o "$WORK/open.json" > /dev/null || fail "no obstacles exited $?"
[ "$(field "$WORK/open.json" 'd["name"]')" = mobile-4-s1 ] || fail "default seed or name wrong"
[ "$(field "$WORK/open.json" 'len(d["obstacles"])')" = 0 ] || fail "obstacles without --obstacles"
"$GEN" generate --family mobile --robots 4 --shape disc --radius 0.25 --workspace 12 --obstacles 3 --rotated \
  -o "$WORK/disc.json" > /dev/null || fail "disc options exited $?"
[ "$(field "$WORK/disc.json" 'd["robots"][0]["shape"]')" = "{'radius': 0.25, 'type': 'disc'}" ] || fail "disc radius not written"
[ "$(field "$WORK/disc.json" 'd["workspace"]["max"]')" = "[12.0, 12.0]" ] || fail "workspace is not 12 x 12"
[ "$(field "$WORK/disc.json" 'len(d["obstacles"])')" = 3 ] || fail "--obstacles 3 did not give 3"
"$GEN" generate --family arms --robots 4 --obstacles --seed 2 -o "$WORK/arms.json" > /dev/null || fail "arms exited $?"
[ "$(field "$WORK/arms.json" 'set(r["type"] for r in d["robots"])')" = "{'manipulator'}" ] || fail "arms scenario is not all manipulators"
[ "$(field "$WORK/arms.json" 'len(d["obstacles"])')" = 2 ] || fail "--obstacles alone did not give one per pair"

# Every file is a valid scenario for the project's own loader: validating
# an unsolved solution is "invalid" (1), never "bad input" (2).
if [ -x "$PLAN" ]; then
  for f in a:mobile-obst-8-s3 open:mobile-4-s1 disc:mobile-disc-r0.25-w12-obst3-rot-4-s1 arms:arms-obst-4-s2; do
    name=${f#*:}
    f=${f%%:*}
    [ "$(field "$WORK/$f.json" 'd["name"]')" = "$name" ] || fail "$f.json is not named $name"
    printf '{"format":"earc.solution.v1","scenario":"%s","method":"none","solved":false,"paths":[],"stats":{}}\n' \
      "$name" > "$WORK/$f.sol.json"
    "$PLAN" validate "$WORK/$f.json" "$WORK/$f.sol.json" > /dev/null 2>&1
    [ $? -eq 1 ] || fail "$f.json is not accepted as a valid scenario by earc-plan validate"
  done
fi

"$GEN" generate --family boats --robots 4 -o "$WORK/x.json" > /dev/null 2>&1 && fail "unknown family accepted"
"$GEN" generate --family mobile --robots 1 -o "$WORK/x.json" > /dev/null 2>&1 && fail "1 robot accepted"
"$GEN" generate --family mobile --robots 129 -o "$WORK/x.json" > /dev/null 2>&1 && fail "129 robots accepted"
"$GEN" generate --family arms --robots 4 --workspace 30 -o "$WORK/x.json" > /dev/null 2>&1 && fail "--workspace accepted for arms"
# Every bad request is bad input: one line naming the option, exit 2, no
# file; an impossible one (too crowded) too, as it is what was asked for.
refused() {  # refused TEXT ARGS...
  local want=$1
  shift
  "$GEN" "$@" -o "$WORK/x.json" > /dev/null 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "earc-scenario $* exited $rc, not 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF -- "$want" "$WORK/err" ||
    fail "earc-scenario $*: expected one line with '$want': $(cat "$WORK/err")"
  [ -e "$WORK/x.json" ] && fail "earc-scenario $* left an output file"
}
refused "--robots: could not place 128 robots in 50 obstacle layouts" generate --family mobile --robots 128 --workspace 4
refused "--robots: could not place 2 robots" generate --robots 2 --obstacles 1000
refused "--workspace: must be in [2, 1000], got 1" generate --workspace 1
refused "--workspace: must be in [3, 1000], got 2.5" generate --workspace 2.5 --obstacles
refused "--radius: must be in [0.01, 5], got 100" generate --shape disc --radius 100
refused "--radius: applies to --shape disc only" generate --radius 0.2
refused "--rotated: turns obstacles: give --obstacles" generate --rotated
refused "--rotated: turns obstacles: give --obstacles" generate --rotated --obstacles 0 --family arms
refused "--robots: '1' is not a whole number in 2..128" generate --robots 1
refused "--seed: '-1' is not a whole number" generate --seed -1
refused "--obstacles: '-1' is not a count in [0, 1000]" generate --obstacles -1
refused "--obstacles: '1001' is not a count in [0, 1000]" generate --obstacles 1001
"$GEN" generate --robots 2 --workspace 2.5 -o "$WORK/small.json" > /dev/null || fail "a small workspace without obstacles exited $?"
echo "ok"
