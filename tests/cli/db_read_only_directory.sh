#!/bin/bash
# A database in a directory this user may not write to: SQLite cannot make
# the -shm its WAL mode reads through, so every command refuses it with one
# line saying why (copy it somewhere writable); a command that would write
# is refused before any work, saying the directory is not writable; the
# file is unchanged and nothing is left beside it. As root, chmod
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

# Reading: SQLite's WAL mode must make r.db-shm there; refused with one
# line that says so (reading such a file as immutable would trust that
# nobody writes it, which no check at open can promise).
for cmd in "$DB inspect --db" "$DB verify --db" "$DB export -o $WORK/r.jsonl --db" \
  "$PLAN plan $SCEN -o $WORK/sol.json --method earc --no-learn --db"; do
  $cmd "$RO/r.db" > "$WORK/out" 2> "$WORK/err"
  rc=$?
  [ $rc -eq 2 ] || fail "$cmd: exit $rc, expected 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$RO/r.db" "$WORK/err" &&
    grep -qF "cannot read: SQLite needs to make r.db-shm beside it and directory $(cd "$RO" && pwd -P) is not writable" \
      "$WORK/err" || fail "$cmd: $(cat "$WORK/err")"
done

# Writing: refused at once, one line, nothing written.
for cmd in "$PLAN plan $SCEN -o $WORK/sol2.json --method earc --db" "$DB build --count 2 -q --db" \
  "$DB curate --dedupe 0.1 --db"; do
  $cmd "$RO/r.db" > "$WORK/out" 2> "$WORK/err"
  rc=$?
  [ $rc -eq 2 ] || fail "$cmd: exit $rc, expected 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$RO/r.db" "$WORK/err" &&
    grep -qF "cannot write: directory $(cd "$RO" && pwd -P) is not writable" "$WORK/err" || fail "$cmd: $(cat "$WORK/err")"
done
[ -e "$WORK/sol.json" ] || [ -e "$WORK/sol2.json" ] && fail "a refused plan wrote a solution"
[ "$(md5sum < "$RO/r.db")" = "$before" ] || fail "the file changed"

echo "ok"
