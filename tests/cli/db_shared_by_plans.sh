#!/bin/bash
# One experience file, several E-ARC plans at once: a long plan learning
# while short plans open, learn and close the same file beside it. The
# plans exit 0 or 1 (on a loaded machine a crowded plan may run out of
# time; never 2, damage), the file
# passes `earc-db verify` (integrity_check and every
# row), and every row id a plan reported learned is in the file. (Each
# plan's background quick_check used to read the file's header through a
# descriptor of its own, whose close dropped the plan's SQLite locks: a
# short plan closing then took itself for the last user and deleted the
# WAL under the long one, which found the file damaged.)
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needBuilt earc-plan earc-db earc-scenario
for tool in jq sqlite3; do command -v $tool > /dev/null || { echo "skipped: no $tool"; exit 77; }; done
"$BUILD/earc-scenario" generate -n 40 --workspace 8 --seed 1 -o "$WORK/long.json" > /dev/null || fail "generate long"
"$BUILD/earc-scenario" generate -n 24 --workspace 8 --obstacles 4 --seed 2 -o "$WORK/short.json" > /dev/null ||
  fail "generate short"
"$BUILD/earc-db" build --db "$WORK/s.db" --kind mobile --count 1000 --seed 1 -q || fail "build"

# (--no-crowd: handed to the crowd solver, the long plan's jam would end
# it within a second, before any short plan had run.)
"$BUILD/earc-plan" plan "$WORK/long.json" -o "$WORK/long.sol.json" --method earc --db "$WORK/s.db" \
  --no-crowd --time-limit 30 -q 2> "$WORK/long.err" &
long=$!
sleep 1
# Short plans one after another while the long one runs (at most 8): at
# least one must have opened and closed the file while the long plan used
# it, i.e. a second one started, or the test proves nothing.
started=0
while [ $started -lt 8 ] && kill -0 $long 2> /dev/null; do
  started=$((started + 1))
  "$BUILD/earc-plan" plan "$WORK/short.json" -o "$WORK/short$started.sol.json" --method earc --db "$WORK/s.db" \
    --seed $started -q 2> "$WORK/short$started.err"
  rc=$?
  [ $rc -le 1 ] || fail "short plan $started exited $rc: $(head -c 300 "$WORK/short$started.err")"
done
[ $started -ge 2 ] || fail "the long plan ended before a short one had closed the file: the test proves nothing"
wait $long
rc=$?
[ $rc -le 1 ] || fail "the long plan exited $rc: $(head -c 300 "$WORK/long.err")"
"$BUILD/earc-db" verify --db "$WORK/s.db" > "$WORK/verify.out" 2>&1 || fail "verify: $(tail -c 400 "$WORK/verify.out")"
learned=0
for sol in "$WORK"/long.sol.json "$WORK"/short?.sol.json; do
  for id in $(jq -r '.stats.db_learned_ids[]?' "$sol"); do
    n=$(sqlite3 "file:$WORK/s.db?mode=ro" "SELECT count(*) FROM experiences WHERE id = $id" 2>&1)
    [ "$n" = 1 ] || fail "row $id, learned by $(basename "$sol"), is not in the file ($n)"
    learned=$((learned + 1))
  done
done
[ $learned -ge 1 ] || fail "no plan learned anything: the test proves nothing"
echo "ok: $((started + 1)) plans shared the file, $learned learned rows all there"
