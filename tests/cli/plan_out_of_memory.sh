#!/bin/bash
# label: bench
# A scenario too large for the memory limit (ulimit -v) is an error line
# naming the file, never `terminate called` and a core dump (nlohmann's
# destructor allocates while a failed parse unwinds; a reserve given back
# at the first failed allocation makes room for it). `earc-plan serve`
# answers such a request with an error and goes on serving, twice in a
# row (the reserve is set aside again). Labelled bench: AddressSanitizer
# cannot run under an address-space limit. Skipped (77) without
# /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-db
SRC=$(cd "$(dirname "$0")/../.." && pwd)
# 150,000 more boxes far from the robots: 12 MB of JSON, well over 100 MB
# as a document.
"$PY" - "$SRC/datasets/mobile-4-s1.json" "$WORK/big.json" <<'PY' || fail "could not write the large scenario"
import json, sys
s = json.load(open(sys.argv[1]))
box = {"type": "box", "center": [500.0, 500.0], "size": [1.0, 1.0], "angle": 0.0}
s["obstacles"] = s.get("obstacles", []) + [dict(box, center=[500.0 + i * 1e-3, 500.0]) for i in range(150000)]
json.dump(s, open(sys.argv[2], "w"))
PY

# Limits from too small to start up to enough to read it: each run ends in
# exit 0, 1 or 2 with at most one error line; the file is named when
# reading it is what ran out.
named=0
for kb in 40000 60000 80000 100000 130000 160000 200000 250000; do
  (ulimit -v $kb; exec "$BUILD/earc-plan" plan "$WORK/big.json" -o "$WORK/out.json" -q --time-limit 5) \
    > "$WORK/out" 2> "$WORK/err"
  rc=$?
  # Too small for the dynamic loader to map the shared libraries (libpq's
  # among them): earc-plan never ran, so there is nothing of ours to check.
  if [ $rc -eq 127 ] && grep -q "error while loading shared libraries" "$WORK/err"; then continue; fi
  [ $rc -le 2 ] || fail "ulimit -v $kb: exit $rc: $(head -c 300 "$WORK/err")"
  grep -q "terminate" "$WORK/err" && fail "ulimit -v $kb: $(head -c 300 "$WORK/err")"
  # (Read whole, the scenario's boxes outside the workspace are warned of.)
  [ "$(grep -vc '^earc-plan: warning: ' "$WORK/err")" -le 1 ] ||
    fail "ulimit -v $kb: more than one line: $(head -c 300 "$WORK/err")"
  grep -q "^earc-plan: error: $WORK/big.json: out of memory while reading it" "$WORK/err" && named=$((named + 1))
done
[ $named -ge 1 ] || fail "no limit ran out of memory while reading the scenario (limits too small or too large?)"

# serve: two such requests, then a ping, under a limit that fits the
# service but not the scenario.
"$BUILD/earc-db" build --db "$WORK/m.db" --kind mobile --count 50 --seed 1 -q || fail "earc-db build"
printf '%s\n' "{\"id\":1,\"scenario_file\":\"$WORK/big.json\"}" "{\"id\":2,\"scenario_file\":\"$WORK/big.json\"}" \
  '{"id":3,"op":"ping"}' > "$WORK/requests"
served=0
for kb in 100000 130000 160000 200000; do
  (ulimit -v $kb; exec "$BUILD/earc-plan" serve --db "$WORK/m.db" < "$WORK/requests") > "$WORK/out" 2> "$WORK/err"
  rc=$?
  grep -q "terminate" "$WORK/err" && fail "serve, ulimit -v $kb: $(head -c 300 "$WORK/err")"
  [ $rc -le 2 ] || fail "serve, ulimit -v $kb: exit $rc: $(head -c 300 "$WORK/err")"
  [ $rc -eq 0 ] || continue  # too little to open the database at all
  # Each request fails for want of memory or, near the limit where it
  # fits, is solved; the ping after them is answered either way.
  [ "$(grep -c '"ok":false\|"solved":true' "$WORK/out")" -eq 2 ] || fail "serve, ulimit -v $kb: $(head -c 600 "$WORK/out")"
  grep '"ok":false' "$WORK/out" | grep -qv "out of memory" && fail "serve, ulimit -v $kb: $(head -c 600 "$WORK/out")"
  grep -q '"id":3,"ok":true' "$WORK/out" || fail "serve, ulimit -v $kb: no answer to the ping: $(cat "$WORK/out")"
  [ "$(grep -c '"ok":false' "$WORK/out")" -eq 2 ] && served=$((served + 1))
done
[ $served -ge 1 ] || fail "serve never ran out of memory on both requests and went on, under the limits tried"
echo "ok: $named limits named the file; serve answered under $served limits"
