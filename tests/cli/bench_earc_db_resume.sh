#!/bin/bash
# label: bench
# earc-bench run records on each earc and lightning trial whether the
# databases learned (--learn), and on each earc trial its E-ARC database
# and where that database's history stood (results schema 8). A run
# resumed into the same --results is refused before anything runs, in one
# line naming the option (exit 2), when it gives another --learn, another
# --earc-db-count than its databases were built from, or an E-ARC database
# that is not the one its earc trials of that --seed found: another file
# (even one built by the same command), one changed since (but by their
# own learning under --learn), or none, so that the run would build one.
# The same database by another path resumes. A file from before schema 8
# resumes on any database. (bench_earc_db_names.sh: the names of the
# databases the run builds, and files from before them.) Skipped (77)
# without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan earc-db
failShowsOutput
cd "$WORK" || exit 1
lastToken() { sqlValue "$1" "SELECT token FROM history ORDER BY id DESC LIMIT 1"; }

NO_COUNT=(run --suites mobile --robots 2 --methods earc --time-limit 5 --seed 3)
RUN=("${NO_COUNT[@]}" --earc-db-count 20)
BUILT=r.sqlite.work/earc-mobile-p20-s3.sqlite
"$BENCH" "${RUN[@]}" --trials 1 --results r.sqlite > out 2> err || fail "run exited $?"
[ "$(sqlValue r.sqlite "SELECT learn || ' ' || earc_db || ' ' || earc_db_state FROM trials")" = \
  "0 $BUILT $(lastToken $BUILT)" ] || fail "the earc trial does not record --learn, its database and its state"
tail=": a results file holds the earc trials of one E-ARC database per kind of robot and seed, as they found it (give that one, or another --results)"
counts=": a results file holds the earc trials of E-ARC databases built from one count"
trials() { [ "$(sqlValue r.sqlite "SELECT count(*) FROM trials")" -eq "$1" ] || fail "not $1 trials: a refused run recorded some"; }

# The same options: nothing to run. Another --learn or count: refused.
"$BENCH" "${RUN[@]}" --trials 1 --results r.sqlite > out 2> err || fail "resumed with the same: exit $?"
grep -q "^nothing to run" out || fail "resumed with the same options ran trials"
refusedInOneLine "r.sqlite: --learn: its earc trials ran with no --learn (fixed databases); this run gives --learn: a results file holds one --learn setting per method" \
  "$BENCH" "${RUN[@]}" --trials 2 --learn --results r.sqlite
refusedInOneLine "r.sqlite: --earc-db-count: its E-ARC database $BUILT was built from 20 problems; this run gives 30 problems$counts" \
  "$BENCH" "${NO_COUNT[@]}" --trials 2 --earc-db-count 30 --results r.sqlite
refusedInOneLine "r.sqlite: --earc-db-count: its E-ARC database $BUILT was built from 20 problems; this run gives earc-db's default count$counts" \
  "$BENCH" "${NO_COUNT[@]}" --trials 2 --results r.sqlite
# Another database, built by the very command that built the first.
"$BUILD/earc-db" build --db other.sqlite --kind mobile --count 20 --seed 3 -q || fail "earc-db build exited $?"
refusedInOneLine "r.sqlite: --db-mobile: its earc trials of mobile robots with --seed 3 ran on the E-ARC database $BUILT; other.sqlite is another$tail" \
  "$BENCH" "${NO_COUNT[@]}" --trials 2 --db-mobile other.sqlite --results r.sqlite
trials 1
# The same database by another path: its trials go on, recording it so.
cp $BUILT moved.sqlite
[ -e $BUILT-wal ] && cp $BUILT-wal moved.sqlite-wal
"$BENCH" "${NO_COUNT[@]}" --trials 2 --db-mobile moved.sqlite --results r.sqlite > out 2> err || fail "moved: exit $?"
trials 2
[ "$(sqlValue r.sqlite "SELECT count(DISTINCT earc_db_state) || ' ' || group_concat(earc_db, ' ') FROM
     (SELECT * FROM trials ORDER BY id)")" = "1 $BUILT moved.sqlite" ] || fail "the moved database is not recorded as it is"

# A change since to its rows, in place (curate), refuses it; so would
# learning, but under --learn, where the trials' own learning is no change.
cp moved.sqlite learned.sqlite
"$BUILD/earc-db" curate --db moved.sqlite --dedupe 1000 -q || fail "earc-db curate exited $?"
refusedInOneLine "r.sqlite: --db-mobile: its earc trials of mobile robots with --seed 3 ran on the E-ARC database $BUILT; moved.sqlite has changed since (curate)$tail" \
  "$BENCH" "${NO_COUNT[@]}" --trials 3 --db-mobile moved.sqlite --results r.sqlite
learnLine() {  # DB TOKEN: a line as a planning session that learned leaves one
  "$PY" - "$1" "$2" <<'PY' || fail "could not add a learn line to $1"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
c.execute("INSERT INTO history (token, at, program, operation, detail, rows_added)"
          " VALUES (?, 0, 'test', 'learn', 'planning session 9', 1)", (int(sys.argv[2]),))
c.commit()
PY
}
learnLine learned.sqlite 77
refusedInOneLine "learned.sqlite has changed since (learn)" \
  "$BENCH" "${NO_COUNT[@]}" --trials 3 --db-mobile learned.sqlite --results r.sqlite
trials 2
"$BENCH" "${RUN[@]}" --trials 1 --learn --results l.sqlite > out 2> err || fail "a --learn run exited $?"
[ "$(sqlValue l.sqlite "SELECT learn FROM trials")" = 1 ] || fail "a --learn trial does not record it"
learnLine l.sqlite.work/earc-mobile-p20-s3-learn.sqlite 78
"$BENCH" "${RUN[@]}" --trials 2 --learn --results l.sqlite > out 2> err || fail "a --learn run resumed after learning: exit $?"
[ "$(sqlValue l.sqlite "SELECT count(*) FROM trials")" -eq 2 ] || fail "the --learn run did not go on"
refusedInOneLine "l.sqlite: --learn: its earc trials ran with --learn; this run gives no --learn (fixed databases)" \
  "$BENCH" "${RUN[@]}" --trials 3 --results l.sqlite

# Gone: the run would build another in its place.
mv $BUILT kept.sqlite
refusedInOneLine "r.sqlite: --db-mobile: its earc trials of mobile robots with --seed 3 ran on the E-ARC database $BUILT; this run would build a new one at $BUILT$tail" \
  "$BENCH" "${RUN[@]}" --trials 3 --results r.sqlite
[ -e $BUILT ] && fail "a refused run built a database"
mv kept.sqlite $BUILT

# Scenario files: their trials' database is held to as well.
file=$(ls r.sqlite.work/scenarios/*.json | head -n 1)
FILES_NO_COUNT=(run --methods earc --time-limit 5 --seed 3)
FILES=("${FILES_NO_COUNT[@]}" --earc-db-count 20)
"$BENCH" "${FILES[@]}" --results f.sqlite "$file" > out 2> err || fail "run of a file exited $?"
refusedInOneLine "f.sqlite: --db-mobile: its earc trials of mobile robots with --seed 3 ran on the E-ARC database f.sqlite.work/earc-files-mobile-" \
  "$BENCH" "${FILES_NO_COUNT[@]}" --db-mobile other.sqlite --results f.sqlite "$file"
grep -qF "; other.sqlite is another$tail" err || fail "not refused as another database: $(cat err)"

# A version 7 file (nothing recorded) resumes on any database and with
# any --learn, and is migrated; the count its databases rows record holds.
"$PY" - <<'PY' || fail "could not make a version 7 file"
import sqlite3
src, dst = sqlite3.connect("r.sqlite"), sqlite3.connect("old.sqlite")
src.backup(dst)
for column in ("learn", "earc_db", "earc_db_state", "lower_bound", "refine_first_time_s",
               "refine_first_sum_of_costs", "refine_final_sum_of_costs", "refine_final_makespan"):
    dst.execute("ALTER TABLE trials DROP COLUMN %s" % column)
dst.execute("PRAGMA user_version = 7")
dst.commit()
PY
refusedInOneLine "old.sqlite: --earc-db-count: its E-ARC database $BUILT was built from 20 problems; this run gives 30 problems" \
  "$BENCH" "${NO_COUNT[@]}" --trials 2 --earc-db-count 30 --results old.sqlite --work-dir r.sqlite.work
"$BENCH" "${NO_COUNT[@]}" --trials 2 --learn --db-mobile other.sqlite --results old.sqlite > out 2> err ||
  fail "a version 7 file resumed on another database with --learn: exit $?"
grep -q "^nothing to run" out || fail "the version 7 file's trials were not skipped"
[ "$(sqlValue old.sqlite "PRAGMA user_version")" -eq 9 ] || fail "the version 7 file was not migrated"
echo "ok: a resumed run is held to its trials' E-ARC database, count and --learn"
