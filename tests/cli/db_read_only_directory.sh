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

# Another user, for whom the directory and the file are read-only by their
# mode alone: SQLite opens the file read-only and says "attempt to write a
# readonly database" where root's open said "unable to open"; the same one
# line either way. Needs root to become nobody, and a way for nobody to
# the programs and the work directory; skipped otherwise.
if [ "$(id -u)" -eq 0 ] && command -v runuser > /dev/null && id nobody > /dev/null 2>&1; then
  chmod 755 "$WORK"
  NOBODY_RO="$WORK/nobody-ro"
  mkdir "$NOBODY_RO" "$WORK/out-any"
  cp "$RO/r.db" "$NOBODY_RO/r.db"
  chmod 755 "$NOBODY_RO"
  chmod 644 "$NOBODY_RO/r.db"
  chmod 777 "$WORK/out-any"
  cp "$SCEN" "$WORK/scen.json" && chmod 644 "$WORK/scen.json"
  if runuser -u nobody -- test -x "$DB" -a -r "$NOBODY_RO/r.db" 2> /dev/null; then
    before_nobody=$(md5sum < "$NOBODY_RO/r.db")
    for cmd in "$DB inspect --db" "$DB verify --db" "$DB export -o $WORK/out-any/r.jsonl --db" \
      "$PLAN plan $WORK/scen.json -o $WORK/out-any/sol.json --method earc --no-learn --db"; do
      runuser -u nobody -- $cmd "$NOBODY_RO/r.db" > "$WORK/out" 2> "$WORK/err"
      rc=$?
      [ $rc -eq 2 ] || fail "as nobody, $cmd: exit $rc, expected 2: $(cat "$WORK/err")"
      [ "$(wc -l < "$WORK/err")" -eq 1 ] &&
        grep -qF "cannot read: SQLite needs to make r.db-shm beside it and directory $(cd "$NOBODY_RO" && pwd -P) is not writable" \
          "$WORK/err" || fail "as nobody, $cmd: $(cat "$WORK/err")"
    done
    [ "$(md5sum < "$NOBODY_RO/r.db")" = "$before_nobody" ] || fail "the file changed (as nobody)"
    [ -e "$WORK/out-any/sol.json" ] && fail "a refused plan wrote a solution (as nobody)"
  else
    echo "note: nobody cannot reach $DB here; the other user's case was not run"
  fi
fi

echo "ok"
