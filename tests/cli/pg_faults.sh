#!/bin/bash
# label: pg
# The PostgreSQL server restarted while an E-ARC plan runs with
# --db postgresql://...: the plan is still written (exit 0 or 1), and
# what it learned is either in the store, every id it reports, or
# reported lost (db_learn_error), never half written; the store verifies.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
. "$(dirname "$0")/pg_common.bash"
failShowsOutput
needBuilt earc-db earc-plan earc-scenario
command -v jq > /dev/null || { echo "skipped: no jq"; exit 77; }

db=$PG_TCP_URI
"$BUILD/earc-db" build --db "$db" --kind mobile --count 40 --seed 1 -q > "$WORK/out" 2> "$WORK/err" || fail "build"
"$BUILD/earc-scenario" generate -n 40 --workspace 8 --seed 1 -o "$WORK/long.json" > /dev/null || fail "generate"
"$BUILD/earc-plan" plan "$WORK/long.json" -o "$WORK/long.sol.json" --method earc --db "$db" --no-crowd \
  --time-limit 6 -q > "$WORK/out" 2> "$WORK/err" &
plan=$!
# Restarted once the plan holds its connection.
for _ in $(seq 100); do
  [ "$(pgValue "$PG_URI" "SELECT count(*) FROM pg_stat_activity WHERE application_name = 'earc'")" -ge 1 ] && break
  sleep 0.05
done
kill -0 $plan 2> /dev/null || fail "the plan ended before the server was restarted: the test proves nothing"
bash "$PG_SRC/tools/postgres-dev.sh" restart "$PG_DIR" || fail "restart"
wait $plan
rc=$?
[ $rc -le 1 ] || fail "the plan exited $rc across the restart: $(head -c 400 "$WORK/err")"
[ -s "$WORK/long.sol.json" ] || fail "no solution written"
learned=$(jq '.stats.db_learned_ids | length' "$WORK/long.sol.json")
lost=$(jq -r '.stats.db_learn_error // ""' "$WORK/long.sol.json")
for id in $(jq -r '.stats.db_learned_ids[]?' "$WORK/long.sol.json"); do
  [ "$(pgValue "$PG_URI" "SELECT count(*) FROM earc.experiences WHERE id = $id")" = 1 ] || fail "learned row $id is missing"
done
[ "$learned" -gt 0 ] || [ -n "$lost" ] || [ "$(jq '.stats.db_learn_candidates' "$WORK/long.sol.json")" = 0 ] ||
  fail "rows to learn, none learned and no loss reported"
"$BUILD/earc-db" verify --db "$db" > "$WORK/out" 2> "$WORK/err" || fail "verify after the restart"
echo "ok: plan written across a server restart (learned $learned${lost:+; reported: $lost})"
