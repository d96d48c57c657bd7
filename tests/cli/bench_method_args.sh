#!/bin/bash
# label: bench
# earc-bench run --method-arg METHOD=ARG: ARG reaches every `earc-plan
# plan` of METHOD and no other's; each trial records the arguments it ran
# with (results schema 5), and table, export (CSV and OMPL logs) and plot
# name the method with them. A results file holds one set per method: a
# run resumed with other arguments for a method is refused, naming the
# method and both sets, and so is a file that mixes two (table, export,
# plot_results.py). Bad arguments end in one line and exit status 2 before
# any trial: an unknown method or one not run, an argument earc-bench gives
# the planner itself, and (after its first trial, which is not recorded)
# one the planner refuses. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
failShowsOutput

# The planner, logging the plan commands it is given.
cat > "$WORK/logging-plan" <<FAKE
#!/bin/bash
[ "\$1" = plan ] && echo "\$*" >> "$WORK/plans"
exec "$BUILD/earc-plan" "\$@"
FAKE
chmod +x "$WORK/logging-plan"
touch "$WORK/plans"
RUN=(run --suites mobile --robots 2 --methods arc,prioritized --trials 2 --time-limit 5 --seed 3
     --plan-program "$WORK/logging-plan")
count() { "$PY" -c 'import sqlite3, sys
print(sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute(sys.argv[2]).fetchone()[0])' "$@"; }

# An option and its value as two arguments, in the order given.
"$BENCH" "${RUN[@]}" --results "$WORK/r.sqlite" --method-arg arc=--window --method-arg arc=4 \
  > "$WORK/out" 2> "$WORK/err" || fail "run with --method-arg exited $?"
[ "$(grep -c -- "--method arc .* --window 4\$" "$WORK/plans")" -eq 2 ] ||
  fail "arc's plans did not end with --window 4: $(cat "$WORK/plans")"
[ "$(grep -c -- "--method prioritized " "$WORK/plans")" -eq 2 ] && ! grep -q -- "prioritized.*--window" "$WORK/plans" ||
  fail "prioritized got arc's arguments: $(cat "$WORK/plans")"
"$PY" - "$WORK/r.sqlite" <<'PYEOF' || fail "results database"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
assert con.execute("PRAGMA user_version").fetchone()[0] == 9
rows = sorted(con.execute("SELECT method, trial, planner_args FROM trials"))
assert rows == [("arc", 0, '["--window","4"]'), ("arc", 1, '["--window","4"]'),
                ("prioritized", 0, None), ("prioritized", 1, None)], rows
PYEOF

# The method named with its arguments; one without any by its name.
grep -q "^| 2 | arc --window 4 | 2/2 " "$WORK/out" || fail "run's table does not name arc's arguments"
"$BENCH" table --results "$WORK/r.sqlite" > "$WORK/table.md" || fail "table exited $?"
grep -q "^| 2 | arc --window 4 | 2/2 " "$WORK/table.md" && grep -q "^| 2 | prioritized | 2/2 " "$WORK/table.md" ||
  fail "table: $(cat "$WORK/table.md")"
"$BENCH" table --results "$WORK/r.sqlite" --wide > "$WORK/table.md" || fail "table --wide exited $?"
grep -qx "| robots | arc --window 4 | prioritized |" "$WORK/table.md" || fail "table --wide: $(cat "$WORK/table.md")"
"$BENCH" export --results "$WORK/r.sqlite" --csv "$WORK/r.csv" --ompl-log "$WORK/logs" > /dev/null ||
  fail "export exited $?"
"$PY" - "$WORK/r.csv" "$WORK/logs/mobile-2.log" <<'PYEOF' || fail "exports"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert sorted((r["method"], r["planner_args"]) for r in rows) == [
    ("arc", "--window 4"), ("arc", "--window 4"), ("prioritized", ""), ("prioritized", "")], rows
lines = open(sys.argv[2]).read().split("\n")
assert "arc --window 4" in lines and "prioritized" in lines, "OMPL planners: %s" % lines
PYEOF

# Resumed with the same arguments: nothing to run. With others, or none:
# refused, naming the method and both, nothing planned or recorded.
"$BENCH" "${RUN[@]}" --results "$WORK/r.sqlite" --method-arg arc=--window --method-arg arc=4 > "$WORK/out" 2>&1 ||
  fail "resumed with the same arguments: exit $?"
grep -q "^nothing to run" "$WORK/out" || fail "resumed with the same arguments ran trials"
plans=$(wc -l < "$WORK/plans")
want="r.sqlite: --method-arg: its arc trials ran with --window 4; this run gives arc --window=8: a results file holds one set of planner arguments per method"
refusedInOneLine "$want" "$BENCH" "${RUN[@]}" --results "$WORK/r.sqlite" --method-arg arc=--window=8
refusedInOneLine "its arc trials ran with --window 4; this run gives arc none: " \
  "$BENCH" "${RUN[@]}" --results "$WORK/r.sqlite"
refusedInOneLine "its prioritized trials ran with no planner arguments; this run gives prioritized --window=8: " \
  "$BENCH" "${RUN[@]}" --results "$WORK/r.sqlite" --method-arg arc=--window --method-arg arc=4 \
  --method-arg prioritized=--window=8
[ "$(wc -l < "$WORK/plans")" -eq "$plans" ] && [ "$(count "$WORK/r.sqlite" "SELECT count(*) FROM trials")" -eq 4 ] ||
  fail "a refused resume planned or recorded trials"

# Refused before any trial (no results file made, nothing planned).
for bad in "--method-arg: unknown method 'astar'|astar=--window=4" \
           "--method-arg: method coupled is not one of this run's methods (--methods)|coupled=--window=4" \
           "--method-arg: 'arc' is not METHOD=ARG|arc" \
           "--method-arg arc: '--seed=3' sets what earc-bench gives earc-plan itself|arc=--seed=3" \
           "--method-arg arc: '-o' sets what earc-bench gives earc-plan itself|arc=-o" \
           "--method-arg arc: 'x.json' is not an option (nor the value of one)|arc=x.json"; do
  refusedInOneLine "${bad%%|*}" "$BENCH" "${RUN[@]}" --results "$WORK/n.sqlite" --method-arg "${bad#*|}"
  [ ! -e "$WORK/n.sqlite" ] || fail "--method-arg ${bad#*|}: refused after making the results file"
done
[ "$(wc -l < "$WORK/plans")" -eq "$plans" ] || fail "a refused option planned"

# An argument the planner refuses (--db-k is for earc): its first trial
# stops the run, which records no trial of the method (here two at once:
# either may be the first refused).
refusedInOneLine ", so would every arc trial (not recorded): exit 2: earc-plan: error: --db-k: is for method earc" \
  "$BENCH" "${RUN[@]}" --results "$WORK/refused.sqlite" --method-arg arc=--db-k=5 --jobs 2
grep -qE "^earc-bench: error: $WORK/logging-plan: --method-arg arc: refused arc's trial mobile-2-t[01] run with --db-k=5, " \
  "$WORK/err" || fail "the planner's refusal does not name the planner, method, trial and arguments: $(cat "$WORK/err")"
[ "$(count "$WORK/refused.sqlite" "SELECT count(*) FROM trials WHERE method = 'arc'")" -eq 0 ] ||
  fail "a refused trial was recorded"

# A file that mixes two sets for one method (a hand edit) is refused by
# every reader, naming both rows.
"$PY" - "$WORK/r.sqlite" "$WORK/mixed.sqlite" > "$WORK/ids" <<'PYEOF' || fail "could not make mixed.sqlite"
import sqlite3, sys
src, dst = sqlite3.connect(sys.argv[1]), sqlite3.connect(sys.argv[2])
src.backup(dst)
ids = [i for (i,) in dst.execute("SELECT id FROM trials WHERE method = 'arc' ORDER BY id")]
dst.execute("UPDATE trials SET planner_args = NULL WHERE id = ?", (ids[1],))
dst.commit()
print(ids[1], ids[0])
PYEOF
read -r second first < "$WORK/ids"
want="mixed.sqlite: trials row id $second, column planner_args: NULL beside '[\"--window\",\"4\"]' of method arc in row id $first: a results file holds one set of planner arguments per method"
refusedInOneLine "$want" "$BENCH" table --results "$WORK/mixed.sqlite"
refusedInOneLine "$want" "$BENCH" export --results "$WORK/mixed.sqlite" --csv "$WORK/mixed.csv"
refusedInOneLine "plot_results.py: $WORK/$want" "$PY" "$SRC/tools/plots/plot_results.py" \
  --results "$WORK/mixed.sqlite" -o "$WORK/mixed-figures"

# The figures' legends name the method as table does.
if hasMatplotlib; then
  "$BENCH" plot --results "$WORK/r.sqlite" -o "$WORK/fig" > /dev/null 2> "$WORK/err" || fail "plot exited $?"
  "$PY" - "$SRC/tools/plots" "$WORK/r.sqlite" <<'PYEOF' || fail "plot's labels"
import sys
sys.path.insert(0, sys.argv[1])
import plot_results
trials, _ = plot_results.load(sys.argv[2], None, None)
assert plot_results.label("arc", trials) == "ARC --window 4", plot_results.label("arc", trials)
assert plot_results.label("prioritized", trials) == "Prioritized"
PYEOF
else
  echo "note: no matplotlib for $PY: plot's labels not tested"
fi
echo "ok: --method-arg reaches its method's plans, is recorded, shown, and kept one set per method"
