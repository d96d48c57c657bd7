#!/bin/bash
# earc-plan plan --method lightning --db FILE: the Lightning database file
# is created by the first solution, recalled from (and left as it was) with
# --no-learn, and refused with one line naming it (exit 2) when it is
# missing under --no-learn, cannot be written (before planning), is not a
# Lightning database of this space, or is damaged.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
GEN="$BUILD/earc-scenario"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
command -v jq > /dev/null || { echo "skipped: no jq (tools/setup.sh --tests)"; exit 77; }

"$GEN" generate --family mobile -n 2 --seed 3 -o "$WORK/two.json" > /dev/null || fail "generate"
"$GEN" generate --family arms -n 2 --seed 3 -o "$WORK/arms.json" > /dev/null || fail "generate arms"
DBF="$WORK/two.lightning"

"$PLAN" plan "$WORK/two.json" -o "$WORK/a.json" --method lightning --db "$DBF" --time-limit 20 -q ||
  fail "first plan: exit $?"
[ -s "$DBF" ] || fail "the database file was not created"
jq -e '.solved and .stats.lightning_db_entries == 0 and .stats.lightning_db_added == 1' "$WORK/a.json" > /dev/null ||
  fail "first plan: $(jq -c .stats "$WORK/a.json")"
before=$(md5sum < "$DBF")

"$PLAN" plan "$WORK/two.json" -o "$WORK/b.json" --method lightning --db "$DBF" --no-learn --time-limit 20 --seed 2 -q ||
  fail "second plan: exit $?"
jq -e '.solved and .stats.lightning_db_entries == 1 and .stats.lightning_db_added == 0' "$WORK/b.json" > /dev/null ||
  fail "second plan did not use the file: $(jq -c .stats "$WORK/b.json")"
[ "$(md5sum < "$DBF")" = "$before" ] || fail "--no-learn changed the database file"

# Refusals: one line naming the file, exit 2, nothing written.
refused() {  # what, expected text, command...
  local what=$1 text=$2
  shift 2
  "$@" > "$WORK/out" 2>&1
  local rc=$?
  [ $rc -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l < "$WORK/out")" -eq 1 ] || fail "$what: not one line: $(cat "$WORK/out")"
  grep -q "$text" "$WORK/out" || fail "$what: message lacks '$text': $(cat "$WORK/out")"
}
refused "missing file with --no-learn" "$WORK/none.lightning" \
  "$PLAN" plan "$WORK/two.json" -o "$WORK/c.json" --method lightning --db "$WORK/none.lightning" --no-learn -q
[ -e "$WORK/none.lightning" ] && fail "a missing file was created under --no-learn"
refused "a database of another space" "$DBF" \
  "$PLAN" plan "$WORK/arms.json" -o "$WORK/d.json" --method lightning --db "$DBF" -q
[ "$(md5sum < "$DBF")" = "$before" ] || fail "a refused plan changed the database file"
refused "a file in a missing directory" "no directory $WORK/nodir" \
  "$PLAN" plan "$WORK/two.json" -o "$WORK/d.json" --method lightning --db "$WORK/nodir/x.lightning" -q
[ -e "$WORK/d.json" ] && fail "a plan whose database cannot be written wrote a solution"
echo "not a database" > "$WORK/text.lightning"
refused "a text file" "$WORK/text.lightning" \
  "$PLAN" plan "$WORK/two.json" -o "$WORK/e.json" --method lightning --db "$WORK/text.lightning" -q
[ "$(cat "$WORK/text.lightning")" = "not a database" ] || fail "a refused file was overwritten"
# E-ARC's database given with the same option: said for what it is.
printf 'SQLite format 3\0' > "$WORK/earc.db"
head -c 4080 /dev/zero >> "$WORK/earc.db"
refused "an E-ARC database" "$WORK/earc.db: an SQLite file (an E-ARC experience database?), not a Lightning database" \
  "$PLAN" plan "$WORK/two.json" -o "$WORK/e.json" --method lightning --db "$WORK/earc.db" -q

# A damaged file (bytes changed, cut short) is refused before OMPL, whose
# loader trusts its input, reads it: exit 2, one line, never a crash.
size=$(stat -c %s "$DBF")
damaged=0
for at in 0 9 40 $((size / 3)) $((size / 2)) $((size - 60)) $((size - 30)) $((size - 2)); do
  cp "$DBF" "$WORK/flip.lightning"
  printf 'X' | dd of="$WORK/flip.lightning" bs=1 seek="$at" conv=notrunc status=none
  refused "a byte changed at $at" "$WORK/flip.lightning" \
    "$PLAN" plan "$WORK/two.json" -o "$WORK/f.json" --method lightning --db "$WORK/flip.lightning" --no-learn -q
  head -c "$at" "$DBF" > "$WORK/cut.lightning"
  refused "cut at $at" "$WORK/cut.lightning" \
    "$PLAN" plan "$WORK/two.json" -o "$WORK/f.json" --method lightning --db "$WORK/cut.lightning" --no-learn -q
  damaged=$((damaged + 2))
done

[ $failures -eq 0 ] && echo "lightning --db: created, recalled, refusals one line each ($damaged damaged files)"
exit $((failures > 0))
