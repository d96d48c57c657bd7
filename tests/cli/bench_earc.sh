#!/bin/bash
# label: bench
# E-ARC through the benchmark: missing E-ARC databases are built with
# `earc-db build` (timed and recorded), and the earc trials plan with them,
# paired with ARC's trials by seed. Skipped (77) without earc-db or
# /usr/bin/python3. (Label bench: its trials run under an address-space
# limit, which AddressSanitizer cannot live with.)
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
[ -x "$BUILD/earc-db" ] || { echo "skipped: earc-db not built in $BUILD"; exit 77; }
needBuilt earc-bench earc-plan
fail() { echo "FAIL: $*"; tail -n 20 "$WORK/run.out" "$WORK/run.err"; exit 1; }

"$BENCH" run --suites mobile,arms --robots 2 --methods earc,arc --trials 2 --time-limit 10 --seed 9 \
  --earc-db-count 30 --results "$WORK/r.sqlite" > "$WORK/run.out" 2> "$WORK/run.err" || fail "run exited $?"
grep -q "^### E-ARC / ARC planning time, paired by seed" "$WORK/run.out" || fail "no paired ratio in the table"
"$PY" - "$WORK/r.sqlite" <<'PYEOF' || fail "results"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
rows = con.execute("SELECT suite, method, success, db_hits, failure FROM trials").fetchall()
assert len(rows) == 8, rows
for suite, method, success, hits, failure in rows:
    assert success == 1, (suite, method, failure)
    assert (hits is not None) == (method == "earc"), (method, hits)
dbs = con.execute("SELECT method, suite, robots, construction_time_s, entries, problems FROM databases ORDER BY suite").fetchall()
assert [(d[0], d[1], d[2]) for d in dbs] == [("earc", "arms", 0), ("earc", "mobile", 0)], dbs
assert all(d[3] > 0 and d[4] > 0 and d[5] == 30 for d in dbs), dbs
PYEOF
# A database that was given is recorded with the entries counted when it
# was checked, and without a construction time.
"$BENCH" run --suites mobile --robots 2 --methods earc --trials 1 --time-limit 10 --seed 9 \
  --db-mobile "$WORK/r.sqlite.work/earc-mobile-p30-s9.sqlite" --results "$WORK/given.sqlite" > "$WORK/run.out" 2> "$WORK/run.err" ||
  fail "run with a given database exited $?"
"$PY" - "$WORK/r.sqlite" "$WORK/given.sqlite" <<'PYEOF' || fail "given database"
import sqlite3, sys
built = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute(
    "SELECT entries FROM databases WHERE suite = 'mobile'").fetchone()[0]
rows = sqlite3.connect("file:%s?mode=ro" % sys.argv[2], uri=True).execute(
    "SELECT suite, construction_time_s, entries FROM databases").fetchall()
assert rows == [("mobile", None, built)], (rows, built)
PYEOF
# The hit count is the database's answers, retrieved or repaired (what
# the table's hit rate and the plan's summary line count), not db_hits
# alone: a stand-in planner reports 2 retrieved and 1 repaired.
cat > "$WORK/hits-plan" <<FAKE
#!/bin/bash
"$BUILD/earc-plan" "\$@" || exit \$?
[ "\$1" = plan ] || exit 0
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
exec "$PY" -c 'import json, sys
d = json.load(open(sys.argv[1]))
d["stats"].update(db_hits=2, db_repairs=1, subproblems_by_solver={"database": 2, "repair": 1, "decoupled": 4})
json.dump(d, open(sys.argv[1], "w"))' "\$out"
FAKE
chmod +x "$WORK/hits-plan"
"$BENCH" run --suites mobile --robots 2 --methods earc --trials 1 --time-limit 10 --seed 9 --plan-program "$WORK/hits-plan" \
  --db-mobile "$WORK/r.sqlite.work/earc-mobile-p30-s9.sqlite" --results "$WORK/hits.sqlite" > "$WORK/run.out" 2> "$WORK/run.err" ||
  fail "run with the stand-in planner exited $?"
got=$("$PY" -c 'import sqlite3, sys
print(sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute("SELECT db_hits FROM trials").fetchone()[0])' "$WORK/hits.sqlite")
[ "$got" = 3 ] || fail "db_hits recorded $got for 2 retrieved and 1 repaired answers"
echo "ok: E-ARC databases built and used"
