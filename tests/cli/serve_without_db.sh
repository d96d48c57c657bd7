#!/bin/bash
# earc-plan serve without --db: a service for the methods that need no
# experience database. With E-ARC as its default method it is refused at
# once, in one line naming --db, creating no file (nor its socket); with
# --method arc it answers a ping, plans an ARC request (a valid plan),
# refuses an E-ARC request with an error answer and goes on, and reports
# no database in its stats. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-scenario
failShowsOutput
PLAN=$BUILD/earc-plan
mkdir "$WORK/run" && cd "$WORK/run" || exit 1

refusedInOneLine "--db: method earc needs an experience database file" "$PLAN" serve < /dev/null
refusedInOneLine "--db: method earc needs an experience database file" "$PLAN" serve --method earc < /dev/null
# Before any socket is bound: the option is named, not the socket's
# directory, which does not exist.
refusedInOneLine "--db: method earc needs an experience database file" "$PLAN" serve --socket none/s.sock < /dev/null
[ -z "$(ls)" ] || fail "a refused service left $(ls)"

"$BUILD/earc-scenario" generate -n 8 --obstacles --seed 3 -o s.json > /dev/null || fail "earc-scenario: exit $?"
{
  echo '{"id": 1, "op": "ping"}'
  echo '{"id": 2, "scenario_file": "s.json"}'
  echo '{"id": 3, "scenario_file": "s.json", "method": "earc"}'
  echo '{"id": 4, "op": "stats"}'
} | "$PLAN" serve --method arc > out 2> err
rc=$?
[ $rc -eq 0 ] || fail "serve --method arc exited $rc"
grep -qF "no experience database" err || fail "the start line does not say there is no database"
grep -qF "database closed" err && fail "a service without a database says it closed one"
"$PY" - out > served.json <<'PY' || fail "answers"
import json, sys
answers = {a["id"]: a for a in map(json.loads, open(sys.argv[1]))}
assert sorted(answers) == [1, 2, 3, 4], answers
assert answers[1]["ok"], answers[1]
plan = answers[2]
assert plan["ok"] and plan["solved"], plan
assert plan["stats"]["method"] == "arc", plan["stats"]
earc = answers[3]
assert not earc["ok"] and "experience database" in earc["error"], earc
stats = answers[4]["stats"]
assert stats["plans"] == 1 and stats["solved"] == 1 and stats["errors"] == 1, stats
assert "db" not in stats and "db_entries" not in stats, stats
json.dump(plan["solution"], sys.stdout)
PY
"$PLAN" validate s.json served.json > /dev/null || fail "the served ARC plan is not valid"
echo "serve without --db: refused for earc, plans arc, refuses an earc request"
