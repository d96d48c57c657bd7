#!/bin/bash
# earc-db bench-retrieval prints one row per class with its entry count and
# key dimension (small entry count: a smoke test, not a measurement).
set -u
BUILD=$1
DB="$BUILD/earc-db"
[ -x "$DB" ] || { echo "FAIL: earc-db not built in $BUILD"; exit 1; }
fail() { echo "FAIL: $*"; exit 1; }
out=$("$DB" bench-retrieval --entries 2000 --queries 50) || fail "bench-retrieval exited $?"
echo "$out" | grep -Eq "^mobile x2 +2000 +8 " || fail "no mobile x2 row: $out"
echo "$out" | grep -Eq "^mobile x4 +2000 +16 " || fail "no mobile x4 row: $out"
echo "$out" | grep -Eq "^manipulator x2 facing +2000 +12 " || fail "no arm row: $out"
echo "$out" | grep -q "fewer than k" && fail "a query returned fewer than k entries: $out"
echo "ok"
