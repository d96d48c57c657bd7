#!/bin/bash
# label: bench
# Limits are honoured. With --time-limit L on a 128-robot scenario that no
# method solves that fast, every method stops within 10% of L, by its own
# clock and by the wall clock (plus 1 s for start-up and writing), and
# says the time limit was why. A scenario whose resolution makes even the
# straight start-to-goal paths too large to hold is refused at once as
# too_large, with the numbers, within a 400 MiB address-space limit. The
# coupled method holds the limit on 5,000 robots, and 200,000 obstacles
# are read and planned on in seconds.
# (Label bench: it times the process, which AddressSanitizer slows down.)
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
GEN="$BUILD/earc-scenario"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
command -v jq > /dev/null || { echo "skipped: no jq (tools/setup.sh --tests)"; exit 77; }

"$GEN" generate --family mobile -n 128 --obstacles --seed 1 -o "$WORK/big.json" > /dev/null || fail "generate"
LIMIT=3
OWN_MAX=$(awk -v l=$LIMIT 'BEGIN { print 1.1 * l }')       # by the plan's own clock
WALL_MAX=$(awk -v l=$LIMIT 'BEGIN { print 1.1 * l + 1 }')  # start-up and writing too
for method in arc earc prioritized coupled lightning; do
  extra=()
  [ "$method" = earc ] && extra=(--db "$WORK/empty.sqlite")
  timedPlan "$WORK/big.json" -o "$WORK/$method.json" --method "$method" --time-limit $LIMIT --seed 1 -q "${extra[@]}"
  checkTimedPlan "$method (limit $LIMIT s)" "$WORK/$method.json" "$OWN_MAX" "$WALL_MAX"
done
# Composite planning over 128 robots cannot finish in 3 s: the limit must
# be what stopped them, or this test checked nothing.
for method in coupled lightning; do
  [ "$(jq .solved "$WORK/$method.json" 2> /dev/null)" = false ] || fail "$method solved 128 robots in $LIMIT s?"
done

# The coupled method on 5,000 discs in a grid, two of which swap places:
# the composite space is 15,000-dimensional, and before the limit covered
# the checks around the search (and the space's setup and teardown were
# linear per robot) this took minutes past a 3 s limit.
awk 'BEGIN {
  n = 5000; side = 71
  printf "{\"format\": \"earc.scenario.v1\", \"name\": \"grid\", \"workspace\": {\"min\": [0, 0], \"max\": [%d, %d]}, \"robots\": [", 2 * side + 2, 2 * side + 2
  for (i = 0; i < n; i++) {
    x = 1 + (i % side) * 2; y = 1 + int(i / side) * 2; gx = x + 0.5; gy = y
    if (i == 0) { gx = 3; gy = 1 } else if (i == 1) { gx = 1; gy = 1 }
    printf "%s{\"name\": \"r%d\", \"type\": \"mobile\", \"shape\": {\"type\": \"disc\", \"radius\": 0.3}, \"start\": [%g, %g, 0], \"goal\": [%g, %g, 0]}", (i ? ", " : ""), i, x, y, gx, gy
  }
  print "]}"
}' > "$WORK/grid.json"
timedPlan "$WORK/grid.json" -o "$WORK/grid.sol.json" --method coupled --time-limit $LIMIT --seed 1 -q
checkTimedPlan "coupled on 5000 robots" "$WORK/grid.sol.json" "$OWN_MAX" "$WALL_MAX"

# 200,000 obstacles: reading them took 40 s while the parser tracked JSON
# paths through a DOM callback (quadratic in an array of objects). Two discs
# swap in a free corner; the whole command must stay well under that.
awk 'BEGIN {
  srand(1); n = 200000
  printf "{\"format\": \"earc.scenario.v1\", \"name\": \"clutter\", \"workspace\": {\"min\": [0, 0], \"max\": [2000, 2000]}, \"obstacles\": ["
  for (i = 0; i < n; i++)
    printf "%s{\"type\": \"box\", \"center\": [%.3f, %.3f], \"size\": [0.5, 0.5]}", (i ? ", " : ""), 10 + rand() * 1980, 10 + rand() * 1980
  print "], \"robots\": [{\"name\": \"a\", \"type\": \"mobile\", \"shape\": {\"type\": \"disc\", \"radius\": 0.3}, \"start\": [1, 1, 0], \"goal\": [3, 1, 0]}, {\"name\": \"b\", \"type\": \"mobile\", \"shape\": {\"type\": \"disc\", \"radius\": 0.3}, \"start\": [3, 1, 0], \"goal\": [1, 1, 0]}]}"
}' > "$WORK/clutter.json"
timedPlan "$WORK/clutter.json" -o "$WORK/clutter.sol.json" --time-limit $LIMIT --seed 1 -q
echo "arc on 200000 obstacles: exit $RC, solved $(jq .solved "$WORK/clutter.sol.json"), wall $WALL s"
[ $RC -eq 0 ] || fail "arc on 200000 obstacles: exit $RC"
awk -v t="$WALL" 'BEGIN { exit !(t <= 20) }' || fail "arc on 200000 obstacles took $WALL s"

# A resolution of 1e-5 over a 20 m workspace: millions of steps per robot.
jq '.resolution = {"translation": 0.00001, "rotation": 0.00001, "joint": 0.00001}' "$WORK/big.json" > "$WORK/fine.json"
# Under a 400 MiB address-space limit: planning it would need gigabytes.
(ulimit -v 409600; exec "$PLAN" plan "$WORK/fine.json" -o "$WORK/fine.sol.json" --time-limit 60) > "$WORK/fine.out"
rc=$?
grep -q '^not solved (too_large) after 0 s: the robots.* straight start-to-goal paths alone hold [0-9]* scalars' \
  "$WORK/fine.out" || fail "too large: the message does not say why: $(cat "$WORK/fine.out")"
[ $rc -eq 1 ] || fail "too large: exit $rc, expected 1"
jq -e '.stats.failure == ["too_large"]' "$WORK/fine.sol.json" > /dev/null || fail "too large: $(jq -c .stats "$WORK/fine.sol.json")"
jq -e '.stats.too_large.straight_path_scalars > .stats.too_large.limit' "$WORK/fine.sol.json" > /dev/null ||
  fail "too large: the numbers are missing: $(jq -c .stats.too_large "$WORK/fine.sol.json")"
jq -e '.stats.planning_time_s < 1' "$WORK/fine.sol.json" > /dev/null || fail "too large: not refused at once"
echo "too large: refused: $(jq -r .stats.too_large.detail "$WORK/fine.sol.json")"

[ $failures -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "ok"
