#!/bin/bash
# Export then import gives the same rows (every number bit for bit); an
# import with one bad row anywhere applies nothing and names the row; a
# database can be imported directly and merged by curate.
set -u
BUILD=$1
DB="$BUILD/earc-db"
PY=/usr/bin/python3
[ -x "$PY" ] || { echo "skipped: no $PY"; exit 77; }
[ -x "$DB" ] || { echo "FAIL: earc-db not built in $BUILD"; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
count() { "$PY" -c 'import sqlite3,sys; print(sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute("select count(*) from experiences").fetchone()[0])' "$1"; }

"$DB" build --db "$WORK/a.db" --count 30 --seed 3 > /dev/null 2>&1 || fail "build mobile"
"$DB" build --db "$WORK/a.db" --kind arms --count 10 --seed 3 > /dev/null 2>&1 || fail "build arms into the same file"
"$DB" export --db "$WORK/a.db" -o "$WORK/a.jsonl" > "$WORK/out" || fail "export exited $?"
grep -q "exported 40 rows" "$WORK/out" || fail "export summary: $(cat "$WORK/out")"
head -1 "$WORK/a.jsonl" | grep -q '"format":"earc.experiences.v1"' || fail "no format header"

# Round trip: the re-export equals the export line for line (ids included:
# the new file numbers its rows the same way).
"$DB" import --db "$WORK/b.db" "$WORK/a.jsonl" > "$WORK/out" || fail "import exited $?"
grep -q "imported 40 of 40 rows" "$WORK/out" || fail "import summary: $(cat "$WORK/out")"
"$DB" export --db "$WORK/b.db" -o "$WORK/b.jsonl" > /dev/null || fail "re-export"
cmp -s <(tail -n +2 "$WORK/a.jsonl") <(tail -n +2 "$WORK/b.jsonl") || fail "export -> import -> export changed rows"

# One bad line (a string where a coordinate belongs) in the second of two
# inputs: exit 2, the line named, nothing imported.
"$PY" - "$WORK/a.jsonl" "$WORK/bad.jsonl" <<'PY'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
row = json.loads(lines[7]); row["paths"][1][0][0] = "x"
lines[7] = json.dumps(row)
open(sys.argv[2], "w").write("\n".join(lines) + "\n")
PY
"$DB" import --db "$WORK/c.db" "$WORK/a.jsonl" "$WORK/bad.jsonl" > "$WORK/out" 2> "$WORK/err"
code=$?
[ $code -eq 2 ] || fail "bad import exited $code, expected 2"
grep -q "bad.jsonl.*line 8" "$WORK/err" || fail "bad line not named: $(cat "$WORK/err")"
[ "$(count "$WORK/c.db")" = 0 ] || fail "a failed import left rows behind"

# A database with a truncated blob, imported directly: exit 2, row id named.
"$PY" -c 'import sqlite3,sys
d = sqlite3.connect(sys.argv[2]); sqlite3.connect(sys.argv[1]).backup(d)  # the backup API, never cp
d.execute("update experiences set paths = substr(paths, 1, 20) where id = 12"); d.commit()' "$WORK/a.db" "$WORK/d.db"
"$DB" import --db "$WORK/e.db" "$WORK/d.db" > "$WORK/out" 2> "$WORK/err"
[ $? -eq 2 ] || fail "import of a damaged database did not exit 2"
grep -q "row 12" "$WORK/err" || fail "damaged row not named: $(cat "$WORK/err")"
[ "$(count "$WORK/e.db")" = 0 ] || fail "a failed import left rows behind"

# Merge with curate into a copy: the original keeps its rows.
"$DB" curate --db "$WORK/b.db" --merge "$WORK/a.db" --dedupe 0 -o "$WORK/merged.db" > "$WORK/out" || fail "curate exited $?"
grep -q "0 merged" "$WORK/out" || fail "identical rows were merged again: $(cat "$WORK/out")"
[ "$(count "$WORK/merged.db")" = 40 ] || fail "merged copy has $(count "$WORK/merged.db") rows"
"$DB" verify --db "$WORK/merged.db" > /dev/null || fail "merged copy does not verify"
echo "ok"
