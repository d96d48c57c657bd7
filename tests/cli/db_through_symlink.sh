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

echo "ok"
