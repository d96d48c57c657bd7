#!/bin/bash
# Files earc-db must not use: a foreign SQLite file and a newer-schema file
# are refused with one clear line (exit 2) and left untouched; verify
# names damaged rows (blobs, signatures; exit 1) and passes a sound file
# (exit 0).
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
DB="$BUILD/earc-db"
needPython
needBuilt earc-db
sql() { "$PY" -c 'import sqlite3,sys
c = sqlite3.connect(sys.argv[1])
for s in sys.argv[2:]: c.execute(s)
c.commit()' "$@"; }

sql "$WORK/foreign.db" "create table photos (id integer primary key)"
before=$(md5sum < "$WORK/foreign.db")
for cmd in inspect build export; do
  extra=""; [ $cmd = export ] && extra="-o $WORK/x.jsonl"
  "$DB" $cmd --db "$WORK/foreign.db" $extra > "$WORK/out" 2> "$WORK/err"
  code=$?
  [ $code -eq 2 ] || fail "$cmd on a foreign file exited $code"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "$cmd: not one line: $(cat "$WORK/err")"
  grep -q "not an earc experience database (application_id 0x00000000, expected 0x45415243" "$WORK/err" \
    || fail "$cmd: unclear message: $(cat "$WORK/err")"
done
[ "$(md5sum < "$WORK/foreign.db")" = "$before" ] || fail "the foreign file was modified"

# A foreign file in WAL mode whose last commits are still in its WAL: the
# refusal leaves both files as they were (a read-write open would have
# copied the WAL into the file before the identity check).
"$PY" - "$WORK/fwal.db" "$WORK/fwalcopy.db" <<'PY' || fail "making a foreign WAL"
import shutil, sqlite3, sys
c = sqlite3.connect(sys.argv[1])
c.execute("pragma journal_mode = wal"); c.execute("pragma wal_autocheckpoint = 0")
c.execute("create table photos (id integer primary key)"); c.commit()
c.execute("insert into photos values (1)"); c.commit()
shutil.copy(sys.argv[1], sys.argv[2]); shutil.copy(sys.argv[1] + "-wal", sys.argv[2] + "-wal")
c.close()
PY
before=$(cat "$WORK/fwalcopy.db" "$WORK/fwalcopy.db-wal" | md5sum)
for cmd in inspect export; do
  extra=""; [ $cmd = export ] && extra="-o $WORK/x.jsonl"
  "$DB" $cmd --db "$WORK/fwalcopy.db" $extra > /dev/null 2> "$WORK/err"
  [ $? -eq 2 ] || fail "$cmd on a foreign WAL-mode file did not exit 2"
  grep -q "not an earc experience database" "$WORK/err" || fail "$cmd on a foreign WAL-mode file: $(cat "$WORK/err")"
  [ "$(cat "$WORK/fwalcopy.db" "$WORK/fwalcopy.db-wal" | md5sum)" = "$before" ] || fail "$cmd: the foreign file or its WAL changed"
done

"$DB" build --db "$WORK/new.db" --count 5 > /dev/null 2>&1 || fail "build"
sql "$WORK/new.db" "pragma user_version = 99"
"$DB" inspect --db "$WORK/new.db" > "$WORK/out" 2> "$WORK/err"
[ $? -eq 2 ] || fail "a newer file was not refused with exit 2"
grep -q "schema version 99 is newer than this program's version" "$WORK/err" || fail "unclear: $(cat "$WORK/err")"

"$DB" build --db "$WORK/ok.db" --count 10 > /dev/null 2>&1 || fail "build"
# Reading our own closed file leaves nothing beside it: no empty -wal and
# 32 KB -shm after each inspect or export (only a read-write connection may
# remove them; these open read-write under query_only). The rows stay.
"$DB" inspect --db "$WORK/ok.db" > /dev/null || fail "inspect of a sound file"
"$DB" export --db "$WORK/ok.db" -o "$WORK/ok.jsonl" > /dev/null || fail "export of a sound file"
leftNothingBeside "$WORK/ok.db" "inspect and export"
"$DB" verify --db "$WORK/ok.db" > "$WORK/out" || fail "verify of a sound file exited $?: $(cat "$WORK/out")"
grep -q "^OK: 10 rows" "$WORK/out" || fail "verify summary: $(cat "$WORK/out")"
sql "$WORK/ok.db" "update experiences set paths = x'00' where id = 3" "update experiences set key = x'0102' where id = 7"
"$DB" verify --db "$WORK/ok.db" > "$WORK/out"
[ $? -eq 1 ] || fail "verify of a damaged file did not exit 1"
grep -q "row 3: path blob" "$WORK/out" || fail "row 3 not named: $(cat "$WORK/out")"
grep -q "row 7: key blob" "$WORK/out" || fail "row 7 not named: $(cat "$WORK/out")"

# Signatures that do not parse, or name robots of another kind or dimension.
"$DB" build --db "$WORK/sig.db" --count 10 > /dev/null 2>&1 || fail "build"
sql "$WORK/sig.db" "update experiences set signature = replace(signature, 'mobile:box:0.6x0.4', 'mobile:disc:-1') where id = 2" \
  "update experiences set signature = replace(signature, 'mobile:box:0.6x0.4', 'arm:links=1:r=0.1:limits=-1/1') where id = 5" \
  "update experiences set signature = signature || '|mobile:disc:r=0.3' where id = 8"
"$DB" verify --db "$WORK/sig.db" > "$WORK/out"
[ $? -eq 1 ] || fail "verify passed bad signatures: $(cat "$WORK/out")"
grep -q 'row 2: signature: robot 0: "mobile:disc:-1" is not a geometry signature' "$WORK/out" || fail "row 2 not named: $(cat "$WORK/out")"
grep -q 'row 5: signature: robot 0: .* is an arm, in a mobile class' "$WORK/out" || fail "row 5 not named: $(cat "$WORK/out")"
grep -q 'row 8: signature: names [0-9]* robots, expected' "$WORK/out" || fail "row 8 not named: $(cat "$WORK/out")"

"$DB" verify --db "$WORK/missing.db" > /dev/null 2>&1
[ $? -eq 2 ] || fail "verify of a missing file did not exit 2"
echo "ok"
