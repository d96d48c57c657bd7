#!/bin/bash
# A full disk: every command says so in one line naming the file that had
# no room, without SQL text, and exits 2. The disk is a small tmpfs,
# mounted by the test and filled to the last block: as root only
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

# Before the disk fills: a source database elsewhere.
"$DB" build --db "$WORK/src.db" --scenario "$SCEN" --count 20 --seed 3 --threads 1 -q || fail "build src.db"
dd if=/dev/zero of="$FULL/filler" bs=4k 2> /dev/null
[ "$(df --output=avail -k "$FULL" | tail -1)" -eq 0 ] || fail "the tmpfs is not full"
cd "$FULL" || fail "cd"

# curate -o: the output had no room, not the source.
refusedInOneLine "copy.db: cannot write: the disk is full" "$DB" curate --db "$WORK/src.db" -o copy.db
noSqlText "curate -o"
grep -qF "src.db" "$WORK/err" && fail "curate -o blames its source: $(cat "$WORK/err")"
ls | grep -q '^copy\.db' && fail "curate -o left $(ls | grep '^copy\.db')"

# The writers into a database: one line, exit 2.
refusedInOneLine "b.db: cannot write: the disk is full" "$DB" build --db b.db --scenario "$SCEN" --count 5 --threads 1 -q
noSqlText "build"
refusedInOneLine "i.db: cannot write: the disk is full" "$DB" import --db i.db "$WORK/src.db"
noSqlText "import"

echo "ok"
