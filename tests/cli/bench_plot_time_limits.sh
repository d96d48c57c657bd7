#!/bin/bash
# label: bench
# earc-bench plot draws trials of different time limits apart, as table
# tables them: a suite run under two limits gets time_SUITE-tlLIMIT and
# success_SUITE-tlLIMIT for each and no figure of both; --time-limit and
# --seed take one limit's or one run's trials, as table's do (one limit
# left: the plain names); and the same trials give the same files, byte
# for byte. Two small real runs (one ARC trial each, limits 5 s and 10 s,
# seeds 3 and 4). Skipped (77) without /usr/bin/python3 with matplotlib.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needBuilt earc-bench earc-plan
needMatplotlib

for run in "5 3" "10 4"; do
  read -r limit seed <<< "$run"
  "$BENCH" run --suites mobile --robots 2 --methods arc --trials 1 --time-limit "$limit" --seed "$seed" \
    --results "$WORK/r.sqlite" > "$WORK/run.out" 2>&1 || fail "run --time-limit $limit exited $?: $(tail -5 "$WORK/run.out")"
done

# plot [ARGS...] -o DIR: the figures' names in DIR, one line.
figures() {
  "$BENCH" plot --results "$WORK/r.sqlite" "$@" > /dev/null 2> "$WORK/plot.err" ||
    fail "plot $* exited $?: $(cat "$WORK/plot.err")"
  (cd "${!#}" && LC_ALL=C ls | tr '\n' ' ')
}
all=$(figures -o "$WORK/all")
want="databases.png databases.svg success_mobile-tl10.png success_mobile-tl10.svg success_mobile-tl5.png success_mobile-tl5.svg time_mobile-tl10.png time_mobile-tl10.svg time_mobile-tl5.png time_mobile-tl5.svg "
[ "$all" = "$want" ] || fail "plot of two time limits wrote: $all"
for args in "--time-limit 5" "--seed 3"; do
  dir="$WORK/${args// /}"
  one=$(figures $args -o "$dir")
  [ "$one" = "databases.png databases.svg success_mobile.png success_mobile.svg time_mobile.png time_mobile.svg " ] ||
    fail "plot $args wrote: $one"
done
# The same trial (limit 5 s, seed 3) chosen two ways: the same files.
for f in time_mobile.svg time_mobile.png success_mobile.svg; do
  cmp -s "$WORK/--time-limit5/$f" "$WORK/--seed3/$f" || fail "plot --time-limit 5 and --seed 3 differ in $f"
done
echo "ok"
