#!/bin/bash
# earc-bench refuses, in one line with exit status 2 and before it changes
# anything on disk, an output directory named like a file (plot -o
# fig.png) or that is a file.
set -u
BUILD=$1
SRC=$2
BENCH="$BUILD/earc-bench"
[ -x "$BENCH" ] || { echo "FAIL: earc-bench not built in $BUILD"; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mkdir "$WORK/d" && cd "$WORK/d" || exit 1

# A results database with one recorded Lightning database in it (a second).
"$BENCH" lightning-db --suite mobile --robots 2 --count 1 --problem-time-limit 0.5 -o l.lightning --results r.sqlite \
  > /dev/null || fail "lightning-db exited $?"
touch a-file
# (A reader of a WAL database may leave an empty -wal and -shm beside it.)
snapshot() { find . -mindepth 1 -printf '%p %s %T@\n' | grep -Ev -- '-(wal|shm) ' | sort; }
snapshot > "$WORK/before"

refused() {  # refused TEXT ARGS...: exit 2, one line on stderr containing TEXT, nothing changed
  local want=$1
  shift
  "$BENCH" "$@" > "$WORK/out" 2> "$WORK/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "earc-bench $* exited $rc, not 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "earc-bench $*: not one line: $(cat "$WORK/err")"
  grep -qF -- "$want" "$WORK/err" || fail "earc-bench $*: the error does not say '$want': $(cat "$WORK/err")"
  snapshot | cmp -s - "$WORK/before" || fail "earc-bench $* changed the directory: $(snapshot | diff "$WORK/before" -)"
}

refused "fig.png: -o: names the directory the files go into, not a .png file" plot --results r.sqlite -o fig.png
refused "a-file: -o: exists and is not a directory" plot --results r.sqlite -o a-file
refused "logs.log: --ompl-log: names the directory the files go into, not a .log file" \
  export --results r.sqlite --ompl-log logs.log
refused "a-file: --ompl-log: exists and is not a directory" export --results r.sqlite --ompl-log a-file
echo "ok"
