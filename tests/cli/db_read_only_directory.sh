#!/bin/bash
# A database in a directory nobody may write to (a shared, read-only copy):
# every command that only reads it works (inspect, verify, export, import
# from it, E-ARC with --no-learn) and leaves nothing beside it; a command
# that would write is refused before any work, with one line saying the
# directory is not writable, and the file is unchanged. As root, chmod
# does not stop writes: the directory is made immutable (chattr +i), and
# the test is skipped where neither works.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-db earc-plan
DB="$BUILD/earc-db"
PLAN="$BUILD/earc-plan"
SCEN="$SRC/tests/data/scenarios/swap-discs.json"
RO="$WORK/ro"
mkdir "$RO"
"$DB" build --db "$RO/r.db" --scenario "$SCEN" --count 20 --seed 3 --threads 1 -q || fail "build"
before=$(md5sum < "$RO/r.db")
chmod a-w "$RO"
immutable=0
if touch "$RO/probe" 2> /dev/null; then
  rm -f "$RO/probe"
  chmod u+w "$RO"
  chattr +i "$RO" 2> /dev/null && immutable=1
  if [ $immutable -eq 0 ] || touch "$RO/probe" 2> /dev/null; then
    [ $immutable -eq 1 ] && chattr -i "$RO"
    echo "skipped: cannot make a directory read-only here"
    exit 77
  fi
fi
trap '[ $immutable -eq 1 ] && chattr -i "$RO"; chmod -R u+w "$WORK"; rm -rf "$WORK"' EXIT

"$DB" inspect --db "$RO/r.db" > "$WORK/out" 2> "$WORK/err" || fail "inspect: $(cat "$WORK/err")"
grep -q "^database  $RO/r.db" "$WORK/out" || fail "inspect: $(head -3 "$WORK/out")"
"$DB" verify --db "$RO/r.db" > "$WORK/out" 2> "$WORK/err" || fail "verify: $(cat "$WORK/err")"
"$DB" export --db "$RO/r.db" -o "$WORK/r.jsonl" -q || fail "export exited $?"
"$DB" import --db "$WORK/copy.db" "$RO/r.db" -q || fail "import from it exited $?"
"$PLAN" plan "$SCEN" -o "$WORK/sol.json" --method earc --db "$RO/r.db" --no-learn -q || fail "plan --no-learn exited $?"
"$PLAN" validate "$SCEN" "$WORK/sol.json" > /dev/null || fail "plan --no-learn: not valid"

# Writing: refused at once, one line, nothing written.
for cmd in "$PLAN plan $SCEN -o $WORK/sol2.json --method earc --db" "$DB build --count 2 -q --db" \
  "$DB curate --dedupe 0.1 --db"; do
  $cmd "$RO/r.db" > "$WORK/out" 2> "$WORK/err"
  rc=$?
  [ $rc -eq 2 ] || fail "$cmd: exit $rc, expected 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$RO/r.db" "$WORK/err" &&
    grep -qF "cannot write: directory $RO is not writable" "$WORK/err" || fail "$cmd: $(cat "$WORK/err")"
done
[ -e "$WORK/sol2.json" ] && fail "a refused plan wrote a solution"
[ "$(md5sum < "$RO/r.db")" = "$before" ] || fail "the file changed"
leftNothingBeside "$RO/r.db" "reading a read-only directory"
echo "ok"
