#!/bin/bash
# earc-plan plan --method earc --db FILE and the file:
# - learning (the default) counts the session and writes what it learned;
# - the summary line says what the database answered and learned;
# - a database for other robots is a warning line (E-ARC then plans as ARC);
# - arms of more joints than a stored path holds are planned, not learned;
# - --db-k and --db-repair-max reach the database solver, and
#   --db-max-stretch refuses answers longer than its bound;
# - --no-learn leaves the file exactly as it was (no session count, no usage
#   counters, nothing beside it) and refuses a missing file instead of
#   creating one;
# - a file whose damage only quick_check sees (opening reads the key index,
#   not the table) is refused with one line and exit 2, no solution written
#   and the file unchanged, although its quick_check runs while planning.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-db earc-plan
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
SCEN="$SRC/tests/data/scenarios/swap-discs.json"
F="$WORK/e.db"
q() { "$PY" -c 'import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute(sys.argv[2]).fetchone()[0])' "$@"; }
stat_of() { "$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"][sys.argv[2]])' "$@"; }

"$DB" build --db "$F" --scenario "$SCEN" --count 40 --seed 3 --threads 1 -q || fail "build"
sessions=$(q "$F" "select value from store_meta where name = 'sessions'")

# A database for other robots: one warning line, and the plan goes on.
"$DB" build --db "$WORK/boxes.db" --size 0.9x0.5 --count 20 --seed 3 --threads 1 -q || fail "build boxes"
"$PLAN" plan "$SCEN" -o "$WORK/w.json" --method earc --db "$WORK/boxes.db" --no-learn -q 2> "$WORK/w.err" ||
  fail "plan with a database for other robots: exit $?"
grep -q "^earc-plan: warning: $WORK/boxes.db holds [0-9]* experiences, none for these robots (mobile:disc" \
  "$WORK/w.err" || fail "no warning for a database of other robots: $(cat "$WORK/w.err")"
[ "$(wc -l < "$WORK/w.err")" -eq 1 ] || fail "more than the warning: $(cat "$WORK/w.err")"

# Arms of 100 joints: more than a stored path holds a state. E-ARC plans
# them and learns nothing (inserting them ended the plan with an error).
manyLinkArms 100 0.02 > "$WORK/a100.json"
"$PLAN" plan "$WORK/a100.json" -o "$WORK/a100.sol.json" --method earc --db "$WORK/a100.db" --time-limit 20 -q \
  2> "$WORK/a100.err" || fail "E-ARC learning on arms of 100 joints: exit $?: $(cat "$WORK/a100.err")"
[ "$(stat_of "$WORK/a100.sol.json" subproblems)" -gt 0 ] || fail "no subproblem on arms of 100 joints: nothing tested"
[ "$(stat_of "$WORK/a100.sol.json" db_learned)" = 0 ] || fail "learned arms of 100 joints"
# ...and says why: each subproblem it solved from scratch was of a kind no
# class holds.
[ "$(stat_of "$WORK/a100.sol.json" db_learn_unstorable)" -gt 0 ] ||
  fail "arms of 100 joints: no subproblem counted as not storable"

# Learning: one more session, the counters of what was retrieved.
"$PLAN" plan "$SCEN" -o "$WORK/a.json" --method earc --db "$F" --seed 1 -q 2> "$WORK/a.err" || fail "plan: exit $?"
[ -s "$WORK/a.err" ] && fail "a plan with a database for its robots said: $(cat "$WORK/a.err")"
[ "$(stat_of "$WORK/a.json" db_queries)" -gt 0 ] || fail "the plan never asked the database"
[ "$(q "$F" "select value from store_meta where name = 'sessions'")" -eq $((sessions + 1)) ] ||
  fail "a learning plan did not count its session"
[ "$(q "$F" "select sum(retrieved_count) from experiences")" -gt 0 ] || fail "no usage counted while learning"
# A plan on a new file solves from scratch and learns: the file's history
# says who created it and counts what the session learned.
"$PLAN" plan "$SCEN" -o "$WORK/n.json" --method earc --db "$WORK/new.db" --seed 1 -q || fail "plan, new file: exit $?"
learned=$(stat_of "$WORK/n.json" db_learned)
[ "$learned" -gt 0 ] || fail "a plan on an empty database learned nothing"
schema=$(q "$WORK/new.db" "pragma user_version")
[ "$(q "$WORK/new.db" "select group_concat(line, '; ') from (select operation || ' ' || rows_added || ' ' || detail as line from history order by id)")" = \
  "create 0 schema $schema; learn $learned planning session 1" ] || fail "the history does not count what the plan learned"
leftNothingBeside "$F" "a learning plan"
# The summary line says what the database did, as the stats count it.
"$PLAN" plan "$SCEN" -o "$WORK/c.json" --method earc --db "$F" --seed 4 > "$WORK/out" || fail "plan: exit $?"
hits=$(stat_of "$WORK/c.json" db_hits)
repairs=$(stat_of "$WORK/c.json" db_repairs)
solved=$("$PY" -c 'import json,sys; print(sum(json.load(open(sys.argv[1]))["stats"]["subproblems_by_solver"].values()))' "$WORK/c.json")
line="; database answered $((hits + repairs)) of $solved solved subproblems ($repairs by repair)"
line+=", learned $(stat_of "$WORK/c.json" db_learned)"
grep -q "^solved: 2 robots, method earc, .*, sum of costs [0-9.]*$line\$" "$WORK/out" ||
  fail "the summary line does not say what the database did: $(cat "$WORK/out")"
"$PLAN" plan "$SCEN" -o "$WORK/c.json" --method arc --seed 4 > "$WORK/out" || fail "plan (arc): exit $?"
grep -q "database" "$WORK/out" && fail "ARC's summary line speaks of a database: $(cat "$WORK/out")"

# --db-k and --db-repair-max reach the database solver: each failed
# query's trace says how many candidates it read, and with repair off a
# query whose best candidate had one invalid run says it was not repaired.
MOB="$SRC/datasets/mobile-obst-16-s1.json"
"$DB" build --db "$WORK/k.db" --scenario "$MOB" --count 600 --seed 2 -q || fail "build for --db-k"
details() {  # details TRACE: one line per database attempt's detail
  "$PY" -c 'import json, sys
for e in json.load(open(sys.argv[1]))["events"]:
    for a in e.get("attempts", []) if e.get("type") == "subproblem" else []:
        if a["solver"] in ("database", "repair"): print(a["solver"], a.get("detail", "-"))' "$1"
}
for k in 10 1; do
  "$PLAN" plan "$MOB" -o "$WORK/k.json" --method earc --db "$WORK/k.db" --no-learn --seed 1 --db-k $k \
    --trace "$WORK/k.trace" -q || fail "--db-k $k: exit $?"
  details "$WORK/k.trace" > "$WORK/k.details"
  grep -q "^database $k candidates: " "$WORK/k.details" || fail "--db-k $k: no query read $k: $(cat "$WORK/k.details")"
  "$PY" - "$WORK/k.details" $k <<'PY' || fail "--db-k $k: a query read more: $(cat "$WORK/k.details")"
import re, sys
read = [int(m.group(1)) for m in (re.match(r"database (\d+) candidates: ", l) for l in open(sys.argv[1])) if m]
assert max(read) <= int(sys.argv[2]), read
PY
done
"$PLAN" plan "$MOB" -o "$WORK/k.json" --method earc --db "$WORK/k.db" --no-learn --seed 1 --db-repair-max 0 \
  --trace "$WORK/k.trace" -q || fail "--db-repair-max 0: exit $?"
details "$WORK/k.trace" > "$WORK/k.details"
grep -q "fewest invalid runs 1, too many to repair$" "$WORK/k.details" ||
  fail "--db-repair-max 0: no query refused to repair one run: $(cat "$WORK/k.details")"
grep -q "^repair" "$WORK/k.details" && fail "--db-repair-max 0: repaired: $(cat "$WORK/k.details")"
[ "$(stat_of "$WORK/k.json" db_repairs)" -eq 0 ] || fail "--db-repair-max 0: db_repairs is not 0"

# --db-max-stretch: an answer longer than F times its slowest robot's
# straight-motion steps is refused (the trace says by how much), the
# subproblem is planned from scratch, and the plan still solves; by
# default nothing is refused; a bound that is not a number is refused.
"$PLAN" plan "$MOB" -o "$WORK/k.json" --method earc --db "$WORK/k.db" --no-learn --seed 1 -q || fail "plan: exit $?"
[ "$(stat_of "$WORK/k.json" db_refused_too_long)" -eq 0 ] || fail "an answer refused as too long by default"
for bad in nan inf -1; do
  "$PLAN" plan "$MOB" -o "$WORK/k.json" --method earc --db "$WORK/k.db" --no-learn --db-max-stretch=$bad -q \
    > /dev/null 2> "$WORK/err" && fail "--db-max-stretch $bad was taken"
  grep -qF -- "--db-max-stretch" "$WORK/err" || fail "--db-max-stretch $bad: $(cat "$WORK/err")"
done
"$PLAN" plan "$MOB" -o "$WORK/k.json" --method earc --db "$WORK/k.db" --no-learn --seed 1 --db-max-stretch 1.05 \
  --trace "$WORK/k.trace" -q || fail "--db-max-stretch 1.05: exit $?"
details "$WORK/k.trace" > "$WORK/k.details"
"$PY" - "$WORK/k.details" "$(stat_of "$WORK/k.json" db_refused_too_long)" <<'PY' || fail "--db-max-stretch: $(cat "$WORK/k.details")"
import re, sys
refused = [re.search(r"answer (\d+) steps, more than 1.05 x (\d+)$", l) for l in open(sys.argv[1])]
refused = [m for m in refused if m]
assert refused, "nothing refused at 1.05"
assert all(int(m.group(1)) > 1.05 * int(m.group(2)) for m in refused), "refused an answer within the bound"
# The stats count every answer refused; the trace says how each query
# ended, and a query that refused an answer may still repair a candidate
# tried before it and end otherwise, or refuse the repaired answer too.
assert int(sys.argv[2]) >= len(refused), "stats db_refused_too_long %s, trace %d" % (sys.argv[2], len(refused))
PY
"$PLAN" validate "$MOB" "$WORK/k.json" > /dev/null || fail "--db-max-stretch: the plan is not valid"

# --no-learn: the same file, byte for byte.
before=$(md5sum < "$F")
"$PLAN" plan "$SCEN" -o "$WORK/b.json" --method earc --db "$F" --no-learn --seed 2 -q || fail "--no-learn: exit $?"
[ "$(stat_of "$WORK/b.json" db_queries)" -gt 0 ] || fail "--no-learn: the plan never asked the database"
[ "$(stat_of "$WORK/b.json" db_learned)" -eq 0 ] || fail "--no-learn learned"
[ "$(md5sum < "$F")" = "$before" ] || fail "--no-learn changed the database file"
leftNothingBeside "$F" "a --no-learn plan"

# Refusals: exit 2, one line naming the file, nothing made or written.
refused() {  # what, file, expected text, command...
  local what=$1 file=$2 text=$3
  shift 3
  rm -f "$WORK/sol.json"
  "$@" > "$WORK/out" 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "$what: exit $rc, expected 2: $(head -c 400 "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "$what: stderr is not one line: $(cat "$WORK/err")"
  grep -qF -- "$file" "$WORK/err" || fail "$what: message does not name $file: $(cat "$WORK/err")"
  grep -q -- "$text" "$WORK/err" || fail "$what: message lacks '$text': $(cat "$WORK/err")"
  [ -e "$WORK/sol.json" ] && fail "$what: a solution was written"
  return 0
}
refused "missing file with --no-learn" "$WORK/none.db" "no such" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/none.db" --no-learn -q
[ -e "$WORK/none.db" ] && fail "a missing file was created under --no-learn"
refused "--db-k with method arc" "--db-k" "is for method earc" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method arc --db-k 3 -q
refused "--db-max-stretch with method arc" "--db-max-stretch" "is for method earc" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method arc --db-max-stretch 3 -q
refused "--trace with method prioritized" "--trace" "is for methods arc and earc" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method prioritized --trace "$WORK/t.json" -q
[ -e "$WORK/t.json" ] && fail "a refused --trace was written"
"$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); d["robots"]=[]; json.dump(d,open(sys.argv[2],"w"))' "$SCEN" "$WORK/none.json"
refused "a scenario without robots" "$WORK/none.json" "\$.robots: empty: no robots to plan for" \
  "$PLAN" plan "$WORK/none.json" -o "$WORK/sol.json" --method arc -q
refused "--db with method arc" "--db" "is for methods earc and lightning" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method arc --db "$F" -q
for bad in inf nan 0 -1; do
  refused "--time-limit $bad" "--time-limit" "$bad" \
    "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method arc --time-limit $bad -q
done
refused "--db in a missing directory" "$WORK/nodir/x.db" "no directory $WORK/nodir" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/nodir/x.db" -q
refused "no --db" "--db" "method earc needs an experience database file (earc-db build makes one" \
  "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc -q

# Damage only quick_check finds: the table's root page is not a b-tree page.
cp "$F" "$WORK/bad.db"
"$PY" - "$WORK/bad.db" <<'PY'
import sqlite3, sys
path = sys.argv[1]
c = sqlite3.connect(path)
c.execute("pragma wal_checkpoint(truncate)")
page = c.execute("pragma page_size").fetchone()[0]
root = c.execute("select rootpage from sqlite_schema where name = 'experiences'").fetchone()[0]
c.close()
with open(path, "r+b") as f:
    f.seek((root - 1) * page)
    f.write(b"\x07")
PY
before=$(md5sum < "$WORK/bad.db")
for mode in learn no-learn; do
  extra=()
  [ $mode = no-learn ] && extra=(--no-learn)
  refused "damaged table page ($mode)" "$WORK/bad.db" "damaged database file" \
    "$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$WORK/bad.db" "${extra[@]}" -q
  [ "$(md5sum < "$WORK/bad.db")" = "$before" ] || fail "damaged table page ($mode): the file was modified"
done
echo "ok"
