#!/bin/bash
# label: bench
# earc-bench run names each E-ARC database it builds by what its rows come
# of, WORK/earc-FAMILY[-pCOUNT]-sSEED[-learn].sqlite (scenario files:
# earc-files-FAMILY-ROBOTS-...), as it names Lightning's, so that a run
# takes one only where it would have built the same: a run of another
# --seed into the same results file, one with --learn, with another count
# (into another results file: one file holds one count), or for files of
# other robots builds its own; another results file sharing the work
# directory takes one built the same way. A resumed file from before the
# names: its schema 8 trials hold the run to the database under the old
# name (refused, naming it, until it is given with --db-mobile); an older
# file's run builds one under the new name and goes on. Skipped (77)
# without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan earc-db earc-scenario
failShowsOutput
cd "$WORK" || exit 1
built() { grep -q "^building E-ARC database $1 " out || fail "$2: did not build $1: $(cat out)"; }
notBuilt() { grep -q "^building E-ARC database" out && fail "$1: built a database: $(cat out)"; }
names() { (cd "$1" && ls -- *.sqlite | tr '\n' ' '); }

BASE=(run --suites mobile --robots 2 --methods earc --time-limit 5)
NO_COUNT=("${BASE[@]}" --trials 1 --work-dir w)
RUN=("${NO_COUNT[@]}" --earc-db-count 20)
OLD=("${BASE[@]}" --earc-db-count 20 --seed 3)
"$BENCH" "${RUN[@]}" --seed 3 --results a.sqlite > out 2> err || fail "seed 3 exited $?"
built w/earc-mobile-p20-s3.sqlite "seed 3"
# Another seed into the same results file: its own database.
"$BENCH" "${RUN[@]}" --seed 4 --results a.sqlite > out 2> err || fail "seed 4 exited $?"
built w/earc-mobile-p20-s4.sqlite "seed 4 into the same results file"
[ "$(sqlValue a.sqlite "SELECT group_concat(seed || ':' || earc_db, ' ') FROM (SELECT * FROM trials ORDER BY id)")" = \
  "3:w/earc-mobile-p20-s3.sqlite 4:w/earc-mobile-p20-s4.sqlite" ] || fail "the trials do not record their seed's database"
# Both seeds resume, each on its own.
for seed in 3 4; do
  "$BENCH" "${RUN[@]}" --seed $seed --results a.sqlite > out 2> err || fail "seed $seed resumed: exit $?"
  grep -q "^nothing to run" out || fail "seed $seed resumed and ran trials"
done
# Another results file sharing the work directory takes the one built the
# same way; with --learn, or earc-db's default count, it builds its own.
"$BENCH" "${RUN[@]}" --seed 3 --results b.sqlite > out 2> err || fail "b exited $?"
notBuilt "another results file, built the same way"
"$BENCH" "${RUN[@]}" --seed 3 --learn --results c.sqlite > out 2> err || fail "--learn exited $?"
built w/earc-mobile-p20-s3-learn.sqlite "--learn"
"$BENCH" "${NO_COUNT[@]}" --seed 3 --results d.sqlite > out 2> err || fail "earc-db's count exited $?"
built w/earc-mobile-s3.sqlite "earc-db's default count"
[ "$(names w)" = "earc-mobile-p20-s3-learn.sqlite earc-mobile-p20-s3.sqlite earc-mobile-p20-s4.sqlite \
earc-mobile-s3.sqlite " ] || fail "not one database per seed, count and --learn: $(names w)"
# One results file holds the trials of databases built from one count,
# whichever seed built them.
refusedInOneLine "a.sqlite: --earc-db-count: its E-ARC database w/earc-mobile-p20-s3.sqlite was built from 20 problems; this run gives 30 problems: a results file holds the earc trials of E-ARC databases built from one count" \
  "$BENCH" "${NO_COUNT[@]}" --earc-db-count 30 --seed 5 --results a.sqlite
[ -e w/earc-mobile-p30-s5.sqlite ] && fail "a refused run built its database"

# Scenario files: named by the robots they are built for too.
for r in 0.25 0.3; do
  "$BUILD/earc-scenario" generate --family mobile -n 2 --shape disc --radius $r --seed 3 -o disc$r.json > /dev/null ||
    fail "generate"
done
"$BENCH" run --methods earc --time-limit 5 --earc-db-count 20 --work-dir w --results f.sqlite disc0.25.json \
  > out 2> err || fail "files exited $?"
first=$(cd w && ls earc-files-mobile-*-p20-s1.sqlite)
[ -n "$first" ] && built "w/$first" "a scenario file"
"$BENCH" run --methods earc --time-limit 5 --earc-db-count 20 --work-dir w --results g.sqlite disc0.3.json \
  > out 2> err || fail "other robots' file exited $?"
[ "$(cd w && ls earc-files-mobile-*-p20-s1.sqlite | wc -l)" = 2 ] ||
  fail "files of other robots took the first files' database: $(names w)"

# Before the names: a schema 8 file whose trials ran on
# WORK/earc-mobile.sqlite, as an older earc-bench left it.
"$BENCH" "${OLD[@]}" --trials 1 --work-dir old.work --results old.sqlite > out 2> err || fail "old exited $?"
mv old.work/earc-mobile-p20-s3.sqlite old.work/earc-mobile.sqlite
[ -e old.work/earc-mobile-p20-s3.sqlite-wal ] && mv old.work/earc-mobile-p20-s3.sqlite-wal old.work/earc-mobile.sqlite-wal
"$PY" - <<'PY' || fail "could not name the database as before"
import sqlite3
c = sqlite3.connect("old.sqlite")
c.execute("UPDATE trials SET earc_db = 'old.work/earc-mobile.sqlite'")
c.execute("UPDATE databases SET path = 'old.work/earc-mobile.sqlite'")
c.commit()
PY
cp old.sqlite old7.sqlite
cp -r old.work old7.work
# Its trials hold the run to that database: refused, naming it and the one
# the run would build, before anything is built; given, it resumes on it.
refusedInOneLine "old.sqlite: --db-mobile: its earc trials of mobile robots with --seed 3 ran on the E-ARC database old.work/earc-mobile.sqlite; this run would build a new one at old.work/earc-mobile-p20-s3.sqlite" \
  "$BENCH" "${OLD[@]}" --trials 2 --work-dir old.work --results old.sqlite
[ -e old.work/earc-mobile-p20-s3.sqlite ] && fail "a refused resume built a database"
"$BENCH" "${BASE[@]}" --seed 3 --trials 2 --work-dir old.work --db-mobile old.work/earc-mobile.sqlite \
  --results old.sqlite > out 2> err || fail "resumed on the old database: exit $?"
notBuilt "resumed on the old database"
[ "$(sqlValue old.sqlite "SELECT count(*) FROM trials WHERE earc_db = 'old.work/earc-mobile.sqlite'")" = 2 ] ||
  fail "the resumed trial did not plan on the old database"
# A version 7 file records no database: its run builds one under the new
# name, from the count its databases rows hold, and goes on.
"$PY" - <<'PY' || fail "could not make a version 7 file"
import sqlite3
c = sqlite3.connect("old7.sqlite")
for column in ("learn", "earc_db", "earc_db_state", "lower_bound", "refine_first_time_s", "refine_first_sum_of_costs",
               "refine_final_sum_of_costs", "refine_final_makespan"):
    c.execute("ALTER TABLE trials DROP COLUMN %s" % column)
c.execute("PRAGMA user_version = 7")
c.commit()
PY
"$BENCH" "${OLD[@]}" --trials 2 --work-dir old7.work --results old7.sqlite > out 2> err ||
  fail "a version 7 file resumed: exit $?"
built old7.work/earc-mobile-p20-s3.sqlite "a version 7 file resumed"
[ "$(sqlValue old7.sqlite "SELECT count(*) || ' ' || max(earc_db) FROM trials")" = "2 old7.work/earc-mobile-p20-s3.sqlite" ] ||
  fail "the version 7 file's run did not go on on its new database"
echo "ok: E-ARC databases the run builds are named by what their rows come of"
