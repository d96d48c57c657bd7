#!/bin/bash
# Export then import gives the same rows (every number bit for bit), and
# importing them again adds none; an
# import with one bad row anywhere applies nothing and names the row; a
# database can be imported directly and merged by curate; inspect prints
# extreme numbers in bounded form, export keeps them exactly; a file with
# older path blobs is compacted to the same rows; rows name their build.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
DB="$BUILD/earc-db"
needPython
needBuilt earc-db
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
# Importing the same export again adds nothing: the rows are there.
"$DB" import --db "$WORK/twice.db" "$WORK/a.jsonl" > /dev/null || fail "first import into twice.db exited $?"
"$DB" import --db "$WORK/twice.db" "$WORK/a.jsonl" > "$WORK/out" || fail "second import exited $?"
grep -q "imported 0 of 40 rows into $WORK/twice.db (40 already in it)" "$WORK/out" || fail "second import said: $(cat "$WORK/out")"
[ "$(count "$WORK/twice.db")" = 40 ] || fail "a second import of the same rows changed the row count to $(count "$WORK/twice.db")"

# Every row names the build that made it, as --version does; inspect counts
# rows per build; curate --drop-made-by deletes one build's rows (in a copy).
build=$("$DB" --version | awk '{print $2}')
"$PY" - "$WORK/a.jsonl" "$build" <<'PY' || fail "exported rows do not name the build $build"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]).read().splitlines()[1:]]
sys.exit(not rows or any(r["made_by"] != sys.argv[2] for r in rows))
PY
"$DB" inspect --db "$WORK/b.db" > "$WORK/out" || fail "inspect exited $?"
grep -q "^made by   $build (40)$" "$WORK/out" || fail "inspect: no made-by line: $(cat "$WORK/out")"
# ...and its history says who created the file and what the import added.
grep -q "  create  by $build: schema " "$WORK/out" || fail "inspect: no creation in the history: $(cat "$WORK/out")"
grep -q "  import  by $build, +40 -0 rows: from $WORK/a.jsonl$" "$WORK/out" ||
  fail "inspect: no import in the history: $(cat "$WORK/out")"
# inspect --json: the same numbers for scripts.
"$DB" inspect --db "$WORK/b.db" --json > "$WORK/out.json" || fail "inspect --json exited $?"
"$PY" - "$WORK/out.json" "$build" <<'PY' || fail "inspect --json: $(head -c 600 "$WORK/out.json")"
import json, sys
j = json.load(open(sys.argv[1]))
ok = (j["format"] == "earc.inspect.v1" and j["entries"] == 40 and sum(c["entries"] for c in j["classes"]) == 40
      and j["builds"] == [{"made_by": sys.argv[2], "rows": 40}]
      and [(l["operation"], l["rows_added"]) for l in j["history"]["lines"]] == [("create", 0), ("import", 40)]
      and len(j["samples"]) == 3)
sys.exit(not ok)
PY
"$DB" curate --db "$WORK/b.db" --drop-made-by "$build" -o "$WORK/none.db" > "$WORK/out" || fail "curate --drop-made-by exited $?"
grep -q "40 of the builds named removed, 0 rows after" "$WORK/out" || fail "curate --drop-made-by said: $(cat "$WORK/out")"
[ "$(count "$WORK/b.db")" = 40 ] || fail "curate -o changed the original"
# A build name that matches no row (a typo) is said, with the builds the
# rows do name; nothing is removed.
"$DB" curate --db "$WORK/b.db" --drop-made-by "${build%?}" -o "$WORK/typo.db" -q > "$WORK/out" 2> "$WORK/err" ||
  fail "curate --drop-made-by with a typo exited $?"
grep -qF "warning: --drop-made-by \"${build%?}\": no row of $WORK/typo.db was made by such a build; its rows name $build (40 rows)" \
  "$WORK/err" || fail "curate --drop-made-by with a typo said: $(cat "$WORK/err")"
[ "$(count "$WORK/typo.db")" = 40 ] || fail "curate --drop-made-by with a typo removed rows"
"$DB" inspect --db "$WORK/none.db" --history 1 > "$WORK/out" || fail "inspect of the curated copy exited $?"
grep -q "^history (last 1 of 3):$" "$WORK/out" || fail "inspect --history 1: $(cat "$WORK/out")"
grep -q "  curate  by $build, +0 -40 rows: copy of " "$WORK/out" || fail "inspect: no curate in the copy's history: $(cat "$WORK/out")"
"$DB" inspect --db "$WORK/none.db" --json > "$WORK/out.json" || fail "inspect --json of the curated copy exited $?"
"$PY" - "$WORK/out.json" "$WORK/b.db" "$build" <<'PY' || fail "the curate's history line: $(head -c 2000 "$WORK/out.json")"
import json, sys
line = json.load(open(sys.argv[1]))["history"]["lines"][-1]
sys.exit(not (line["operation"] == "curate" and line["rows_removed"] == 40 and
              line["detail"] == 'copy of %s: --drop-made-by "%s"' % (sys.argv[2], sys.argv[3])))
PY

# -q: the same work and nothing printed, as build and plan do with -q.
"$DB" export --db "$WORK/a.db" -o "$WORK/q.jsonl" -q > "$WORK/out" 2>&1 || fail "export -q exited $?"
"$DB" import --db "$WORK/q.db" "$WORK/q.jsonl" -q >> "$WORK/out" 2>&1 || fail "import -q exited $?"
"$DB" curate --db "$WORK/q.db" -o "$WORK/q2.db" --dedupe 0 -q >> "$WORK/out" 2>&1 || fail "curate -q exited $?"
[ -s "$WORK/out" ] && fail "-q printed: $(cat "$WORK/out")"
cmp -s "$WORK/a.jsonl" "$WORK/q.jsonl" || fail "export -q wrote another file"
[ "$(count "$WORK/q2.db")" = 40 ] || fail "import -q then curate -q: $(count "$WORK/q2.db") rows, expected 40"

# Extreme numbers a row may hold (a solve time of 1e308 s): inspect prints
# them in bounded form, export keeps every digit. A cost of 1e308 is refused
# (not the paths' length) in a message of normal length.
"$PY" - "$WORK/a.jsonl" "$WORK/big.jsonl" "$WORK/bigcost.jsonl" <<'PY'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
header = json.loads(lines[0]); header["rows"] = 1
row = json.loads(lines[1]); row["solve_time_s"] = 1e308
open(sys.argv[2], "w").write(json.dumps(header) + "\n" + json.dumps(row) + "\n")
row["solve_time_s"] = 0.5; row["cost"] = 1e308
open(sys.argv[3], "w").write(json.dumps(header) + "\n" + json.dumps(row) + "\n")
PY
"$DB" import --db "$WORK/big.db" "$WORK/big.jsonl" > /dev/null || fail "import of a 1e308 solve time"
"$DB" inspect --db "$WORK/big.db" > "$WORK/out" || fail "inspect exited $?"
grep -q "solve 1e+308 s" "$WORK/out" || fail "inspect: no bounded solve time: $(cat "$WORK/out")"
[ "$(awk 'length > 200' "$WORK/out" | wc -l)" -eq 0 ] || fail "inspect printed a line over 200 characters: $(cat "$WORK/out")"
"$DB" export --db "$WORK/big.db" -o "$WORK/big2.jsonl" > /dev/null || fail "export of a 1e308 solve time"
"$PY" -c 'import json,sys; r = json.loads(open(sys.argv[1]).read().splitlines()[1]); sys.exit(r["solve_time_s"] != 1e308)' \
  "$WORK/big2.jsonl" || fail "export changed the 1e308 solve time"
"$DB" import --db "$WORK/bigcost.db" "$WORK/bigcost.jsonl" > /dev/null 2> "$WORK/err"
[ $? -eq 2 ] || fail "a cost of 1e308 was imported"
grep -q "cost 1e+308 is not the paths' length" "$WORK/err" && [ "$(wc -c < "$WORK/err")" -lt 300 ] \
  || fail "unclear or overlong refusal of a 1e308 cost: $(head -c 600 "$WORK/err")"

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
[ -e "$WORK/c.db" ] && fail "a failed import made its target"

# A database with a truncated blob, imported directly: exit 2, row id named.
"$PY" -c 'import sqlite3,sys
d = sqlite3.connect(sys.argv[2]); sqlite3.connect(sys.argv[1]).backup(d)  # the backup API, never cp
d.execute("update experiences set paths = substr(paths, 1, 20) where id = 12"); d.commit()' "$WORK/a.db" "$WORK/d.db"
"$DB" import --db "$WORK/e.db" "$WORK/d.db" > "$WORK/out" 2> "$WORK/err"
[ $? -eq 2 ] || fail "import of a damaged database did not exit 2"
grep -q "row 12" "$WORK/err" || fail "damaged row not named: $(cat "$WORK/err")"
[ -e "$WORK/e.db" ] && fail "a failed import made its target"

# Merge with curate into a copy: the original keeps its rows.
"$DB" curate --db "$WORK/b.db" --merge "$WORK/a.db" --dedupe 0 -o "$WORK/merged.db" > "$WORK/out" || fail "curate exited $?"
grep -q "0 merged" "$WORK/out" || fail "identical rows were merged again: $(cat "$WORK/out")"
[ "$(count "$WORK/merged.db")" = 40 ] || fail "merged copy has $(count "$WORK/merged.db") rows"
"$DB" verify --db "$WORK/merged.db" > /dev/null || fail "merged copy does not verify"

# A database an earlier earc wrote (path blob format version 1, the fuzz
# seed tiny.db): inspect says so, curate --compact rewrites every blob, and
# the rows export exactly as before.
"$PY" -c 'import sqlite3,sys; sqlite3.connect(sys.argv[1]).backup(sqlite3.connect(sys.argv[2]))' \
  "$SRC/tests/fuzz/corpus/import/tiny.db" "$WORK/old.db"
"$DB" inspect --db "$WORK/old.db" > "$WORK/out" || fail "inspect of the old file exited $?"
grep -q "4 path blobs in an older format, without a checksum (earc-db curate --compact rewrites them)" "$WORK/out" ||
  fail "inspect does not name the older blobs: $(cat "$WORK/out")"
"$DB" export --db "$WORK/old.db" -o "$WORK/old.jsonl" > /dev/null || fail "export of the old file exited $?"
"$DB" curate --db "$WORK/old.db" --compact > "$WORK/out" || fail "curate --compact exited $?"
grep -q "4 rows after, 4 path blobs rewritten in the current format" "$WORK/out" || fail "compact said: $(cat "$WORK/out")"
"$DB" inspect --db "$WORK/old.db" > "$WORK/out" || fail "inspect after compact exited $?"
grep -q "older" "$WORK/out" && fail "blobs still older after compact: $(cat "$WORK/out")"
"$DB" verify --db "$WORK/old.db" > /dev/null || fail "compacted file does not verify"
"$DB" export --db "$WORK/old.db" -o "$WORK/compacted.jsonl" > /dev/null || fail "export after compact exited $?"
# (The header names the schema the file had: curate migrated it.)
cmp -s <(tail -n +2 "$WORK/old.jsonl") <(tail -n +2 "$WORK/compacted.jsonl") || fail "compact changed the rows"
echo "ok"
