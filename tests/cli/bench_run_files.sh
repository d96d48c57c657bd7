#!/bin/bash
# label: bench
# earc-bench run FILE...: the files are the trials (suite "files", one per
# file and method, numbered per robot count in the order given). E-ARC's
# database is built for the files' robots (once per geometry), so E-ARC
# has experiences for them; Lightning's is per world (a file that differs
# from another only in starts and goals shares its database). Every
# method's solution is validated; a resumed run skips what is recorded,
# and one given the files in another order is refused, naming the file.
# Bad requests end in one line and exit 2 before any trial: --suites
# (and the other suite options) with files, a file of 1 robot, a file
# that mixes mobile robots and arms. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan earc-db earc-scenario
failShowsOutput
cd "$WORK" || exit 1

for seed in 3 4; do
  "$BUILD/earc-scenario" generate --family mobile -n 3 --shape disc --radius 0.25 --obstacles 4 --seed $seed \
    -o d$seed.json > /dev/null || fail "generate"
done
"$BUILD/earc-scenario" generate --family arms -n 2 --seed 5 -o a2.json > /dev/null || fail "generate arms"
# d3's world with its starts and goals swapped: another problem, one world.
"$PY" - <<'PY' || fail "swap"
import json
s = json.load(open("d3.json"))
for r in s["robots"]:
    r["start"], r["goal"] = r["goal"], r["start"]
s["name"] = "d3-swapped"
json.dump(s, open("d3s.json", "w"))
PY
RUN=(run --methods earc,arc,lightning --time-limit 5 --earc-db-count 200 --lightning-problems 2
     --lightning-problem-time-limit 1 --results r.sqlite)
"$BENCH" "${RUN[@]}" d3.json d4.json a2.json d3s.json > out 2> err || fail "run exited $?"
grep -q '^### files' out || fail "no table of the files"
[ "$(sqlite3 r.sqlite "select count(*) from trials where suite = 'files'")" = 12 ] || fail "not 12 trials"
[ "$(sqlite3 r.sqlite "select count(*) from trials where success = 1")" = 12 ] || fail "not every trial solved"
# Numbered per robot count in the order given: the 3-robot files are
# trials 0, 1, 2 (d3, d4, d3s), the 2-robot one trial 0.
[ "$(sqlite3 r.sqlite "select group_concat(distinct robots || ':' || trial) from
     (select * from trials order by robots, trial)")" = "2:0,3:0,3:1,3:2" ] || fail "trials numbered wrong"
[ "$(sqlite3 r.sqlite "select count(distinct scenario_seed) from trials")" = 4 ] || fail "scenario seeds are not per file"
# The CSV says which file each trial planned, as the run was given it.
"$BENCH" export --results r.sqlite --csv trials.csv > out 2> err || fail "export exited $?"
"$PY" - <<'PY' || fail "the CSV does not name each trial's file: $(cat trials.csv)"
import csv
rows = list(csv.DictReader(open("trials.csv")))
want = {("3", "0"): "d3.json", ("3", "1"): "d4.json", ("3", "2"): "d3s.json", ("2", "0"): "a2.json"}
assert len(rows) == 12, len(rows)
for r in rows:
    assert r["scenario_file"] == want[(r["robots"], r["trial"])], r
PY
# One E-ARC database per kind, built for the files' robots (named by them,
# the count and the seed): no warning.
for f in d3 a2; do
  db=$(echo r.sqlite.work/earc-files-$([ $f = a2 ] && echo arms || echo mobile)-????????????????-p200-s1.sqlite)
  [ -s "$db" ] || fail "no $db: $(ls r.sqlite.work)"
  "$BUILD/earc-plan" plan $f.json -o /dev/null --method earc --db "$db" --no-learn -q 2> err || fail "plan $f"
  [ -s err ] && fail "E-ARC's database does not fit $f: $(cat err)"
done
# Lightning: d3 and d3s share a world, so three databases for four files.
[ "$(ls r.sqlite.work/lightning/*.lightning | wc -l)" = 3 ] || fail "not 3 Lightning databases: $(ls r.sqlite.work/lightning)"

"$BENCH" "${RUN[@]}" d3.json d4.json a2.json d3s.json > out 2> err || fail "resume exited $?"
grep -q "nothing to run: all 12 trials are in r.sqlite" out || fail "the resumed run ran again"
refusedInOneLine "planned on another scenario than d4.json, the 1st file of 3 robots given" \
  "$BENCH" "${RUN[@]}" d4.json d3.json a2.json d3s.json
refusedInOneLine "--suites: is for the suites; scenario files are the trials themselves" \
  "$BENCH" run --suites mobile d3.json --results other.sqlite
refusedInOneLine "--trials: is for the suites" "$BENCH" run --trials 3 d3.json --results other.sqlite

# A database given for files whose robots it does not serve: one warning
# per geometry, and the run goes on.
"$BENCH" run --methods earc --time-limit 5 --db-mobile r.sqlite.work/earc-files-arms-*.sqlite --results w.sqlite \
  d3.json d4.json > out 2> err || fail "run with another kind's database exited $?"
[ "$(grep -c 'earc-bench: warning: d3.json: .*none for these robots' err)" = 1 ] || fail "no one warning: $(cat err)"
grep -q 'd4.json' err && fail "warned twice for one geometry: $(cat err)"

"$PY" - <<'PY' || fail "bad files"
import json
s = json.load(open("d3.json"))
one = dict(s, robots=s["robots"][:1])
json.dump(one, open("one.json", "w"))
a = json.load(open("a2.json"))
json.dump(dict(s, robots=s["robots"] + a["robots"][:1]), open("mixed.json", "w"))
PY
# Arms too far apart for any database class: said once, no build for
# them, and the other file's database and trials are kept (a failed build
# used to delete the database and fail every E-ARC arm trial for good).
"$PY" - <<'PY' || fail "far arms"
import json
a = json.load(open("a2.json"))
a["name"] = "far"
a["workspace"]["max"][0] = max(a["workspace"]["max"][0], 40)
a["robots"][1]["base"][0] = a["robots"][0]["base"][0] + 30
json.dump(a, open("far.json", "w"))
PY
"$BENCH" run --methods earc --time-limit 5 --earc-db-count 50 --results f.sqlite a2.json far.json > out 2> err ||
  fail "run with unreachable arms exited $?"
[ "$(grep -c "earc-bench: warning: far.json: no two arms .* can reach each other.*E-ARC plans as ARC does" err)" = 1 ] ||
  fail "no one warning for the far arms: $(cat err)"
[ "$(sqlite3 f.sqlite "select count(*) from trials where success = 1")" = 2 ] || fail "an E-ARC arm trial failed"
"$BUILD/earc-db" inspect --db f.sqlite.work/earc-files-arms-*-p50-s1.sqlite --json > inspect.json || fail "inspect"
[ "$("$PY" -c 'import json; print(json.load(open("inspect.json"))["entries"])')" -gt 0 ] ||
  fail "a2's database rows are gone: $(head -c 300 inspect.json)"
"$BENCH" run --methods earc --time-limit 5 --results g.sqlite far.json > out 2> err || fail "far arms alone exited $?"
[ "$(sqlite3 g.sqlite "select success from trials")" = 1 ] || fail "far arms alone: E-ARC failed"

refusedInOneLine "one.json: 1 robot: earc-bench run takes scenarios of 2 to 1024 robots" \
  "$BENCH" run d3.json one.json --results other.sqlite
refusedInOneLine 'mixed.json: $.robots: mixes mobile robots and arms' "$BENCH" run mixed.json --results other.sqlite
[ -e other.sqlite ] && fail "a refused run created its results file"
"$BENCH" lightning-db --scenario d3.json --robots 3 -o x.lightning > out 2> err && fail "--scenario with --robots accepted"
echo "ok: scenario files are trials, with databases for their robots and worlds"
