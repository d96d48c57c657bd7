#!/bin/bash
# label: bench
# The time limit holds on arms of a thousand links, where one state's
# self-collision check takes about a millisecond: every method stops
# within half a second of --time-limit by its own clock and within two by
# the wall clock, and says the time limit was why. Before the limit was
# polled inside roadmap construction, motion checks and the space-time
# search, arc, earc and prioritized planned for 2.4 to 3.6 s here, and
# Lightning (whose path simplifier runs a round however late) for 3.5 to
# 4.9 s, depending on the machine's load.
# (Label bench: it times the process, which AddressSanitizer slows down.)
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
command -v jq > /dev/null || { echo "skipped: no jq (tools/setup.sh --tests)"; exit 77; }
needBuilt earc-plan

# Two facing arms of N links (2.5 long in all, radius 0.3 of a link) that
# sweep through each other from up to down: the straight motions collide.
# $2 bounds every joint but the first (0: the full circle).
arms() {
  awk -v n="$1" -v lim="$2" 'BEGIN {
    pi = atan2(0, -1); L = 2.5 / n; if (lim == 0) lim = pi
    printf "{\"format\": \"earc.scenario.v1\", \"name\": \"many-links\", \"workspace\": {\"min\": [0, 0], \"max\": [10, 10]}, \"robots\": ["
    for (a = 0; a < 2; a++) {
      printf "%s{\"name\": \"a%d\", \"type\": \"manipulator\", \"base\": [%s, 5, %.17g], \"link_radius\": %.17g, \"links\": [", (a ? ", " : ""), a, (a ? 7 : 3), (a ? pi : 0), 0.3 * L
      for (i = 0; i < n; i++) printf "%s%.17g", (i ? ", " : ""), L
      printf "], \"joint_limits\": [[%.17g, %.17g]", -pi, pi
      for (i = 1; i < n; i++) printf ", [%.17g, %.17g]", -lim, lim
      s = (a ? -pi / 2 : pi / 2)
      printf "], \"start\": [%.17g", s
      for (i = 1; i < n; i++) printf ", 0"
      printf "], \"goal\": [%.17g", -s
      for (i = 1; i < n; i++) printf ", 0"
      printf "]}"
    }
    print "]}"
  }'
}
arms 1000 0 > "$WORK/free.json"      # random samples almost all self-collide
arms 1000 0.02 > "$WORK/stiff.json"  # Lightning finds a path and simplifies it

LIMIT=1
OWN_MAX=$(awk -v l=$LIMIT 'BEGIN { print l + 0.5 }')  # by the plan's own clock
# Reading the scenario, and validating a plan solved in time, come on top.
WALL_MAX=$((LIMIT + 2))
for method in arc earc prioritized coupled lightning; do
  scenario=free extra=()
  [ "$method" = earc ] && extra=(--db "$WORK/empty.sqlite")
  [ "$method" = lightning ] && scenario=stiff
  timedPlan "$WORK/$scenario.json" -o "$WORK/$method.sol.json" --method "$method" --time-limit $LIMIT --seed 1 -q "${extra[@]}"
  checkTimedPlan "$method on $scenario (limit $LIMIT s)" "$WORK/$method.sol.json" "$OWN_MAX" "$WALL_MAX"
done
# No roadmap of these arms is built in 1 s: the limit must be what
# stopped them, or this test checked nothing.
for method in arc prioritized; do
  [ "$(jq .solved "$WORK/$method.sol.json" 2> /dev/null)" = false ] || fail "$method solved in $LIMIT s?"
done

[ $failures -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "ok"
