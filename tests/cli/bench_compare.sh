#!/bin/bash
# label: bench
# earc-bench compare: a build against itself plans the same paths; a
# planner whose plans differ (but are valid) is reported as differing; one
# whose plans are invalid is reported loudly with exit status 1; one that
# crashes, exits 1 after solving, or writes no solution is that side's
# named failure and the comparison goes on; one that refuses its options
# or database (exit 2, not naming the scenario) stops it after the first
# pair, one that refuses a scenario fails that pair; E-ARC plans start from copies,
# so the given database is left as it was; the CSV and the picture hold a
# row per plan pair and a point per scenario; two methods can be compared
# (--old-method/--new-method), only the one that plans with a database
# getting a copy; --old-arg/--new-arg take one argument each, so scenario
# files after them stay scenarios; a CSV on stdout is not mixed with the
# report; bad options (an argument compare gives the plan command itself)
# end in one line and exit status 2 before any plan runs.
# Skipped (77) without /usr/bin/python3 or earc-db. (Label bench: plans run
# under an address-space limit, which AddressSanitizer cannot live with.)
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
PLAN="$BUILD/earc-plan"
needPython
[ -x "$BUILD/earc-db" ] || { echo "skipped: earc-db not built in $BUILD"; exit 77; }
needBuilt earc-bench earc-plan
show() { tail -n 20 "$WORK/out" "$WORK/err"; }
BASE=(compare --suite mobile --robots 4 --trials 3 --seed 4 --time-limit 10 --work-dir "$WORK/w")

# The same build on both sides: every pair of plans is the same.
"$BENCH" "${BASE[@]}" --old "$PLAN" --new "$PLAN" --csv "$WORK/same.csv" --picture "$WORK/same.svg" -v \
  > "$WORK/out" 2> "$WORK/err" || { show; fail "self-comparison exited $?"; }
grep -q "^old solved 3 of 3 plans, new 3 of 3$" "$WORK/out" || { show; fail "solved counts"; }
grep -q "^same paths: 3 of 3 plan pairs$" "$WORK/out" || { show; fail "a build differs from itself"; }
version=$("$PLAN" --version) || fail "earc-plan --version exited $?"
grep -qxF "builds: old earc ${version#earc-plan }, new earc ${version#earc-plan }" "$WORK/out" ||
  { show; fail "the builds compared are not named"; }
grep -q "^new/old: ratio of medians [0-9.]*, paired median [0-9.]* (95% bootstrap interval [0-9.]* to [0-9.]*)$" \
  "$WORK/out" || { show; fail "no ratio line"; }
[ "$(grep -c "^mobile-4-t[012]: old .* same paths$" "$WORK/out")" -eq 3 ] || { show; fail "no line per scenario"; }
"$PY" - "$WORK/same.csv" "$WORK/same.svg" <<'PYEOF' || fail "CSV or picture"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["scenario"] for r in rows] == ["mobile-4-t0", "mobile-4-t1", "mobile-4-t2"], rows
assert all(r["old_solved"] == "1" and r["new_solved"] == "1" and r["same_paths"] == "1" for r in rows), rows
assert all(float(r["old_time_s"]) > 0 and float(r["new_time_s"]) > 0 for r in rows), rows
svg = open(sys.argv[2]).read()
assert svg.count("<circle") == 3 and 'stroke="#d62728"' not in svg, svg
PYEOF
# The picture says what was compared and how many plans each side failed.
svgTexts() { "$PY" -c 'import sys, xml.dom.minidom
for t in xml.dom.minidom.parse(sys.argv[1]).getElementsByTagName("text"): print(t.firstChild.data)' "$1"; }
svgTexts "$WORK/same.svg" > "$WORK/texts" || fail "the picture is not XML"
for want in "earc-bench compare: mobile, 4 robots, 3 scenarios, time limit 10 s" \
  "old: arc (earc ${version#earc-plan })" "new: arc (earc ${version#earc-plan })" \
  "failed: old 0 of 3 plans, new 0 of 3; 3 scenarios solved by both"; do
  grep -qxF "$want" "$WORK/texts" || fail "the picture does not say '$want': $(cat "$WORK/texts")"
done
# Repeats: each scenario planned twice a side, both pairs recorded. The
# CSV on stdout itself (a pipe) is the CSV alone: the report goes to stderr.
"$BENCH" compare --suite mobile --robots 4 --trials 1 --seed 4 --time-limit 10 --work-dir "$WORK/w" --repeats 2 \
  --old "$PLAN" --csv /dev/stdout 2> "$WORK/err" | cat > "$WORK/rep.csv"
rc=${PIPESTATUS[0]}
[ $rc -eq 0 ] || { show; fail "repeats: compare exited $rc"; }
grep -q "^same paths: 2 of 2 plan pairs$" "$WORK/err" || { show; fail "repeats: not two pairs on stderr"; }
head -n 1 "$WORK/rep.csv" | grep -q "^scenario,repeat," || fail "repeats: --csv /dev/stdout: $(head -n 2 "$WORK/rep.csv")"
[ "$(cut -d, -f1,2 "$WORK/rep.csv" | tail -n +2 | tr '\n' ' ')" = '"mobile-4-t0",0 "mobile-4-t0",1 ' ] ||
  fail "repeats: CSV rows $(cat "$WORK/rep.csv")"
# The scenarios are the ones earc-bench run plans for this seed.
"$BENCH" run --suites mobile --robots 4 --trials 1 --seed 4 --methods arc --time-limit 10 --keep-solutions \
  --results "$WORK/r.sqlite" > /dev/null 2>&1 || fail "run exited $?"
cmp -s "$WORK/w/scenarios/mobile-4-t0.json" "$WORK/r.sqlite.work/scenarios/"mobile-4-t0-*.json ||
  fail "compare's scenario differs from run's"

# A planner whose plans are valid but not the same: the first robot waits
# one more step at its goal, and the plan's stats say it costs one more.
cat > "$WORK/waits" <<FAKE
#!/bin/bash
"$PLAN" "\$@" || exit \$?
out=""
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
exec "$PY" -c 'import json,sys
d = json.load(open(sys.argv[1])); p = d["paths"][0]["states"]; p.append(p[-1]); d["stats"]["sum_of_costs"] += 1
json.dump(d, open(sys.argv[1], "w"))' "\$out"
FAKE
chmod +x "$WORK/waits"
"$BENCH" "${BASE[@]}" --old "$PLAN" --new "$WORK/waits" --csv "$WORK/differ.csv" --picture "$WORK/differ.svg" \
  > "$WORK/out" 2> "$WORK/err" || { show; fail "comparison with differing plans exited $?"; }
grep -q "^same paths: 0 of 3 plan pairs$" "$WORK/out" || { show; fail "differing plans not reported"; }
"$PY" - "$WORK/differ.csv" <<'PYEOF' || fail "the longer plans are not in the CSV"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
# What each plan's stats say.
assert all(int(r["new_sum_of_costs"]) == int(r["old_sum_of_costs"]) + 1 for r in rows), rows
assert all(int(r["new_makespan"]) == int(r["old_makespan"]) > 0 for r in rows), rows
PYEOF
grep -q "^plans (medians over the same scenarios): makespan old [0-9]*, new [0-9]*; sum of costs old [0-9]*, new [0-9]*$" \
  "$WORK/out" || { show; fail "no plan quality line"; }
[ "$(grep -o 'stroke="#d62728"' "$WORK/differ.svg" | wc -l)" -eq 3 ] || fail "differing plans not drawn hollow"

# A planner whose robots jump from start to goal: INVALID, exit 1.
writeTeleportingPlanner "$WORK/teleports"
"$BENCH" "${BASE[@]}" --old "$PLAN" --new "$WORK/teleports" > "$WORK/out" 2> "$WORK/err"
rc=$?
[ $rc -eq 1 ] || { show; fail "invalid plans: exit $rc, not 1"; }
grep -q "^INVALID SOLUTION: new ($WORK/teleports) on .*mobile-4-t0.json: INVALID" "$WORK/err" || { show; fail "no loud report"; }
grep -q "^old solved 3 of 3 plans, new 0 of 3; 3 INVALID solutions$" "$WORK/out" || { show; fail "invalid count"; }
grep -qxF "builds: old earc ${version#earc-plan }, new unknown" "$WORK/out" || { show; fail "an unnamed build"; }
grep -q "^no scenario was solved by both: no ratio$" "$WORK/out" || { show; fail "a ratio without pairs"; }

# A planner that crashes: that side's failure, named, and no ratio; the
# comparison itself finishes (exit 0).
printf '#!/bin/bash\nkill -SEGV $$\n' > "$WORK/crashes"
chmod +x "$WORK/crashes"
"$BENCH" "${BASE[@]}" --old "$PLAN" --new "$WORK/crashes" -v > "$WORK/out" 2> "$WORK/err" ||
  { show; fail "a crashing side ended the comparison"; }
grep -q "^old solved 3 of 3 plans, new 0 of 3$" "$WORK/out" || { show; fail "crashes not counted"; }
[ "$(grep -c "^mobile-4-t[012]: new: crashed: SIGSEGV (11); $" "$WORK/out")" -eq 3 ] || { show; fail "crash not named"; }

# A side whose exit status disagrees with its solution, or that writes no
# solution: named failures, the same as run's.
declare -A said=([exit1]="exit status 1 disagrees with the solution's solved flag"
                 [silent]="exit 1 without a readable solution: out of luck")
for how in exit1 silent; do
  writeMisreportingPlanner "$WORK/$how" $how
  "$BENCH" "${BASE[@]}" --old "$PLAN" --new "$WORK/$how" -v > "$WORK/out" 2> "$WORK/err" ||
    { show; fail "a side that misreports ($how) ended the comparison"; }
  grep -q "^old solved 3 of 3 plans, new 0 of 3$" "$WORK/out" || { show; fail "$how: plans counted as solved"; }
  [ "$(grep -cF "new: ${said[$how]}; " "$WORK/out")" -eq 3 ] || { show; fail "$how: not named"; }
done

# E-ARC: every plan starts from a copy of the database; the file given is
# not touched. Scenario files may be given instead of a suite. Budgets
# counted in work: on a busy machine E-ARC's timed ones can change a plan.
"$BUILD/earc-db" build --db "$WORK/m.sqlite" --kind mobile --count 30 --seed 2 -q > /dev/null 2>&1 ||
  fail "earc-db build exited $?"
before=$(sha256sum < "$WORK/m.sqlite")
"$BENCH" compare --old "$PLAN" --method earc --db "$WORK/m.sqlite" --work-dir "$WORK/w2" --time-limit 10 \
  --old-arg --deterministic --new-arg --deterministic "$WORK"/w/scenarios/mobile-4-t*.json > "$WORK/out" 2> "$WORK/err" || { show; fail "E-ARC comparison exited $?"; }
grep -q "^same paths: 3 of 3 plan pairs$" "$WORK/out" || { show; fail "E-ARC differs from itself"; }
[ "$(sha256sum < "$WORK/m.sqlite")" = "$before" ] || fail "the given database changed"
leftNothingBeside "$WORK/m.sqlite" "compare"
# One method against another: ARC (no database) against E-ARC, plan by plan.
"$BENCH" compare --old "$PLAN" --old-method arc --new-method earc --db "$WORK/m.sqlite" --work-dir "$WORK/w4" \
  --time-limit 10 "$WORK"/w/scenarios/mobile-4-t*.json > "$WORK/out" 2> "$WORK/err" || { show; fail "ARC against E-ARC exited $?"; }
grep -q "^earc-bench compare: 3 scenarios x 1 repeat, methods old arc, new earc, time limit 10 s$" "$WORK/out" ||
  { show; fail "the methods compared are not named"; }
grep -q "^old solved 3 of 3 plans, new 3 of 3$" "$WORK/out" || { show; fail "ARC against E-ARC: solved counts"; }
ls "$WORK/w4" | grep -q "^db-old" && fail "ARC's side was given a database"
[ "$(sha256sum < "$WORK/m.sqlite")" = "$before" ] || fail "the given database changed (two methods)"

# Each --old-arg/--new-arg takes one argument: a scenario file after
# --new-arg=X is a scenario (not the suite's generated ones), and X alone
# goes to the new side's plan command.
"$BENCH" compare --old "$PLAN" --old-method arc --new-method earc --db "$WORK/m.sqlite" --work-dir "$WORK/w5" \
  --time-limit 10 --suite mobile --robots 4 --trials 2 --old-arg=--window=20 --new-arg=--db-k=5 --picture "$WORK/args.svg" \
  "$WORK/w/scenarios/mobile-4-t0.json" > "$WORK/out" 2> "$WORK/err" || { show; fail "--new-arg then a file: exited $?"; }
# The picture names each side's options (scenario files: no suite).
svgTexts "$WORK/args.svg" > "$WORK/texts" || fail "the picture is not XML"
for want in "earc-bench compare: 1 scenario, time limit 10 s" "old: arc --window=20 (earc ${version#earc-plan })" \
  "new: earc --db-k=5 (earc ${version#earc-plan })"; do
  grep -qxF "$want" "$WORK/texts" || fail "the picture does not say '$want': $(cat "$WORK/texts")"
done
grep -q "^earc-bench compare: 1 scenario x 1 repeat, methods old arc, new earc, " "$WORK/out" ||
  { show; fail "the scenario file after --new-arg=X was not taken as the scenario"; }
grep -q "^  old: $PLAN --window=20$" "$WORK/out" && grep -q "^  new: .*/earc-plan --db-k=5$" "$WORK/out" ||
  { show; fail "the sides' plan commands got other arguments than one each"; }

# A side that refuses its input (exit 2: here a database too new for it)
# would refuse every plan: compare stops after the first pair, in one line
# naming the program and what it said, exit 2.
cat > "$WORK/refuses" <<FAKE
#!/bin/bash
echo x >> "$WORK/refusals"
echo "earc-plan: db.sqlite: schema version 5 is newer than this build knows (4)" >&2
exit 2
FAKE
chmod +x "$WORK/refuses"
"$BENCH" "${BASE[@]}" --old "$WORK/refuses" --new "$PLAN" > "$WORK/out" 2> "$WORK/err"
rc=$?
[ $rc -eq 2 ] || { show; fail "a refusing side: exit $rc, not 2"; }
[ "$(wc -l < "$WORK/err")" -eq 1 ] || { show; fail "a refusing side: not one line"; }
grep -qxF "earc-bench: error: $WORK/refuses: --old: refused the first plan (mobile-4-t0), so would every plan: exit 2: earc-plan: \
db.sqlite: schema version 5 is newer than this build knows (4)" "$WORK/err" || { show; fail "the refusal is not named"; }
[ "$(wc -l < "$WORK/refusals")" -eq 1 ] || fail "planned on after the refusal ($(wc -l < "$WORK/refusals") plans)"

# A program that exits 0 without writing a solution is no earc-plan: the
# same stop, not a table of failures with exit 0.
"$BENCH" "${BASE[@]}" --old /bin/true --new "$PLAN" > "$WORK/out" 2> "$WORK/err"
rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < "$WORK/err")" -eq 1 ] &&
  grep -qF "earc-bench: error: /bin/true: --old: exited 0 on the first plan (mobile-4-t0) without a readable solution: is it an earc-plan?" "$WORK/err" ||
  { show; fail "/bin/true as --old: exit $rc"; }

# A refusal that names the scenario (one this side cannot read) is that
# pair's failure; the comparison goes on.
cat > "$WORK/picky" <<FAKE
#!/bin/bash
echo "earc-plan: error: \$2: \\\$.robots[0]: a robot kind this build does not know" >&2
exit 2
FAKE
chmod +x "$WORK/picky"
"$BENCH" "${BASE[@]}" --old "$WORK/picky" --new "$PLAN" -v > "$WORK/out" 2> "$WORK/err" ||
  { show; fail "a scenario refused by one side ended the comparison"; }
grep -q "^old solved 0 of 3 plans, new 3 of 3$" "$WORK/out" || { show; fail "scenario refusals not counted"; }
[ "$(grep -c "^mobile-4-t[012]: old: exit 2: earc-plan: error: .*/mobile-4-t[012].json: \$.robots\[0\]: a robot kind" \
  "$WORK/out")" -eq 3 ] || { show; fail "scenario refusals not named"; }

# Bad options: one line, exit 2, nothing planned.
refused() {  # refused TEXT ARGS...
  local want=$1
  shift
  rm -rf "$WORK/w3"
  "$BENCH" compare --work-dir "$WORK/w3" "$@" > "$WORK/out" 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || { show; fail "compare $* exited $rc, not 2"; }
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || { show; fail "compare $*: not one line"; }
  grep -qF -- "$want" "$WORK/err" || { show; fail "compare $*: the error does not say '$want'"; }
  [ ! -d "$WORK/w3/solutions" ] || fail "compare $*: planned despite the error"
}
refused "--old" --suite mobile --robots 4
refused "/nonexistent: --old: no such file" --old /nonexistent
refused "--db: method earc needs a database" --old "$PLAN" --method earc
refused "--method: unknown method 'astar'" --old "$PLAN" --method astar
refused "--new-method: unknown method 'astar'" --old "$PLAN" --new-method astar
refused "--db: method earc needs a database" --old "$PLAN" --old-method arc --new-method earc
refused "--db: methods lightning and earc read different kinds of database" --old "$PLAN" --old-method lightning \
  --new-method earc --db "$WORK/m.sqlite"
refused "--robots: suite mobile has no 5-robot trials" --old "$PLAN" --suite mobile --robots 5
echo '{"format": "earc.scenario.v1", "robots": [' > "$WORK/broken.json"
refused "$WORK/broken.json" --old "$PLAN" "$WORK/broken.json"
refused "--picture" --old "$PLAN" --picture "$WORK/fig.jpg"
# Arguments compare gives the plan command itself, or a second scenario,
# as run's --method-arg refuses them (plannerArgsProblem).
refused "--new-arg: '--seed=3' sets what earc-bench gives earc-plan itself" --old "$PLAN" --new-arg=--seed=3
refused "--old-arg: 'x.json' is not an option (nor the value of one)" --old "$PLAN" --old-arg x.json
echo "ok"
