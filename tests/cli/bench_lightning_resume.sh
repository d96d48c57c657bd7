#!/bin/bash
# label: bench
# earc-bench run records on each lightning trial how the run grows the
# Lightning databases (--lightning-problems, else
# --lightning-problems-per-robot, and --lightning-problem-time-limit;
# results schema 7). A run resumed into the same --results with other ones
# is refused before anything runs, in one line naming the option, the
# recorded and the given value (exit 2), where it would pool trials of
# differently grown databases in one cell; the same ones resume. A file
# from before schema 7 records none, and resumes with any. Each database
# is named by what grows it, so that no run takes one grown otherwise;
# the limit per problem reaches lightning-db exactly. Skipped (77)
# without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
failShowsOutput
cd "$WORK" || exit 1

RUN=(run --suites mobile --robots 2 --methods arc,lightning --trials 1 --time-limit 5 --seed 3)
LIGHTNING=(--lightning-problems 2 --lightning-problem-time-limit 1)
"$BENCH" "${RUN[@]}" "${LIGHTNING[@]}" --results r.sqlite > out 2> err || fail "run exited $?"
[ "$(sqlValue r.sqlite "SELECT count(*) FROM trials")" -eq 2 ] || fail "not 2 trials"
[ "$(sqlValue r.sqlite "SELECT lightning_problems || ' ' || ifnull(lightning_problems_per_robot, 'NULL') || ' ' ||
     lightning_problem_time_limit_s FROM trials WHERE method = 'lightning'")" = "2 NULL 1.0" ] ||
  fail "the lightning trial does not record its settings"
[ "$(sqlValue r.sqlite "SELECT count(*) FROM trials WHERE method = 'arc' AND (lightning_problems IS NOT NULL OR
     lightning_problems_per_robot IS NOT NULL OR lightning_problem_time_limit_s IS NOT NULL)")" -eq 0 ] ||
  fail "an arc trial records Lightning settings"

# The same settings: nothing to run. Others: refused, nothing run or recorded.
"$BENCH" "${RUN[@]}" "${LIGHTNING[@]}" --results r.sqlite > out 2> err || fail "resumed with the same: exit $?"
grep -q "^nothing to run" out || fail "resumed with the same settings ran trials"
tail=": a results file holds one Lightning database setting (give the same, or another --results)"
refusedInOneLine "r.sqlite: --lightning-problem-time-limit: its lightning trials ran with 1; this run gives 3$tail" \
  "$BENCH" "${RUN[@]}" --lightning-problems 2 --lightning-problem-time-limit 3 --results r.sqlite
refusedInOneLine "r.sqlite: --lightning-problems: its lightning trials ran with 2; this run gives 5$tail" \
  "$BENCH" "${RUN[@]}" --lightning-problems 5 --lightning-problem-time-limit 1 --results r.sqlite
refusedInOneLine "r.sqlite: --lightning-problems: its lightning trials ran with 2; this run gives none (4 per robot)$tail" \
  "$BENCH" "${RUN[@]}" --lightning-problem-time-limit 1 --results r.sqlite
# More trials with other settings would have been run: still refused.
refusedInOneLine "r.sqlite: --lightning-problem-time-limit: its lightning trials ran with 1; this run gives 2" \
  "$BENCH" run --suites mobile --robots 2 --methods arc,lightning --trials 2 --time-limit 5 --seed 3 \
  --lightning-problems 2 --lightning-problem-time-limit 2 --results r.sqlite
[ "$(sqlValue r.sqlite "SELECT count(*) FROM trials")" -eq 2 ] || fail "a refused resume recorded trials"
# A run without lightning is not held to them.
"$BENCH" run --suites mobile --robots 2 --methods arc --trials 1 --time-limit 5 --seed 3 \
  --lightning-problem-time-limit 3 --results r.sqlite > out 2> err || fail "arc alone, other settings: exit $?"

# Per robot: recorded as such, and held to.
"$BENCH" "${RUN[@]}" --lightning-problems-per-robot 1 --lightning-problem-time-limit 1 --results p.sqlite \
  > out 2> err || fail "run per robot exited $?"
[ "$(sqlValue p.sqlite "SELECT ifnull(lightning_problems, 'NULL') || ' ' || lightning_problems_per_robot FROM trials
     WHERE method = 'lightning'")" = "NULL 1" ] || fail "the per-robot count is not recorded"
refusedInOneLine "p.sqlite: --lightning-problems-per-robot: its lightning trials ran with 1; this run gives 2$tail" \
  "$BENCH" "${RUN[@]}" --lightning-problems-per-robot 2 --lightning-problem-time-limit 1 --results p.sqlite

# A version 6 file (no settings recorded): resumed with any settings, and
# migrated; its old lightning trial holds the run to nothing.
"$PY" - <<'PY' || fail "could not make a version 6 file"
import sqlite3
src, dst = sqlite3.connect("r.sqlite"), sqlite3.connect("old.sqlite")
src.backup(dst)
for column in ("lightning_problems", "lightning_problems_per_robot", "lightning_problem_time_limit_s", "learn",
               "earc_db", "earc_db_state", "lower_bound", "refine_first_time_s", "refine_first_sum_of_costs",
               "refine_final_sum_of_costs", "refine_final_makespan"):
    dst.execute("ALTER TABLE trials DROP COLUMN %s" % column)
dst.execute("PRAGMA user_version = 6")
dst.commit()
PY
"$BENCH" "${RUN[@]}" --lightning-problem-time-limit 3 --results old.sqlite --work-dir r.sqlite.work > out 2> err ||
  fail "a version 6 file resumed with other settings: exit $?"
grep -q "^nothing to run" out || fail "the version 6 file's trials were not skipped"
[ "$(sqlValue old.sqlite "PRAGMA user_version")" -eq 9 ] || fail "the version 6 file was not migrated"
[ "$(sqlValue old.sqlite "SELECT count(*) FROM trials WHERE lightning_problem_time_limit_s IS NULL")" -eq 2 ] ||
  fail "the old trials gained settings"
# A limit per problem reaches lightning-db exactly, however small: 1e-07,
# not std::to_string's 0.000000, which lightning-db refuses.
"$BENCH" run --suites mobile --robots 2 --methods lightning --trials 1 --time-limit 5 --seed 3 \
  --lightning-problems 1 --lightning-problem-time-limit 1e-7 --results tiny.sqlite > out 2> err ||
  fail "a run with a limit per problem of 1e-7 exited $?"
grep -q "failed" err && fail "growing the Lightning database under 1e-7 s per problem failed"
[ "$(sqlValue tiny.sqlite "SELECT count(*) FROM databases WHERE method = 'lightning'")" -eq 1 ] ||
  fail "no Lightning database recorded for a limit per problem of 1e-7"
# A database is named by what grows it. Another results file sharing the
# --lightning-dir takes one grown the same way, and grows its own under
# other settings, another seed or --learn, where it took the first.
SHARED=(run --suites mobile --robots 2 --methods lightning --trials 1 --time-limit 5 --lightning-dir shared)
ONE=(--lightning-problems 1 --lightning-problem-time-limit 1)
"$BENCH" "${SHARED[@]}" --seed 3 "${ONE[@]}" --results s1.sqlite > out 2> err || fail "shared run exited $?"
[ "$(cd shared && echo *)" = "mobile-2-p1-t1-s3.lightning" ] || fail "not named by its growth: $(ls shared)"
# The run says what the build gave, under the line that started it.
grep -A1 "^building Lightning database" out | grep -Eq "^  shared/mobile-2-p1-t1-s3.lightning: [0-9]+ entries .*, [01] solved" ||
  fail "no summary of the Lightning build: $(cat out)"
"$BENCH" "${SHARED[@]}" --seed 3 "${ONE[@]}" --results s2.sqlite > out 2> err || fail "second shared run exited $?"
grep -q "^building Lightning database" out && fail "grown again for the same settings"
n=0
for other in "--seed 4 ${ONE[*]}" "--seed 3 --lightning-problems 2 --lightning-problem-time-limit 1" \
  "--seed 3 --lightning-problems 1 --lightning-problem-time-limit 0.5" "--seed 3 ${ONE[*]} --learn"; do
  n=$((n + 1))
  # shellcheck disable=SC2086
  "$BENCH" "${SHARED[@]}" $other --results "other$n.sqlite" > out 2> err || fail "run with $other exited $?"
  grep -q "^building Lightning database" out || fail "a run with $other took the database grown with ${ONE[*]}"
done
[ "$(cd shared && echo *)" = "mobile-2-p1-t0.5-s3.lightning mobile-2-p1-t1-s3-learn.lightning \
mobile-2-p1-t1-s3.lightning mobile-2-p1-t1-s4.lightning mobile-2-p2-t1-s3.lightning" ] ||
  fail "not one database per growth: $(ls shared)"
echo "ok: Lightning settings are recorded per trial and a resumed run is held to them"
