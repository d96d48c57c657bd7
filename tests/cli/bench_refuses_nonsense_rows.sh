#!/bin/bash
# label: bench
# earc-bench refuses a results database holding a value no run writes (a
# hand edit: robots -3, a planning time stored as text, a negative or
# infinite time, success 2, an unknown method, a seed that is no number, a
# solved trial's time beyond its limit, a database's robots -1): table and
# export exit 2 with one line naming the file, the table, the row's id and
# the column, and every subcommand that reads the file (run, lightning-db,
# plot too) refuses it so before it changes anything on disk. The rows come
# from a small real run (one ARC trial, one Lightning database), edited with
# the sqlite3 command. Skipped (77) without it.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needBuilt earc-bench earc-plan
command -v sqlite3 > /dev/null || { echo "skipped: no sqlite3 command"; exit 77; }
mkdir "$WORK/d" && cd "$WORK/d" || exit 1

"$BENCH" run --suites mobile --robots 2 --methods arc --trials 1 --time-limit 5 --results r.sqlite \
  --work-dir "$WORK/run" > "$WORK/run.out" 2>&1 || fail "run exited $?: $(tail -5 "$WORK/run.out")"
"$BENCH" lightning-db --suite mobile --robots 2 --count 1 --problem-time-limit 0.5 -o "$WORK/l.lightning" \
  --results r.sqlite > /dev/null || fail "lightning-db exited $?"
"$BENCH" table --results r.sqlite > /dev/null || fail "table of the file as the run left it exited $?"
[ "$(sqlite3 r.sqlite "SELECT count(*) FROM trials; SELECT count(*) FROM databases" | tr '\n' ' ')" = "1 1 " ] ||
  fail "the run left other rows than one trial and one database"

# NAME|SQL|what the error says after "NAME.sqlite: ".
cases=(
  "robots|UPDATE trials SET robots = -3|trials row id 1, column robots: -3 is not a robot count from 2 to 1024"
  "text-time|UPDATE trials SET planning_time_s = 'NaN'|trials row id 1, column planning_time_s: 'NaN' is not a number of seconds (0 or more)"
  "negative-time|UPDATE trials SET wall_time_s = -0.5|trials row id 1, column wall_time_s: -0.5 is not a number of seconds (0 or more)"
  "infinite-limit|UPDATE trials SET time_limit_s = 1e999|trials row id 1, column time_limit_s: inf is not a number of seconds above 0"
  "success|PRAGMA ignore_check_constraints = ON; UPDATE trials SET success = 2|trials row id 1, column success: 2 is not 0 or 1"
  "method|UPDATE trials SET method = 'magic'|trials row id 1, column method: 'magic' is not a method earc-bench runs (earc, arc, lightning, prioritized, coupled, lacam)"
  "seed|UPDATE trials SET seed = '-7'|trials row id 1, column seed: '-7' is not a seed"
  "late|UPDATE trials SET success = 1, failure = NULL, planning_time_s = 60|trials row id 1, column planning_time_s: 60 s of a solved trial is beyond its time limit of 5 s"
  "db-robots|UPDATE databases SET robots = -1|databases row id 1, column robots: -1 is not 0 (every robot count) or a robot count from 2 to 1024"
)
for c in "${cases[@]}"; do
  IFS='|' read -r name sql want <<< "$c"
  sqlite3 r.sqlite ".backup $name.sqlite" && sqlite3 "$name.sqlite" "$sql" || fail "could not make $name.sqlite"
done
dirSnapshot > "$WORK/before"

refused() {  # refused TEXT ARGS...: exit 2, one line on stderr containing TEXT, nothing changed
  refusedInOneLine "$1" "$BENCH" "${@:2}"
  dirSnapshot | cmp -s - "$WORK/before" || fail "earc-bench ${*:2} changed the directory: $(dirSnapshot | diff "$WORK/before" -)"
}

for c in "${cases[@]}"; do
  IFS='|' read -r name sql want <<< "$c"
  refused "$name.sqlite: $want" table --results "$name.sqlite"
  refused "$name.sqlite: $want" export --results "$name.sqlite" --csv out.csv
done
# Every reader checks the rows when it opens the file, before any work.
want="robots.sqlite: trials row id 1, column robots: -3 is not a robot count from 2 to 1024"
refused "$want" table --results robots.sqlite --wide
refused "$want" export --results robots.sqlite --ompl-log logs
refused "$want" plot --results robots.sqlite -o figures
refused "$want" run --suites mobile --robots 2 --methods arc --trials 2 --time-limit 5 --results robots.sqlite
refused "$want" lightning-db --suite mobile --robots 2 --count 1 -o new.lightning --results robots.sqlite
echo "ok"
