#!/bin/bash
# label: unsanitized
# The independent checker (../shared/tools/check_solution.py) accepts every
# generated scenario and every committed dataset as a valid scenario: with
# an unsolved dummy solution it must say "invalid solution" (1), never
# "invalid scenario" (2). Skipped (77) without ../shared or /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
CHECK="$SRC/../shared/tools/check_solution.py"
[ -d "$SRC/../shared" ] && [ -f "$CHECK" ] || { echo "skipped: no $SRC/../shared"; exit 77; }
needPython
GEN="$BUILD/earc-scenario"
needBuilt earc-scenario

for seed in 1 2; do
  for n in 2 8 32 128; do
    "$GEN" generate --family mobile --robots $n --seed $seed -o "$WORK/mobile-$n-$seed.json" > /dev/null || fail "mobile $n exited $?"
    "$GEN" generate --family mobile --robots $n --obstacles --seed $seed -o "$WORK/mobile-obst-$n-$seed.json" > /dev/null \
      || fail "mobile obstacles $n exited $?"
  done
  "$GEN" generate --family mobile --robots 16 --obstacles 20 --rotated --shape disc --seed $seed \
    -o "$WORK/mobile-disc-rot-$seed.json" > /dev/null || fail "rotated disc exited $?"
  for n in 2 4 8 16; do
    "$GEN" generate --family arms --robots $n --seed $seed -o "$WORK/arms-$n-$seed.json" > /dev/null || fail "arms $n exited $?"
    "$GEN" generate --family arms --robots $n --obstacles --seed $seed -o "$WORK/arms-obst-$n-$seed.json" > /dev/null \
      || fail "arms obstacles $n exited $?"
  done
  for map in random-32-32-10 den520d; do
    "$GEN" movingai "$SRC/datasets/movingai/$map.map" --robots 16 --seed $seed -o "$WORK/$map-$seed.json" > /dev/null \
      || fail "movingai $map exited $?"
  done
done

printf '{"format":"earc.solution.v1","scenario":"dummy","method":"none","solved":false,"paths":[],"stats":{}}\n' \
  > "$WORK/dummy.solution"
count=0
for f in "$WORK"/*.json "$SRC"/datasets/*.json; do
  [ -e "$f" ] || continue
  "$PY" "$CHECK" "$f" "$WORK/dummy.solution" > "$WORK/out" 2>&1
  status=$?
  [ $status -eq 1 ] || fail "check_solution.py exited $status for $(basename "$f"): $(head -5 "$WORK/out")"
  count=$((count + 1))
done
echo "ok: $count scenarios"
