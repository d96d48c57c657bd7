#!/bin/bash
# --deterministic: the same seed gives the same plan, and earc-db build the
# same rows, on a machine whose clock runs 100 times faster than its work
# (faketime: every budget in seconds then ends 100 times sooner, as on a
# machine 100 times slower or busier), for ARC, E-ARC, lacam and the builder;
# without it the plan changes there, so the slowdown is felt. Requests to
# earc-plan serve take "deterministic" too. Skipped (77) without faketime
# (tools/setup.sh --tests installs it).
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-plan
needBuilt earc-db
needBuilt earc-scenario
command -v faketime > /dev/null || { echo "skipped: no faketime"; exit 77; }
command -v jq > /dev/null || { echo "skipped: no jq"; exit 77; }
PLAN="$BUILD/earc-plan"
DB="$BUILD/earc-db"
# libfaketime is preloaded before the sanitizers' runtime in the
# sanitizer build; it still works there (checked: a busy loop of 1 s reads
# 20 s under x20).
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
fast() { faketime -f "+0 x100" "$@"; }
paths() { jq -c .paths "$1"; }

"$BUILD/earc-scenario" generate --family mobile -n 16 --obstacles --seed 5 -o "$WORK/s.json" > /dev/null \
  || fail "generate"
# The whole plan's --time-limit stays wall-clock time (of the fast clock):
# far more than it needs.
LIMIT=(--time-limit 1000000)

# ARC: with --deterministic the same paths; without, a budget of seconds
# ends sooner and the plan goes another way.
"$PLAN" plan "$WORK/s.json" -o "$WORK/arc-idle.json" --method arc --seed 1 --deterministic -q "${LIMIT[@]}" \
  || fail "arc --deterministic exited $?"
fast "$PLAN" plan "$WORK/s.json" -o "$WORK/arc-fast.json" --method arc --seed 1 --deterministic -q "${LIMIT[@]}" \
  || fail "arc --deterministic under faketime exited $?"
[ "$(jq -r .stats.solver_budgets "$WORK/arc-idle.json")" = work ] || fail "stats.solver_budgets is not work"
[ "$(paths "$WORK/arc-idle.json")" = "$(paths "$WORK/arc-fast.json")" ] \
  || fail "arc --deterministic: the paths changed with the clock's speed"
"$PLAN" plan "$WORK/s.json" -o "$WORK/arc-sec-idle.json" --method arc --seed 1 -q "${LIMIT[@]}" || fail "arc exited $?"
fast "$PLAN" plan "$WORK/s.json" -o "$WORK/arc-sec-fast.json" --method arc --seed 1 -q "${LIMIT[@]}" \
  || fail "arc under faketime exited $?"
[ "$(jq -r .stats.solver_budgets "$WORK/arc-sec-idle.json")" = seconds ] || fail "stats.solver_budgets is not seconds"
[ "$(paths "$WORK/arc-sec-idle.json")" != "$(paths "$WORK/arc-sec-fast.json")" ] \
  || fail "without --deterministic the faster clock changed nothing: this test shows nothing"

# The crowd solver: its ways' spreading has a budget of seconds (cut short
# on 300 robots under the fast clock), refinement a share of --refine.
"$BUILD/earc-scenario" movingai warehouse-10-20-10-2-1 --scen warehouse-10-20-10-2-1-random-1 --robots 300 \
  -o "$WORK/w.json" > /dev/null || fail "movingai"
for side in idle fast; do
  run=(); [ $side = fast ] && run=(faketime -f "+0 x100")
  "${run[@]}" "$PLAN" plan "$WORK/w.json" -o "$WORK/lacam-$side.json" --method lacam --seed 1 --deterministic -q \
    "${LIMIT[@]}" || fail "lacam $side exited $?"
done
[ "$(paths "$WORK/lacam-idle.json")" = "$(paths "$WORK/lacam-fast.json")" ] \
  || fail "lacam --deterministic: the paths changed with the clock's speed"
fast "$PLAN" plan "$WORK/w.json" -o "$WORK/lacam-sec-fast.json" --method lacam --seed 1 -q "${LIMIT[@]}" \
  || fail "lacam under faketime exited $?"
[ "$(paths "$WORK/lacam-idle.json")" != "$(paths "$WORK/lacam-sec-fast.json")" ] \
  || fail "lacam: without --deterministic the faster clock changed nothing: this test shows nothing"

# The builder: budgets per problem of work. Large discs leave problems
# that use up their budget.
build() {
  $2 "$DB" build --db "$WORK/$1.db" --kind mobile --shape disc --radius 0.8 --count 60 --seed 1 --deterministic -q \
    || fail "build $1 exited $?"
  "$DB" export --db "$WORK/$1.db" -o "$WORK/$1.jsonl" > /dev/null || fail "export $1"
  # Without what legitimately differs (clock readings).
  jq -c 'del(.created_at, .solve_time_s)' "$WORK/$1.jsonl" > "$WORK/$1.rows"
}
build idle ""
build fast fast
[ "$(wc -l < "$WORK/idle.rows")" -gt 10 ] || fail "the build stored almost nothing: $(cat "$WORK/idle.rows")"
cmp -s "$WORK/idle.rows" "$WORK/fast.rows" || fail "build --deterministic: the rows changed with the clock's speed"
"$DB" inspect --db "$WORK/idle.db" | grep -q "s of work a problem" || fail "the build's history does not say work"

# E-ARC with a database (not learning, so both plans read the same rows).
"$DB" build --db "$WORK/m.db" --kind mobile --count 400 --seed 1 --deterministic -q || fail "build m.db"
for side in idle fast; do
  run=(); [ $side = fast ] && run=(faketime -f "+0 x100")
  "${run[@]}" "$PLAN" plan "$WORK/s.json" -o "$WORK/earc-$side.json" --method earc --db "$WORK/m.db" --no-learn \
    --seed 1 --deterministic -q "${LIMIT[@]}" || fail "earc $side exited $?"
done
[ "$(jq '.stats.db_hits // 0' "$WORK/earc-idle.json")" -gt 0 ] || fail "the database answered nothing"
[ "$(paths "$WORK/earc-idle.json")" = "$(paths "$WORK/earc-fast.json")" ] \
  || fail "earc --deterministic: the paths changed with the clock's speed"

# Refused where it cannot hold: Lightning races two threads.
"$PLAN" plan "$WORK/s.json" -o "$WORK/l.json" --method lightning --deterministic > "$WORK/out" 2>&1
[ $? -eq 2 ] || fail "lightning --deterministic was not refused: $(cat "$WORK/out")"
grep -q -- "--deterministic: is not for method lightning" "$WORK/out" || fail "refusal: $(cat "$WORK/out")"
[ -e "$WORK/l.json" ] && fail "a refused plan wrote its output"

# earc-plan serve: a request's "deterministic", and --deterministic as the default.
req() { jq -cn --arg f "$WORK/s.json" --argjson d "$1" '{id: 1, scenario_file: $f, method: "arc", seed: 1} + $d'; }
{ req '{"deterministic": true}'; req '{}'; req '{"deterministic": "yes"}'; req '{"deterministic": true, "method": "lightning"}'; } \
  | "$PLAN" serve --db "$WORK/m.db" 2> /dev/null > "$WORK/served.jsonl" || fail "serve exited $?"
[ "$(sed -n 1p "$WORK/served.jsonl" | jq -r .stats.solver_budgets)" = work ] || fail "request 1: $(sed -n 1p "$WORK/served.jsonl")"
[ "$(sed -n 1p "$WORK/served.jsonl" | jq -c .solution.paths)" = "$(paths "$WORK/arc-idle.json")" ] \
  || fail "a deterministic request planned other paths than earc-plan plan --deterministic"
[ "$(sed -n 2p "$WORK/served.jsonl" | jq -r .stats.solver_budgets)" = seconds ] || fail "request 2: $(sed -n 2p "$WORK/served.jsonl")"
sed -n 3p "$WORK/served.jsonl" | jq -r 'select(.ok == false) | .error' | grep -q 'deterministic: must be true or false' \
  || fail "request 3: $(sed -n 3p "$WORK/served.jsonl")"
sed -n 4p "$WORK/served.jsonl" | jq -r 'select(.ok == false) | .error' | grep -q 'deterministic: is not for method lightning' \
  || fail "request 4: $(sed -n 4p "$WORK/served.jsonl")"
echo '{"id": 1, "scenario_file": "'"$WORK/s.json"'", "method": "arc", "seed": 1}' \
  | "$PLAN" serve --db "$WORK/m.db" --deterministic 2> /dev/null > "$WORK/served2.jsonl" || fail "serve exited $?"
[ "$(jq -r .stats.solver_budgets "$WORK/served2.jsonl")" = work ] || fail "serve --deterministic: $(cat "$WORK/served2.jsonl")"
echo "ok"
