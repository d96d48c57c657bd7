#!/bin/bash
# --db-row-cache-mb N of earc-plan plan and serve: the bound of the
# experience store's cache of retrieved rows reaches the store. With 0 no
# retrieval is served from the cache (stats db_row_cache_hits 0), with a
# large bound some are, and the plans are the same either way (a
# deterministic plan reading the database without learning). A service
# takes it too. A value that is not a whole number in range, the option
# for a method that reads no experience database, and the option of a
# service without --db are refused in one line naming the option.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-db earc-plan
failShowsOutput
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
MOB="$SRC/datasets/mobile-obst-16-s1.json"
F="$WORK/k.db"
stat_of() { "$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"][sys.argv[2]])' "$@"; }

"$DB" build --db "$F" --scenario "$MOB" --count 300 --seed 2 -q || fail "build"
for mb in 0 1024; do
  "$PLAN" plan "$MOB" -o "$WORK/p$mb.json" --method earc --db "$F" --no-learn --deterministic --seed 1 \
    --db-row-cache-mb $mb -q || fail "--db-row-cache-mb $mb: exit $?"
  [ "$(stat_of "$WORK/p$mb.json" db_queries)" -gt 0 ] || fail "--db-row-cache-mb $mb: the plan never asked the database"
done
hits0=$(stat_of "$WORK/p0.json" db_row_cache_hits)
misses0=$(stat_of "$WORK/p0.json" db_row_cache_misses)
hits=$(stat_of "$WORK/p1024.json" db_row_cache_hits)
misses=$(stat_of "$WORK/p1024.json" db_row_cache_misses)
[ "$hits0" -eq 0 ] || fail "--db-row-cache-mb 0: $hits0 rows served from the cache"
[ "$misses0" -gt 0 ] || fail "--db-row-cache-mb 0: no row read: nothing tested"
[ "$hits" -gt 0 ] || fail "--db-row-cache-mb 1024: no row served from the cache ($misses read)"
# Every row a retrieval returned came from the cache or was read.
[ $((hits + misses)) -eq "$misses0" ] || fail "the cache changed the rows retrieved: $hits + $misses, not $misses0"
"$PY" - "$WORK/p0.json" "$WORK/p1024.json" <<'PY' || fail "the row cache changed the plan"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert a["paths"] == b["paths"], "different paths"
PY

# A service takes the option and keeps its cache across requests: the
# second of two equal requests finds rows the first read.
{ echo "{\"id\": 1, \"scenario_file\": \"$MOB\", \"method\": \"earc\", \"seed\": 1, \"learn\": false, \"deterministic\": true}"
  echo "{\"id\": 2, \"scenario_file\": \"$MOB\", \"method\": \"earc\", \"seed\": 1, \"learn\": false, \"deterministic\": true}"
} | "$PLAN" serve --db "$F" --db-row-cache-mb 1024 > "$WORK/serve.out" 2> "$WORK/serve.err" ||
  fail "serve --db-row-cache-mb 1024: exit $?"
"$PY" - "$WORK/serve.out" <<'PY' || fail "serve --db-row-cache-mb 1024: $(head -c 600 "$WORK/serve.out")"
import json, sys
a, b = (json.loads(l) for l in open(sys.argv[1]).read().splitlines())
assert a["ok"] and b["ok"], (a, b)
assert b["stats"]["db_row_cache_misses"] == 0 and b["stats"]["db_row_cache_hits"] > 0, b["stats"]
PY

for bad in -1 abc 1.5 1e3 0x10 65537; do
  refusedInOneLine "--db-row-cache-mb" "$PLAN" plan "$MOB" -o "$WORK/x.json" --method earc --db "$F" \
    --db-row-cache-mb=$bad -q
  refusedInOneLine "--db-row-cache-mb" "$PLAN" serve --db "$F" --db-row-cache-mb=$bad < /dev/null
done
[ -e "$WORK/x.json" ] && fail "a refused plan wrote its solution"
refusedInOneLine "--db-row-cache-mb: is for method earc" "$PLAN" plan "$MOB" -o "$WORK/x.json" --method arc \
  --db-row-cache-mb 8 -q
refusedInOneLine "--db-row-cache-mb: is for the experience database (--db)" "$PLAN" serve --method arc \
  --db-row-cache-mb 8 < /dev/null
echo "ok: --db-row-cache-mb: $hits0 hits at 0, $hits of $misses0 rows at 1024 MiB, the same paths"
