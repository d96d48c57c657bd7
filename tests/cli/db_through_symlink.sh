#!/bin/bash
# A database given through a symbolic link behaves exactly like its target,
# for every command: the header checks apply (a bad file format byte is
# refused by name, not found at the first write), it imports and merges,
# reading it leaves nothing beside the target, and a plan and a service
# use it. SQLite's unix VFS refuses to open a link itself (O_NOFOLLOW):
# earc resolves the name first, as SQLite does for a main database. A
# dangling link given as curate's output has its target created, as
# export's does.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-db earc-plan earc-bench
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
SCEN="$SRC/tests/data/scenarios/swap-discs.json"
rows() { "$DB" inspect --db "$1" --json | "$PY" -c 'import json, sys; print(json.load(sys.stdin)["entries"])'; }
needPython

# The files in data/, the links in links/ (relative links, into another
# directory: the target's directory is where -wal and -shm go).
mkdir "$WORK/data" "$WORK/links"
cd "$WORK/data" || fail "cd"
"$DB" build --db real.db --scenario "$SCEN" --count 20 --seed 3 --threads 1 -q || fail "build real.db"
"$DB" build --db other.db --scenario "$SCEN" --count 20 --seed 4 --threads 1 -q || fail "build other.db"
n=$(rows real.db)
[ "$n" -gt 0 ] || fail "real.db holds no rows"
cp real.db bad.db
printf '\xe9' | dd of=bad.db bs=1 seek=18 conv=notrunc 2> /dev/null
cd "$WORK/links" || fail "cd"
ln -s ../data/real.db link.db
ln -s ../data/bad.db badlink.db
ln -s link.db link2.db  # a link to a link

# Import and merge from a link: the rows of the target.
"$DB" import --db "$WORK/data/b.db" link2.db -q || fail "import from a link to a link: exit $?"
[ "$(rows "$WORK/data/b.db")" = "$n" ] || fail "import from a link: $(rows "$WORK/data/b.db") rows, the target holds $n"
before=$(rows "$WORK/data/other.db")
"$DB" curate --db "$WORK/data/other.db" --merge link.db > "$WORK/out" 2> "$WORK/err" ||
  fail "curate --merge from a link: exit $?: $(cat "$WORK/err")"
grep -qF ", $n merged," "$WORK/out" || fail "curate --merge from a link: $(cat "$WORK/out")"
[ "$(rows "$WORK/data/other.db")" = $((before + n)) ] || fail "curate --merge from a link: rows"

# A file format byte SQLite never writes is refused through a link as
# directly, by every command, before SQLite opens the file.
want="damaged database file (SQLite header byte 18, the file format write version, is 233"
refusedBadlink() {
  refusedInOneLine "$want" "$@"
  grep -qF "badlink.db: " "$WORK/err" || fail "$*: the error does not name badlink.db: $(cat "$WORK/err")"
}
refusedBadlink "$DB" verify --db badlink.db
refusedBadlink "$DB" inspect --db badlink.db
refusedBadlink "$DB" export --db badlink.db -o "$WORK/bad.jsonl"
refusedBadlink "$DB" build --db badlink.db --count 2 --seed 9 --threads 1 -q
refusedBadlink "$DB" import --db "$WORK/data/c.db" badlink.db
refusedBadlink "$DB" curate --db "$WORK/data/other.db" --merge badlink.db
refusedBadlink "$DB" curate --db badlink.db --dedupe 0.1
refusedBadlink "$PLAN" plan "$SCEN" -o "$WORK/bad.json" --method earc --db badlink.db
refusedBadlink "$PLAN" serve --db badlink.db < /dev/null
refusedBadlink "$BUILD/earc-bench" run "$SCEN" --methods earc --db-mobile badlink.db \
  --results "$WORK/bad.sqlite"
[ -e "$WORK/data/c.db" ] && fail "a refused import created its target"
[ -e "$WORK/bad.json" ] && fail "a refused plan wrote a solution"

# A 0-byte target is judged by the -wal beside it, which is what SQLite
# reads, not by one beside the link: with a stray -wal next to the link,
# a source that only is read is still refused as an empty file.
: > "$WORK/data/empty.db"
ln -s ../data/empty.db empty.db
printf stray > empty.db-wal
refusedInOneLine "empty.db: empty file (0 bytes), not an earc database yet" "$DB" import --db "$WORK/data/d.db" empty.db
refusedInOneLine "empty.db: empty file (0 bytes), not an earc database yet" \
  "$DB" curate --db "$WORK/data/other.db" --merge empty.db
rm empty.db-wal

# Reading through a link leaves nothing beside the target (or the link).
for cmd in "inspect --db link.db" "export -q -o $WORK/r.jsonl --db link.db" \
  "curate -q -o $WORK/copy.db --db link.db"; do
  # shellcheck disable=SC2086
  "$DB" $cmd > /dev/null 2> "$WORK/err" || fail "$cmd: exit $?: $(cat "$WORK/err")"
  leftNothingBeside "$WORK/data/real.db" "$cmd through a link"
  leftNothingBeside "$WORK/links/link.db" "$cmd through a link"
done
[ -L link.db ] || fail "the link is gone"

# A plan and a service through a link: they read the target and learn
# into it, and leave nothing beside it when they close.
"$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db link2.db -q || fail "plan through a link: exit $?"
"$PLAN" validate "$SCEN" "$WORK/sol.json" > /dev/null || fail "the plan through a link is not valid"
leftNothingBeside "$WORK/data/real.db" "a plan through a link"
[ -L link.db ] && [ -L link2.db ] || fail "a plan replaced a link"
echo '{"id": 1, "op": "stats"}' | "$PLAN" serve --db link.db > "$WORK/serve.out" 2> "$WORK/serve.err" ||
  fail "serve through a link: exit $?: $(cat "$WORK/serve.err")"
"$PY" -c 'import json, sys
a = json.loads(open(sys.argv[1]).readline())
assert a["ok"] and a["stats"]["db_entries"] >= int(sys.argv[2]), a' "$WORK/serve.out" "$n" ||
  fail "serve through a link: $(cat "$WORK/serve.out")"
leftNothingBeside "$WORK/data/real.db" "a service through a link"

# inspect counts the WAL beside the target: another process holds the
# file open with rows in its WAL, and inspect through the link says as
# much as inspect of the file itself.
"$PY" - "$DB" "$WORK/data/real.db" "$WORK/links/link.db" <<'PYEOF' || fail "inspect's wal_bytes through a link"
import json, sqlite3, subprocess, sys
db, real, link = sys.argv[1:]
c = sqlite3.connect(real)
c.execute("PRAGMA wal_autocheckpoint = 0")
c.execute("UPDATE experiences SET retrieved_count = retrieved_count + 1")
c.commit()
got = [json.loads(subprocess.run([db, "inspect", "--db", f, "--json"], check=True, capture_output=True).stdout)["wal_bytes"]
       for f in (real, link)]
assert got[0] > 0 and got[1] == got[0], got
c.close()
PYEOF

# A dangling link as curate's output: its target is created (and the
# link kept), as export -o does; a second curate to it is refused.
cd "$WORK/links" || fail "cd"
ln -s ../data/curated.db dangling.db
"$DB" curate --db link.db --dedupe 0.1 -o dangling.db > "$WORK/out" 2> "$WORK/err" ||
  fail "curate -o onto a dangling link: exit $?: $(cat "$WORK/err")"
grep -qF "curated dangling.db:" "$WORK/out" || fail "curate -o onto a dangling link: $(cat "$WORK/out")"
[ -L dangling.db ] && [ -f "$WORK/data/curated.db" ] || fail "curate -o did not create the link's target"
"$DB" verify --db "$WORK/data/curated.db" > /dev/null || fail "the curated target does not verify"
ls "$WORK/data" | grep -q 'curated\.db\.tmp' && fail "curate -o left a temporary beside the target"
ls "$WORK/links" | grep -q '\.tmp\.' && fail "curate -o left a temporary beside the link"
refusedInOneLine "dangling.db: already exists; not overwriting it" \
  "$DB" curate --db link.db --dedupe 0.1 -o dangling.db
ln -s ../data/exported.jsonl dangling.jsonl
"$DB" export --db link.db -o dangling.jsonl -q || fail "export -o onto a dangling link"
[ -L dangling.jsonl ] && [ -s "$WORK/data/exported.jsonl" ] || fail "export -o did not create the link's target"
# The -wal of a new database made through a dangling link is part of it.
ln -s ../data/new.db dangling-new.db
refusedInOneLine "is the -wal file of --db" \
  "$PLAN" plan "$SCEN" -o "$WORK/data/new.db-wal" --method earc --db dangling-new.db
# earc-db build through a dangling link that makes no problem at all
# removes the file it made, the link's target, and keeps the link.
ln -s ../data/huge.db huge.db
refusedInOneLine "none of 3 problems could be made" \
  "$DB" build --db huge.db --shape disc --radius 40 --count 3 --threads 1
[ -L huge.db ] || fail "a build that made nothing removed the link it was given"
[ -e "$WORK/data/huge.db" ] && fail "a build that made nothing left the file it made through a link"

# earc-bench through links: a given database's size counts the WAL
# beside its target, and a build into a dangling link that fails part
# way removes what it made (the target and its WAL), not the link. A
# stand-in earc-db beside a copy of earc-bench fails so; a stand-in
# planner keeps the trials quick and away from the database.
mkdir "$WORK/bin"
cp "$BUILD/earc-bench" "$WORK/bin/"
ln -s "$BUILD/earc-plan" "$WORK/bin/earc-plan"
cat > "$WORK/bin/earc-db" <<'FAKE'
#!/bin/bash
while [ $# -gt 0 ]; do [ "$1" = --db ] && db=$2; shift; done
t=$(readlink -m "$db")
printf half > "$t"; printf half > "$t-wal"
echo "killed part way" >&2
exit 1
FAKE
chmod +x "$WORK/bin/earc-db"
writeTeleportingPlanner "$WORK/teleport"
ln -s ../data/half.db half.db
"$WORK/bin/earc-bench" run "$SCEN" --methods earc --db-mobile half.db --plan-program "$WORK/teleport" \
  --results "$WORK/half.sqlite" > "$WORK/out" 2> "$WORK/err"
grep -qF "building half.db failed" "$WORK/err" || fail "the stand-in build did not fail: $(cat "$WORK/err")"
[ -L half.db ] || fail "earc-bench removed the link it was given after a failed build"
[ -e "$WORK/data/half.db" ] || [ -e "$WORK/data/half.db-wal" ] &&
  fail "earc-bench left a half-built database at a link's target"
"$PY" - "$BUILD/earc-bench" "$SCEN" "$WORK/teleport" "$WORK/data/real.db" link.db "$WORK/size.sqlite" <<'PYEOF' ||
import os, sqlite3, subprocess, sys
bench, scen, planner, real, link, results = sys.argv[1:]
c = sqlite3.connect(real)
c.execute("PRAGMA wal_autocheckpoint = 0")
c.execute("UPDATE experiences SET retrieved_count = retrieved_count + 1")
c.commit()
want = os.path.getsize(real) + os.path.getsize(real + "-wal")
subprocess.run([bench, "run", scen, "--methods", "earc", "--db-mobile", link, "--plan-program", planner,
                "--results", results], capture_output=True)
got = sqlite3.connect("file:%s?mode=ro" % results, uri=True).execute("SELECT size_bytes FROM databases").fetchall()
assert got == [(want,)], (got, want)
c.close()
PYEOF
  fail "the size of a database given through a link"
# earc-bench's results file through a link: read as our own, under
# query_only, so that nothing is left beside the target.
ln -s ../size.sqlite results.sqlite
"$BUILD/earc-bench" table --results results.sqlite > /dev/null 2> "$WORK/err" ||
  fail "earc-bench table through a link: $(cat "$WORK/err")"
leftNothingBeside "$WORK/size.sqlite" "earc-bench table through a link"

# earc-bench compare's outputs may not be the -wal beside a linked --db's
# target either.
refusedInOneLine "is the --db file's -wal file" "$BUILD/earc-bench" compare --old "$PLAN" --method earc \
  --db link.db --suite mobile --robots 2 --trials 1 --work-dir "$WORK/w" --csv "$WORK/data/real.db-wal"
[ -e "$WORK/data/real.db-wal" ] && fail "compare wrote over the -wal of its --db's target"

# earc-bench compare starts each side from a copy of --db with its WAL,
# which is beside the target: rows another process deleted (held in the
# WAL) stay deleted in the copies.
"$PY" - "$BUILD/earc-bench" "$PLAN" "$WORK/data/real.db" link.db "$WORK/cmp" <<'PYEOF' || fail "compare through a link"
import sqlite3, subprocess, sys
bench, plan, real, link, work = sys.argv[1:]
c = sqlite3.connect(real)
c.execute("PRAGMA wal_autocheckpoint = 0")
c.execute("DELETE FROM experiences WHERE id NOT IN (SELECT id FROM experiences ORDER BY id LIMIT 3)")
c.commit()
r = subprocess.run([bench, "compare", "--old", plan, "--method", "earc", "--db", link, "--suite", "mobile", "--robots", "2",
                    "--trials", "1", "--time-limit", "5", "--work-dir", work], capture_output=True, text=True)
assert r.returncode == 0, r.stderr
for side in ("old", "new"):
    got = sqlite3.connect("file:%s/db-%s.sqlite?mode=ro" % (work, side), uri=True).execute(
        "SELECT count(*) FROM experiences").fetchone()[0]
    assert got == 3, (side, got)
c.close()
PYEOF

echo "ok"
