# Shared by the command-line tests (not a test itself: CTest runs *.sh).
# Sourced right after `BUILD=$1` (and `SRC=$2`): makes them absolute, so
# that a test run as `tests/cli/T.sh build .` works too; sets PY, a default
# fail, a scratch directory $WORK removed on exit (a test that sets its own
# EXIT trap removes it there), and the checks below.
PY=/usr/bin/python3
BUILD=$(cd "$BUILD" && pwd) || { echo "FAIL: no build directory $1"; exit 1; }
if [ -n "${SRC:-}" ]; then SRC=$(cd "$SRC" && pwd) || { echo "FAIL: no source directory $SRC"; exit 1; }; fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# Makes fail also show the last lines of $WORK/out and $WORK/err, where a
# test leaves the output of the command it checks.
failShowsOutput() { fail() { echo "FAIL: $*"; tail -n 20 "$WORK/out" "$WORK/err" 2>/dev/null; exit 1; }; }
# Skipped (77) without /usr/bin/python3.
needPython() { [ -x "$PY" ] || { echo "skipped: no $PY"; exit 77; }; }
# Sets CXX (default c++); skipped (77) without that compiler.
needCompiler() { CXX=${CXX:-c++}; command -v "$CXX" > /dev/null || { echo "skipped: no $CXX"; exit 77; }; }
# True when $PY has matplotlib and numpy (the plot scripts' needs).
hasMatplotlib() { "$PY" -c "import matplotlib, numpy" 2> /dev/null; }
# Skipped (77) without /usr/bin/python3 with matplotlib.
needMatplotlib() { needPython; hasMatplotlib || { echo "skipped: no matplotlib for $PY"; exit 77; }; }
# sqlValue FILE SQL: the first value of the query's first row, FILE (an
# SQLite database) opened read-only.
sqlValue() {
  "$PY" -c 'import sqlite3, sys
print(sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True).execute(sys.argv[2]).fetchone()[0])' "$@"
}
# refusedInOneLine WANT PROGRAM ARGS...: FAIL unless PROGRAM exits 2 with
# one line on stderr that contains WANT (left in $WORK/err).
refusedInOneLine() {
  local want=$1
  shift
  "$@" > "$WORK/out" 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "$* exited $rc, not 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "$*: not one line: $(cat "$WORK/err")"
  grep -qF -- "$want" "$WORK/err" || fail "$*: the error does not say '$want': $(cat "$WORK/err")"
}
# The current directory's files, sizes and times, to compare before and
# after a command that must change nothing (a reader of a WAL database may
# leave an empty -wal and -shm beside it: those are left out).
dirSnapshot() { find . -mindepth 1 -printf '%p %s %T@\n' | grep -Ev -- '-(wal|shm) ' | sort; }
# endsWithin PID SECONDS WHAT: waits up to SECONDS for process PID to end;
# else kills it (SIGKILL) and FAILs saying WHAT did not stop in time.
endsWithin() {
  local _
  for _ in $(seq 1 $(($2 * 10))); do
    kill -0 "$1" 2> /dev/null || return 0
    sleep 0.1
  done
  kill -KILL "$1"
  fail "$3 did not stop within $2 s"
}
# FAIL unless every program named is built in $BUILD.
needBuilt() {
  local p
  for p in "$@"; do
    [ -x "$BUILD/$p" ] || { echo "FAIL: $p not built in $BUILD"; exit 1; }
  done
}
# FAIL unless nothing is left beside the SQLite file $1 (no -wal, no
# -shm) after the step named $2: reading a closed file of ours leaves none.
leftNothingBeside() {
  local f
  for f in "$1-wal" "$1-shm"; do
    [ -e "$f" ] && fail "$2 left $(basename "$f") beside $(basename "$1")"
  done
  return 0
}
# Writes $1: a stand-in for earc-plan whose `plan` writes a solution in
# which every robot jumps from start to goal in one step (INVALID); its
# other subcommands are $BUILD/earc-plan's.
writeTeleportingPlanner() {
  cat > "$1" <<FAKE
#!/bin/bash
if [ "\$1" != plan ]; then exec "$BUILD/earc-plan" "\$@"; fi
scenario=\$2; out=""
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
exec "$PY" -c 'import json,sys
s = json.load(open(sys.argv[1]))
paths = [{"robot": r["name"], "states": [r["start"], r["goal"]]} for r in s["robots"]]
json.dump({"format": "earc.solution.v1", "scenario": s["name"], "method": "arc", "solved": True,
           "paths": paths, "stats": {"planning_time_s": 0.01}}, open(sys.argv[2], "w"))' "\$scenario" "\$out"
FAKE
  chmod +x "$1"
}
# Writes $1: a stand-in for earc-plan whose `plan` misreports. $2 says
# how: "exit1" plans (validly) and then exits 1, so that the exit status
# disagrees with the solution's solved flag; "silent" prints "out of
# luck" on stderr and exits 1 without writing a solution. Its other
# subcommands are $BUILD/earc-plan's.
writeMisreportingPlanner() {
  cat > "$1" <<FAKE
#!/bin/bash
if [ "\$1" != plan ]; then exec "$BUILD/earc-plan" "\$@"; fi
FAKE
  case $2 in
    exit1) echo "\"$BUILD/earc-plan\" \"\$@\"; exit 1" >> "$1" ;;
    silent) echo 'echo "out of luck" >&2; exit 1' >> "$1" ;;
    *) fail "writeMisreportingPlanner: no such way to misreport: $2" ;;
  esac
  chmod +x "$1"
}
# Runs `$BUILD/earc-plan plan "$@"`, timed: sets RC (its exit status) and
# WALL (its seconds by the wall clock, start-up and writing included).
timedPlan() {
  local start
  start=$(date +%s.%N)
  "$BUILD/earc-plan" plan "$@"
  RC=$?
  WALL=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
}
# Checks the solution $2 of the plan timedPlan ran last (named $1 in what
# it says): planned for at most $3 s by its own clock and ran for at most
# $4 s, and if unsolved, exited 1 saying the time limit was why. Needs jq.
checkTimedPlan() {
  local name=$1 out=$2 own_max=$3 wall_max=$4 own solved
  [ -f "$out" ] || { fail "$name: no solution file (exit $RC)"; return 1; }
  own=$(jq '.stats.planning_time_s' "$out")
  solved=$(jq '.solved' "$out")
  echo "$name: exit $RC, solved $solved, planning_time_s $own, wall $WALL s"
  awk -v t="$own" -v m="$own_max" 'BEGIN { exit !(t <= m) }' || fail "$name planned for $own s (at most $own_max s)"
  awk -v t="$WALL" -v m="$wall_max" 'BEGIN { exit !(t <= m) }' || fail "$name ran for $WALL s (at most $wall_max s)"
  if [ "$solved" = false ]; then
    [ "$RC" -eq 1 ] || fail "$name unsolved: exit $RC, expected 1"
    jq -e '.stats.failure | index("time_limit")' "$out" > /dev/null ||
      fail "$name: unsolved but not for the time limit: $(jq -c .stats.failure "$out")"
  fi
}
# Writes on stdout a scenario of two facing arms of $1 links (2.5 long in
# all, radius 0.3 of a link) that sweep through each other from up to
# down: the straight motions collide.
# $2 bounds every joint but the first (0: the full circle).
manyLinkArms() {
  awk -v n="$1" -v lim="$2" 'BEGIN {
    pi = atan2(0, -1); L = 2.5 / n; if (lim == 0) lim = pi
    printf "{\"format\": \"earc.scenario.v1\", \"name\": \"many-links\", \"workspace\": {\"min\": [0, 0], \"max\": [10, 10]}, \"robots\": ["
    for (a = 0; a < 2; a++) {
      printf "%s{\"name\": \"a%d\", \"type\": \"manipulator\", \"base\": [%s, 5, %.17g], \"link_radius\": %.17g, \"links\": [", (a ? ", " : ""), a, (a ? 7 : 3), (a ? pi : 0), 0.3 * L
      for (i = 0; i < n; i++) printf "%s%.17g", (i ? ", " : ""), L
      printf "], \"joint_limits\": [[%.17g, %.17g]", -pi, pi
      for (i = 1; i < n; i++) printf ", [%.17g, %.17g]", -lim, lim
      s = (a ? -pi / 2 : pi / 2)
      printf "], \"start\": [%.17g", s
      for (i = 1; i < n; i++) printf ", 0"
      printf "], \"goal\": [%.17g", -s
      for (i = 1; i < n; i++) printf ", 0"
      printf "]}"
    }
    print "]}"
  }'
}
