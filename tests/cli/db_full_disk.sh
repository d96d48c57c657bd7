#!/bin/bash
# A full disk: every command says so in one line naming the file that had
# no room, without SQL text, exits 2 and leaves no partial file; a plan
# whose database cannot take its lesson (or cannot even be created) is
# still made and written, with one warning line. The disk is a small
# tmpfs, mounted by the test and filled to the last block: as root only
# (skipped otherwise, or where mounting is not allowed).
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-db earc-plan
needPython
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
SCEN="$SRC/tests/data/scenarios/swap-discs.json"
FULL="$WORK/full"
mkdir "$FULL"
[ "$(id -u)" -eq 0 ] || { echo "skipped: mounting a full tmpfs needs root"; exit 77; }
mount -t tmpfs -o size=400k tmpfs "$FULL" 2> /dev/null || { echo "skipped: cannot mount a tmpfs here"; exit 77; }
trap 'cd / && umount "$FULL"; rm -rf "$WORK"' EXIT
# noSqlText: FAIL when the last error ($WORK/err) quotes SQL.
noSqlText() {
  grep -qE 'executing|PRAGMA|VACUUM|COMMIT|INSERT|UPDATE' "$WORK/err" && fail "$1: SQL text in the message: $(cat "$WORK/err")"
  return 0
}

# Before the disk fills: a database (on the full disk later) whose open
# must write, being in rollback-journal mode (earc switches it to WAL),
# and a source database elsewhere.
"$DB" build --db "$WORK/src.db" --scenario "$SCEN" --count 20 --seed 3 --threads 1 -q || fail "build src.db"
"$DB" build --db "$FULL/rb.db" --scenario "$SCEN" --count 20 --seed 3 --threads 1 -q || fail "build rb.db"
"$PY" -c 'import sqlite3, sys
c = sqlite3.connect(sys.argv[1]); assert c.execute("PRAGMA journal_mode = DELETE").fetchone()[0] == "delete"' \
  "$FULL/rb.db" || fail "rb.db to rollback-journal mode"
rb=$(md5sum < "$FULL/rb.db")
dd if=/dev/zero of="$FULL/filler" bs=4k 2> /dev/null
[ "$(df --output=avail -k "$FULL" | tail -1)" -eq 0 ] || fail "the tmpfs is not full"
cd "$FULL" || fail "cd"

# curate -o: the output had no room, not the source.
refusedInOneLine "copy.db: cannot write: the disk is full" "$DB" curate --db "$WORK/src.db" -o copy.db
noSqlText "curate -o"
grep -qF "src.db" "$WORK/err" && fail "curate -o blames its source: $(cat "$WORK/err")"
ls | grep -q '^copy\.db' && fail "curate -o left $(ls | grep '^copy\.db')"

# A plan with a new database on the full disk: made and written, as ARC
# plans it (no experience), with one warning line; no empty new.db.
"$PLAN" plan "$SCEN" -o "$WORK/arc.json" --method arc --seed 3 -q || fail "arc plan"
"$PLAN" plan "$SCEN" -o "$WORK/new.json" --method earc --db new.db --seed 3 -q 2> "$WORK/err" ||
  fail "a plan with a new database on a full disk: exit $?: $(cat "$WORK/err")"
[ "$(wc -l < "$WORK/err")" -eq 1 ] &&
  grep -qF "warning: new.db: cannot write: the disk is full, so the database could not be created; E-ARC planned as ARC does" \
    "$WORK/err" || fail "a plan with a new database on a full disk: $(cat "$WORK/err")"
noSqlText "a plan with a new database"
ls | grep -q '^new\.db' && fail "a plan left $(ls | grep '^new\.db') on the full disk"
"$PY" -c 'import json, sys
arc, earc = (json.load(open(f)) for f in sys.argv[1:])
assert earc["solved"] and earc["paths"] == arc["paths"], "not the plan ARC makes"
st = earc["stats"]
assert st["db_learned"] == 0 and "could not be created" in st["db_learn_error"], st' "$WORK/arc.json" "$WORK/new.json" ||
  fail "the plan with a new database on a full disk"
# ... and when even the plan has no room: one line, exit 2, nothing left.
refusedInOneLine "new.json: cannot write: the disk is full" "$PLAN" plan "$SCEN" -o new.json --method earc --db new.db
ls | grep -q '^new\.' && fail "a plan left $(ls | grep '^new\.') on the full disk"
# A database whose open must write (switching it to WAL): read as it is,
# with one warning line, and left as it was.
"$PLAN" plan "$SCEN" -o "$WORK/rb.json" --method earc --db rb.db --seed 3 -q 2> "$WORK/err" ||
  fail "a plan with a database that cannot be written: exit $?: $(cat "$WORK/err")"
[ "$(wc -l < "$WORK/err")" -eq 1 ] &&
  grep -qF "warning: rb.db: cannot write: the disk is full; E-ARC planned with what the database holds and learned nothing" \
    "$WORK/err" || fail "a plan with a database that cannot be written: $(cat "$WORK/err")"
"$PY" -c 'import json, sys
st = json.load(open(sys.argv[1]))["stats"]
assert st["db_queries"] >= 1 and st["db_hits"] + st["db_repairs"] >= 1 and st["db_learned"] == 0, st' "$WORK/rb.json" ||
  fail "the plan with a database that cannot be written did not use it"
[ "$(md5sum < rb.db)" = "$rb" ] || fail "rb.db changed"
# The service cannot do without its file: refused, one line.
refusedInOneLine "serve.db: database: cannot write: the disk is full" "$PLAN" serve --db serve.db < /dev/null
noSqlText "serve"
ls | grep -q '^serve\.db' && fail "serve left $(ls | grep '^serve\.db')"

# The offline writers: one line, exit 2, no partial database.
refusedInOneLine "b.db: cannot write: the disk is full" "$DB" build --db b.db --scenario "$SCEN" --count 5 --threads 1 -q
noSqlText "build"
refusedInOneLine "i.db: cannot write: the disk is full" "$DB" import --db i.db "$WORK/src.db"
noSqlText "import"
ls | grep -qE '^(b|i)\.db' && fail "a writer left $(ls | grep -E '^(b|i)\.db')"

# Written outputs: export's, like the writers above, is exit 2 (it was 1),
# and leaves neither a partial file nor a temporary.
refusedInOneLine "e.jsonl: cannot write: the disk is full" "$DB" export --db "$WORK/src.db" -o e.jsonl
ls | grep -q '^e\.jsonl' && fail "export left $(ls | grep '^e\.jsonl')"
rm filler
ls | grep -vxF rb.db && fail "files left on the full disk"

echo "ok"
