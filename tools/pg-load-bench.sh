#!/usr/bin/env bash
# Load benchmark of the experience store's two engines (not a test):
# two groups of four `earc-plan plan --method earc` loops learning into one
# PostgreSQL store for SECONDS, one group over TCP and one over the Unix
# socket (standing in for two machines), then the same eight loops against
# one SQLite file. Prints plans and inserts per second, failed plans, and
# checks that every row id a plan reported learned is in the store and
# that the store holds exactly its seed rows plus those.
#   tools/pg-load-bench.sh BUILD_DIR [SECONDS]   (default 300)
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR [SECONDS]}" && pwd)
seconds=${2:-300}
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
pg=$(mktemp -u /tmp/earc-pg-bench.XXXXXX)  # not under $work: the server user must reach it
trap 'bash "$src/tools/postgres-dev.sh" stop "$pg" > /dev/null 2>&1; rm -rf "$work"' EXIT
EARC_PG_OPTIONS="${EARC_PG_OPTIONS:-}" bash "$src/tools/postgres-dev.sh" start "$pg" > /dev/null
socket=$(cat "$pg/uri-socket")
tcp=$(cat "$pg/uri-tcp")
for i in $(seq 0 9); do
  "$build/earc-scenario" generate -n $((8 + i)) --workspace 6 --obstacles 3 --seed $((100 + i)) \
    -o "$work/s$i.json" > /dev/null
done

# worker NAME DB: plans scenarios round robin until the deadline.
worker() {
  local name=$1 db=$2 n=0 rc
  : > "$work/$name.ids"
  : > "$work/$name.rc"
  while [ "$(date +%s)" -lt "$deadline" ]; do
    "$build/earc-plan" plan "$work/s$((n % 10)).json" -o "$work/$name.sol.json" --method earc --db "$db" \
      --seed $n -q 2>> "$work/$name.err" && rc=0 || rc=$?
    echo $rc >> "$work/$name.rc"
    [ -s "$work/$name.sol.json" ] && jq -r '.stats.db_learned_ids[]?' "$work/$name.sol.json" >> "$work/$name.ids"
    rm -f "$work/$name.sol.json"
    n=$((n + 1))
  done
}

# run LABEL DB_A DB_B COUNT_SQL: eight workers, four on each; the report line.
run() {
  local label=$1 a=$2 b=$3 count=$4 seed after plans failed ids
  seed=$($count)
  deadline=$(($(date +%s) + seconds))
  for i in 1 2 3 4; do worker "$label-a$i" "$a" & worker "$label-b$i" "$b" & done
  wait
  after=$($count)
  plans=$(cat "$work/$label"-*.rc | wc -l)
  failed=$(grep -cv '^[01]$' <(cat "$work/$label"-*.rc) || true)
  ids=$(cat "$work/$label"-*.ids | wc -l)
  local missing=0 dup
  dup=$(cat "$work/$label"-*.ids | sort | uniq -d | wc -l)
  for id in $(cat "$work/$label"-*.ids); do
    [ "$($count "WHERE id = $id")" = 1 ] || missing=$((missing + 1))
  done
  printf '%-10s %6d plans %6.2f plans/s %6d inserts %6.2f inserts/s  failed %d  reported ids missing %d, repeated %d  rows %d -> %d (%s)\n' \
    "$label" "$plans" "$(echo "$plans / $seconds" | bc -l)" "$ids" "$(echo "$ids / $seconds" | bc -l)" "$failed" \
    "$missing" "$dup" "$seed" "$after" "$([ $((after - seed)) -eq "$ids" ] && echo "exactly the reported rows" || echo "MISMATCH")"
}

pgCount() { psql -X -A -t -q "$tcp" -c "SELECT count(*) FROM earc.experiences ${1:-}"; }
sqliteCount() { /usr/bin/python3 -c 'import sqlite3, sys
print(sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute("SELECT count(*) FROM experiences " + sys.argv[2]).fetchone()[0])' "$work/s.db" "${1:-}"; }

"$build/earc-db" build --db "$tcp" --kind mobile --count 200 --seed 1 -q > /dev/null
"$build/earc-db" build --db "$work/s.db" --kind mobile --count 200 --seed 1 -q > /dev/null
echo "$seconds s, 2 x 4 planner loops, $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
run postgresql "$tcp" "$socket" pgCount
run sqlite "$work/s.db" "$work/s.db" sqliteCount
