#!/bin/bash
# Hostile database and import files: every command that reads one either
# works or exits 2 with one line on stderr naming the file and what is wrong
# (verify may instead list problems and exit 1); never a crash, a signal or
# a screen of text; an import with any bad row changes nothing.
#   missing and 0-byte files (one wording each for every command that only
#   reads), truncated database, truncated WAL, foreign SQLite file, newer schema,
#   import sources with bad rows (JSON: wrong dimension, NaN, a signature
#   that does not parse or names another kind of robot, a state no robot
#   could take; SQLite: path blob with a wrong header or length, NaN in a
#   blob, wrong key length, a state no robot could take), a database
#   holding such states (verify lists them, a plan skips them and solves),
#   and a seeded loop that flips random bytes of a real database.
# EARC_HOSTILE_FLIPS sets the loop's rounds (default 15; the unit test
# test_store_hostile flips 120 more in-process).
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
needPython
needBuilt earc-db earc-plan
SCEN="$SRC/tests/data/scenarios/swap-discs.json"
sql() { "$PY" -c 'import sqlite3,sys
c = sqlite3.connect(sys.argv[1])
for s in sys.argv[2:]: c.execute(s)
c.commit()' "$@"; }
rows() { "$PY" -c 'import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute("select count(*) from experiences").fetchone()[0])' "$1"; }

# run NAME FILE CMD...: runs CMD with stdout/stderr in $WORK/out, $WORK/err; sets $code.
run() { "${@:3}" > "$WORK/out" 2> "$WORK/err"; code=$?; }
# refused CASE FILE PATTERN: the last command exited 2 with one stderr line
# that names FILE and matches PATTERN (grep -E).
refused() {
  [ $code -eq 2 ] || fail "$1: exit $code, expected 2: $(head -c 400 "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "$1: stderr is not one line: $(head -c 800 "$WORK/err")"
  grep -qF "$2" "$WORK/err" || fail "$1: message does not name $2: $(cat "$WORK/err")"
  grep -qE "$3" "$WORK/err" || fail "$1: message does not say /$3/: $(cat "$WORK/err")"
}
# every_command CASE FILE PATTERN: inspect, verify, export, import FILE as a
# source, and plan with FILE as the database, each refuse it; FILE unchanged.
every_command() {
  local name=$1 file=$2 pattern=$3 before
  before=$(md5sum < "$file")
  run "$name" "$file" "$DB" inspect --db "$file"; refused "$name: inspect" "$file" "$pattern"
  run "$name" "$file" "$DB" verify --db "$file"; refused "$name: verify" "$file" "$pattern"
  run "$name" "$file" "$DB" export --db "$file" -o "$WORK/x.jsonl"; refused "$name: export" "$file" "$pattern"
  [ -e "$WORK/x.jsonl" ] && fail "$name: export wrote a file"
  rm -f "$WORK/target.db"*
  run "$name" "$file" "$DB" import --db "$WORK/target.db" "$file"; refused "$name: import" "$file" "$pattern"
  [ -e "$WORK/target.db" ] && fail "$name: a refused import made its target"
  run "$name" "$file" "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$file"
  refused "$name: plan" "$file" "$pattern"
  [ "$(md5sum < "$file")" = "$before" ] || fail "$name: the file was modified"
  rm -f "$file-wal" "$file-shm"
}

"$DB" build --db "$WORK/good.db" --scenario "$SCEN" --count 24 --seed 3 --threads 1 > /dev/null 2>&1 || fail "build"
sql "$WORK/good.db" "pragma wal_checkpoint(truncate)"
size=$(stat -c %s "$WORK/good.db")

# --- Truncated database: half the file, and less than one page.
head -c $((size / 2)) "$WORK/good.db" > "$WORK/half.db"
every_command "truncated to half" "$WORK/half.db" "damaged database file .truncated: [0-9]+ bytes, its header says [0-9]+."
head -c 1000 "$WORK/good.db" > "$WORK/stub.db"
every_command "truncated to 1000 bytes" "$WORK/stub.db" "damaged database file|not a SQLite database"

# --- Foreign SQLite file and a file that is no database at all.
sql "$WORK/foreign.db" "create table photos (id integer primary key, data blob)" "insert into photos values (1, x'00')"
every_command "foreign SQLite file" "$WORK/foreign.db" "not an earc experience database \(application_id 0x00000000"
head -c 5000 /dev/urandom > "$WORK/noise.db"
every_command "random bytes" "$WORK/noise.db" "not a SQLite database|not an earc experience database or export"

# --- A FIFO or a device as the database: refused before SQLite opens it
# (it would hang reading a FIFO, and write a journal beside /dev/null).
mkfifo "$WORK/fifo.db"
for cmd in "inspect --db" "verify --db" "export -o $WORK/x.jsonl --db" "build --count 1 -q --db" "import $WORK/good.db --db"; do
  run "fifo" "$WORK/fifo.db" timeout 20 $DB $cmd "$WORK/fifo.db"
  refused "a FIFO: $cmd" "$WORK/fifo.db" "not a regular file"
done
run "fifo" "$WORK/fifo.db" timeout 20 "$DB" import --db "$WORK/target.db" "$WORK/fifo.db"
refused "a FIFO as an import source" "$WORK/fifo.db" "not a regular file"
run "null" /dev/null timeout 20 "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db /dev/null
refused "/dev/null as the database" /dev/null "not a regular file"
[ -e /dev/null-journal ] && fail "a journal was written beside /dev/null"
rm -f "$WORK/target.db"*

# --- Newer schema: refused naming both versions, nothing written.
cp "$WORK/good.db" "$WORK/newer.db"
sql "$WORK/newer.db" "pragma user_version = 99"
every_command "newer schema" "$WORK/newer.db" "schema version 99 is newer than this program's version"
rm -f "$WORK/t.db"*
"$DB" import --db "$WORK/t.db" "$WORK/good.db" > /dev/null || fail "import into a fresh file"
cp "$WORK/newer.db" "$WORK/newer-target.db"
before=$(md5sum < "$WORK/newer-target.db")
run "newer target" "$WORK/newer-target.db" "$DB" import --db "$WORK/newer-target.db" "$WORK/good.db"
refused "import into a newer file" "$WORK/newer-target.db" "schema version 99 is newer"
[ "$(md5sum < "$WORK/newer-target.db")" = "$before" ] || fail "import modified a newer file"

# writers_refuse CASE FILE PATTERN: build into FILE, import into it, curate
# it in place and into a copy each refuse it (exit 2, one line naming FILE
# and matching PATTERN); FILE unchanged, no copy made.
writers_refuse() {
  local name=$1 file=$2 pattern=$3 before
  before=$(md5sum < "$file")
  rm -f "$WORK/copy.db"*
  run "$name" "$file" "$DB" build --db "$file" --count 2 --threads 1 -q; refused "$name: build" "$file" "$pattern"
  run "$name" "$file" "$DB" import --db "$file" "$WORK/good.db"; refused "$name: import into it" "$file" "$pattern"
  run "$name" "$file" "$DB" curate --db "$file"; refused "$name: curate" "$file" "$pattern"
  run "$name" "$file" "$DB" curate --db "$file" -o "$WORK/copy.db"; refused "$name: curate -o" "$file" "$pattern"
  [ -e "$WORK/copy.db" ] && fail "$name: curate -o made a copy"
  [ "$(md5sum < "$file")" = "$before" ] || fail "$name: the file was modified"
  rm -f "$file-wal" "$file-shm"
}

# --- A file format byte SQLite never writes in the header (18, the write
# version: 233): SQLite opened such a file read-only, and a plan or a
# build failed only at its first write, after its work. Every command
# refuses it at open, naming the byte and its value.
cp "$WORK/good.db" "$WORK/format.db"
printf '\351' | dd of="$WORK/format.db" bs=1 seek=18 conv=notrunc 2> /dev/null
pattern="damaged database file \(SQLite header byte 18, the file format write version, is 233; SQLite writes 1 or 2 there, earc 2\)"
every_command "header byte 18" "$WORK/format.db" "$pattern"
writers_refuse "header byte 18" "$WORK/format.db" "$pattern"

# --- An index entry that no longer matches its row (one bit flipped in an
# index leaf page): quick_check, which every open runs, passes it; verify's
# integrity_check names it. build, import and curate would write into the
# damaged file and add to the damage (curate -o would copy it): they run
# integrity_check first and refuse the file.
cp "$WORK/good.db" "$WORK/stale.db"
"$PY" - "$WORK/stale.db" <<'EOF' || fail "making a stale index entry"
import sqlite3, sys
path = sys.argv[1]
c = sqlite3.connect(path)
key = c.execute("select key from experiences where id = 3").fetchone()[0]
page = c.execute("pragma page_size").fetchone()[0]
c.close()
b = bytearray(open(path, "rb").read())
at = b.find(key)
while at >= 0 and b[at // page * page] != 0x0a:  # the copy in an index leaf page
    at = b.find(key, at + 1)
assert at >= 0, "row 3's key is in no index leaf page"
b[at + len(key) - 1] ^= 1
open(path, "wb").write(b)
c = sqlite3.connect(path)
assert c.execute("pragma quick_check").fetchall() == [("ok",)], "quick_check sees the damage"
assert c.execute("pragma integrity_check").fetchall() == [("row 3 missing from index experiences_keys",)]
c.close()
EOF
writers_refuse "stale index entry" "$WORK/stale.db" \
  "damaged database file \(integrity_check: row 3 missing from index experiences_keys\); restore a copy"
run "stale index entry" x "$DB" verify --db "$WORK/stale.db"
[ $code -eq 1 ] && grep -q "^FAIL: integrity_check: row 3 missing from index experiences_keys$" "$WORK/out" \
  || fail "stale index entry: verify exit $code: $(cat "$WORK/out" "$WORK/err")"

# --- A column of the schema dropped (an edited file): one line naming it,
# no SQL text; verify lists it as a problem (exit 1).
cp "$WORK/good.db" "$WORK/no-cost.db"
sql "$WORK/no-cost.db" "alter table experiences drop column cost"
pattern="damaged database file \(no such column: cost; its schema version has it\)$"
run "no column" "$WORK/no-cost.db" "$DB" inspect --db "$WORK/no-cost.db"; refused "no column: inspect" "$WORK/no-cost.db" "$pattern"
run "no column" "$WORK/no-cost.db" "$DB" export --db "$WORK/no-cost.db" -o "$WORK/x.jsonl"
refused "no column: export" "$WORK/no-cost.db" "$pattern"
run "no column" "$WORK/no-cost.db" "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/no-cost.db"
refused "no column: plan" "$WORK/no-cost.db" "$pattern"
run "no column" "$WORK/no-cost.db" "$DB" verify --db "$WORK/no-cost.db"
[ $code -eq 1 ] && grep -qE "$pattern" "$WORK/out" || fail "no column: verify exit $code: $(cat "$WORK/out" "$WORK/err")"

# --- A missing file and a 0-byte file: every command that only reads says
# the same about each (SQLite would take a 0-byte file for an empty
# database); commands that write make a 0-byte file a database.
# read_only_commands CASE FILE PATTERN
read_only_commands() {
  local name=$1 file=$2 pattern=$3
  rm -f "$WORK/target.db"* "$WORK/copy.db"*
  run "$name" "$file" "$DB" inspect --db "$file"; refused "$name: inspect" "$file" "$pattern"
  run "$name" "$file" "$DB" verify --db "$file"; refused "$name: verify" "$file" "$pattern"
  run "$name" "$file" "$DB" export --db "$file" -o "$WORK/x.jsonl"; refused "$name: export" "$file" "$pattern"
  run "$name" "$file" "$DB" import --db "$WORK/target.db" "$file"; refused "$name: import" "$file" "$pattern"
  [ -e "$WORK/target.db" ] && fail "$name: a refused import made its target"
  run "$name" "$file" "$DB" curate --db "$file" -o "$WORK/copy.db"; refused "$name: curate -o" "$file" "$pattern"
  run "$name" "$file" "$DB" curate --db "$WORK/good.db" --merge "$file" -o "$WORK/copy.db"
  refused "$name: curate --merge" "$file" "$pattern"
  [ -e "$WORK/x.jsonl" ] || [ -e "$WORK/copy.db" ] && fail "$name: a refused command wrote its output"
  return 0
}
read_only_commands "missing file" "$WORK/missing.db" "^earc-db: error: $WORK/missing.db: no such file\$"
run "missing file" x "$DB" curate --db "$WORK/missing.db"; refused "missing file: curate" "$WORK/missing.db" "no such file\$"
[ -e "$WORK/missing.db" ] && fail "curate made a missing database"
: > "$WORK/zero.db"
read_only_commands "0-byte file" "$WORK/zero.db" \
  "^earc-db: error: $WORK/zero.db: empty file \(0 bytes\), not an earc database yet\$"
[ -s "$WORK/zero.db" ] && fail "a read-only command wrote into the 0-byte file"
"$DB" curate --db "$WORK/zero.db" > /dev/null || fail "curate in place of a 0-byte file"
: > "$WORK/zero.db"
"$DB" import --db "$WORK/zero.db" "$WORK/good.db" > /dev/null || fail "import into a 0-byte file"
[ "$(rows "$WORK/zero.db")" -eq 24 ] || fail "import into a 0-byte file: not 24 rows"

# --- Truncated WAL: committed transactions in whole frames survive, a torn
# last frame is ignored; every command works.
cp "$WORK/good.db" "$WORK/wal.db"
"$PY" - "$WORK/wal.db" "$WORK/walcopy.db" <<'EOF' || fail "making a WAL"
import shutil, sqlite3, sys
src, dst = sys.argv[1], sys.argv[2]
c = sqlite3.connect(src)
c.execute("pragma wal_autocheckpoint = 0")
rows = c.execute("select kind, robot_count, signature, base_class, key, paths, cost, source, created_at from experiences").fetchall()
for r in rows[:10]:  # ten committed transactions, each its own frames
    c.execute("insert into experiences (kind, robot_count, signature, base_class, key, paths, cost, source, created_at) values (?,?,?,?,?,?,?,?,?)", r)
    c.commit()
shutil.copy(src, dst)
wal = open(src + "-wal", "rb").read()
open(dst + "-wal", "wb").write(wal[: len(wal) - 3000])  # tear the last frames
c.close()
EOF
n=$(rows "$WORK/walcopy.db")
[ "$n" -gt 24 ] && [ "$n" -lt 34 ] || fail "torn WAL: expected some of the ten WAL commits, found $n rows"
run "torn WAL" x "$DB" inspect --db "$WORK/walcopy.db"
[ $code -eq 0 ] || fail "inspect with a torn WAL exited $code: $(cat "$WORK/err")"
grep -q "entries   $n in" "$WORK/out" || fail "inspect with a torn WAL: not $n entries: $(cat "$WORK/out")"
run "torn WAL" x "$DB" verify --db "$WORK/walcopy.db"
[ $code -eq 0 ] || fail "verify with a torn WAL exited $code: $(cat "$WORK/out" "$WORK/err")"
run "torn WAL" x "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/walcopy.db"
[ $code -eq 0 ] || fail "plan with a torn WAL exited $code: $(cat "$WORK/err")"

# --- Import sources with bad rows: JSON export lines and SQLite rows. Each
# refused naming the file and the row, and the target keeps its rows.
"$DB" export --db "$WORK/good.db" -o "$WORK/good.jsonl" > /dev/null || fail "export"
rm -f "$WORK/target.db"*
"$DB" import --db "$WORK/target.db" "$WORK/good.db" > /dev/null || fail "import into the target"
target_rows=$(rows "$WORK/target.db")
# bad_import CASE FILE PATTERN
bad_import() {
  local before
  before=$(md5sum < "$WORK/target.db")
  run "$1" "$2" "$DB" import --db "$WORK/target.db" "$WORK/good.jsonl" "$2"
  refused "$1" "$2" "$3"
  grep -q "nothing was imported" "$WORK/err" || fail "$1: does not say nothing was imported: $(cat "$WORK/err")"
  [ "$(rows "$WORK/target.db")" -eq "$target_rows" ] || fail "$1: the target's rows changed"
}
"$PY" - "$WORK/good.jsonl" "$WORK" <<'EOF' || fail "making bad exports"
import json, sys
src, work = sys.argv[1], sys.argv[2]
lines = open(src).read().splitlines()
def write(name, line_no, edit):
    out = list(lines)
    row = json.loads(out[line_no])
    edit(row)
    out[line_no] = json.dumps(row)
    open(f"{work}/{name}.jsonl", "w").write("\n".join(out) + "\n")
def dim(r): r["paths"][0][1] = r["paths"][0][1][:2]
def nan(r): r["paths"][1][2][0] = float("nan")   # json.dumps writes NaN
def key(r): r["key"] = r["key"][:-1]
def sig(r): r["signature"] = "|".join(["mobile:disc:-1"] * r["robot_count"])
def sig_kind(r): r["signature"] = "|".join(["arm:links=1:r=0.1:limits=-1/1"] * r["robot_count"])
def far(r):  # start, goal, key and cost as they were
    p = r["paths"][0]
    p[len(p) // 2][0] = p[len(p) // 2][1] = 1e300
write("bad-dimension", 3, dim)
write("bad-nan", 5, nan)
write("bad-key", 2, key)
write("bad-signature", 4, sig)
write("bad-signature-kind", 4, sig_kind)
write("bad-far-state", 2, far)
EOF
bad_import "export with a wrong dimension" "$WORK/bad-dimension.jsonl" "line 4 .*dimension differs"
bad_import "export with a NaN" "$WORK/bad-nan.jsonl" "line 6 .*(NaN|not valid JSON|parse)"
bad_import "export with a short key" "$WORK/bad-key.jsonl" "line 3 .*key has"
bad_import "export with a malformed signature" "$WORK/bad-signature.jsonl" \
  'line 5 \(id [0-9]+\)\.signature: robot 0: "mobile:disc:-1" is not a geometry signature'
bad_import "export with an arm's signature in a mobile row" "$WORK/bad-signature-kind.jsonl" \
  'line 5 \(id [0-9]+\)\.signature: robot 0: .* is an arm, in a mobile class'
bad_import "export with a state no robot could take" "$WORK/bad-far-state.jsonl" \
  'line 3 \(id [0-9]+\): paths\[0\]\[[0-9]+\]: x 1e\+300 is beyond \+-1e\+06 of its subproblem.s centre'
"$PY" - "$WORK/good.db" "$WORK" <<'EOF' || fail "making bad databases"
import shutil, sqlite3, struct, sys
src, work = sys.argv[1], sys.argv[2]
def make(name, sql, *args):
    shutil.copy(src, f"{work}/{name}.db")
    c = sqlite3.connect(f"{work}/{name}.db")
    c.execute(sql, args)
    c.commit()
    c.close()
blob = sqlite3.connect(src).execute("select paths from experiences where id = 5").fetchone()[0]
make("blob-magic", "update experiences set paths = ? where id = 5", b"XPTH" + blob[4:])
make("blob-version", "update experiences set paths = ? where id = 5", blob[:4] + b"\x07\x00" + blob[6:])
make("blob-short", "update experiences set paths = ? where id = 5", blob[:-8])
make("blob-long", "update experiences set paths = ? where id = 5", blob + b"\0" * 8)
nan = struct.pack("<d", float("nan"))
# The first keyframe state of robot 0 (blob version 2: header, keyframe
# count K, K steps, then the states).
at = 20 + 4 * struct.unpack("<I", blob[16:20])[0]
make("blob-nan", "update experiences set paths = ? where id = 5", blob[:at] + nan + blob[at + 8:])
make("key-length", "update experiences set key = substr(key, 1, 16) where id = 7")
make("two-bad", "update experiences set paths = x'00' where id in (2, 9)")
EOF
bad_import "database with a bad blob magic" "$WORK/blob-magic.db" "row 5: path blob: bad magic"
bad_import "database with a bad blob version" "$WORK/blob-version.db" "row 5: path blob: format version 7"
bad_import "database with a short blob" "$WORK/blob-short.db" "row 5: path blob: .*length"
bad_import "database with a long blob" "$WORK/blob-long.db" "row 5: path blob: .*length"
bad_import "database with a NaN in a blob" "$WORK/blob-nan.db" "row 5: path blob: .*not finite"
bad_import "database with a short key" "$WORK/key-length.db" "row 7: key"
bad_import "database with two bad rows" "$WORK/two-bad.db" "row 2: path blob.*1 more bad row \(row 9\)"
# States no robot could take, written with SQL past the store's checks:
# every row's robot 0 at x = y = 1e300 halfway (a version 1 blob, plain
# doubles), the rest of the row as it was.
"$PY" - "$WORK/good.db" "$WORK/good.jsonl" "$WORK/far.db" <<'EOF' || fail "making a database with far states"
import json, shutil, sqlite3, struct, sys
src, export, dst = sys.argv[1:]
shutil.copy(src, dst)
c = sqlite3.connect(dst)
for line in open(export).read().splitlines()[1:]:
    r = json.loads(line)
    p = r["paths"]
    p[0][len(p[0]) // 2][0] = p[0][len(p[0]) // 2][1] = 1e300
    blob = b"EPTH" + struct.pack("<HBBHHI", 1, 8, 0, len(p), len(p[0][0]), len(p[0]))
    blob += b"".join(struct.pack("<d", v) for path in p for q in path for v in q)
    c.execute("update experiences set paths = ? where id = ?", (blob, r["id"]))
c.commit()
EOF
bad_import "database with a state no robot could take" "$WORK/far.db" \
  "row 1: paths\[0\]\[[0-9]+\]: x 1e\+300 is beyond .*23 more bad rows"
# verify lists every such row (exit 1); a plan skips those it retrieves,
# each with a warning naming the file and the row, and solves validly.
run "far states" x "$DB" verify --db "$WORK/far.db"
[ $code -eq 1 ] || fail "far states: verify exit $code: $(head -c 400 "$WORK/out" "$WORK/err")"
[ "$(grep -c 'row [0-9]*: paths\[0\]\[[0-9]*\]: x 1e+300 is beyond' "$WORK/out")" -eq 24 ] ||
  fail "far states: verify does not list the 24 rows: $(head -c 800 "$WORK/out")"
run "far states" x "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/far.db" --no-learn -q
[ $code -eq 0 ] || fail "far states: plan exit $code: $(head -c 400 "$WORK/err")"
grep -qE "^earc: experience store $WORK/far.db: skipping row [0-9]+: paths\[0\]\[[0-9]+\]: x 1e\+300" "$WORK/err" ||
  fail "far states: no warning naming the file and a row: $(head -c 400 "$WORK/err")"
"$PLAN" validate "$SCEN" "$WORK/sol.json" > /dev/null || fail "far states: the plan is not valid"
# Whole-file commands on such a database: export and curate refuse it in one
# line (no warning about the row first), inspect shows it with no warning.
for bad in blob-magic:5 key-length:7; do
  file="$WORK/${bad%%:*}.db" row=${bad##*:}
  rm -f "$WORK/x.jsonl" "$WORK/copy.db"*
  run export "$file" "$DB" export --db "$file" -o "$WORK/x.jsonl"; refused "export of $file" "$file" "row $row: "
  run curate "$file" "$DB" curate --db "$file" -o "$WORK/copy.db" --dedupe 0.01
  refused "curate of $file" "$file" "row $row: "
  [ -e "$WORK/x.jsonl" ] || [ -e "$WORK/copy.db" ] && fail "a refused command wrote its output"
  run inspect "$file" "$DB" inspect --db "$file"
  [ $code -eq 0 ] && [ ! -s "$WORK/err" ] || fail "inspect of $file: exit $code: $(cat "$WORK/err")"
done
# Without --dedupe, curate keeps a damaged row as it was and says so,
# whichever blob is damaged.
for bad in key-length blob-magic two-bad:2; do
  file="$WORK/${bad%%:*}.db" n=1
  [ "$bad" != "${bad#*:}" ] && n=${bad#*:}
  rm -f "$WORK/copy.db"*
  run curate x "$DB" curate --db "$file" -o "$WORK/copy.db"
  [ $code -eq 0 ] && [ ! -s "$WORK/err" ] || fail "curate of $file: exit $code: $(cat "$WORK/err")"
  grep -q "($n damaged, kept as they were; earc-db verify names them)" "$WORK/out" || fail "curate of $file: $(cat "$WORK/out")"
done

# --- Random bytes flipped in a real database, seeded: every command works
# or refuses the file cleanly. Each round damages a fresh copy in 1..8 places
# past the 100-byte header (the header's own checks are covered above).
"$DB" build --db "$WORK/flip-src.db" --scenario "$SCEN" --count 40 --seed 4 --threads 1 > /dev/null 2>&1 || fail "build"
sql "$WORK/flip-src.db" "pragma wal_checkpoint(truncate)"
rounds=${EARC_HOSTILE_FLIPS:-15}
# check_clean ROUND CMD: exit 0, or 2 with one line naming the copy; verify
# may exit 1 with a report ending in FAILED and nothing on stderr; plan may
# exit 1 (not solved) with a solution written; never a signal.
check_clean() {
  local round=$1 what=$2
  [ $code -lt 128 ] || fail "round $round: $what died with signal $((code - 128)): $(head -c 800 "$WORK/err")"
  case $code in
    0) ;;
    2) [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$WORK/f.db" "$WORK/err" \
         || fail "round $round: $what exit 2 without one line naming the file: $(head -c 800 "$WORK/err")" ;;
    1) if [ "$what" = verify ]; then
         tail -1 "$WORK/out" | grep -q "^FAILED: " && [ ! -s "$WORK/err" ] \
           || fail "round $round: verify exit 1 without a report: $(head -c 800 "$WORK/out" "$WORK/err")"
       elif [ "$what" = plan ]; then
         grep -q "^not solved" "$WORK/out" || fail "round $round: plan exit 1: $(head -c 800 "$WORK/err")"
       else
         fail "round $round: $what exit 1: $(head -c 800 "$WORK/err")"
       fi ;;
    *) fail "round $round: $what exit $code: $(head -c 800 "$WORK/err")" ;;
  esac
}
fsize=$(stat -c %s "$WORK/flip-src.db")
refusals=0
for round in $(seq 1 "$rounds"); do
  rm -f "$WORK/f.db"* "$WORK/x.jsonl" "$WORK/target.db"*
  cp "$WORK/flip-src.db" "$WORK/f.db"
  "$PY" - "$WORK/f.db" "$round" "$fsize" <<'EOF'
import random, sys
path, seed, size = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rng = random.Random(seed)
with open(path, "r+b") as f:
    for _ in range(rng.randint(1, 8)):
        at = rng.randrange(100, size)
        f.seek(at)
        b = f.read(1)[0]
        f.seek(at)
        f.write(bytes([b ^ (1 << rng.randrange(8))]))
EOF
  run $round x "$DB" inspect --db "$WORK/f.db"; check_clean $round inspect
  [ $code -eq 2 ] && refusals=$((refusals + 1))
  run $round x "$DB" verify --db "$WORK/f.db"; check_clean $round verify
  run $round x "$DB" export --db "$WORK/f.db" -o "$WORK/x.jsonl"; check_clean $round export
  run $round x "$DB" import --db "$WORK/target.db" "$WORK/f.db"; check_clean $round import
  [ $code -eq 0 ] || [ ! -e "$WORK/target.db" ] || [ "$(rows "$WORK/target.db")" -eq 0 ] \
    || fail "round $round: a refused import left rows in the target"
  run $round x "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/f.db" --time-limit 20
  check_clean $round plan
done
echo "ok: $rounds flip rounds, $refusals refused by inspect"
