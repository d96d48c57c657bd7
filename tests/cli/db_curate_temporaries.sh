#!/bin/bash
# A curate killed part way leaves OUT.tmp.PID (and -wal, -shm) beside its
# output: the next curate to that output removes those of a process that
# is gone, and leaves a live process's temporary (it may still be working)
# and files that only look alike (export's OUT.tmp.PID.RANDOM) alone.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
DB="$BUILD/earc-db"
needBuilt earc-db
live=
trap '[ -n "$live" ] && kill "$live" 2> /dev/null; rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1

"$DB" build --db e.db --count 5 --seed 1 > /dev/null 2>&1 || fail "build"
# A PID that was alive a moment ago and is not any more, and a live one.
sh -c 'exit 0' &
dead=$!
wait "$dead"
kill -0 "$dead" 2> /dev/null && fail "PID $dead still alive"
sleep 600 &
live=$!
for f in "copy.db.tmp.$dead" "copy.db.tmp.$dead-wal" "copy.db.tmp.$dead-shm" "copy.db.tmp.$live" \
         "copy.db.tmp.$live-wal" "copy.db.tmp.$dead.12345" "other.db.tmp.$dead"; do
  echo stale > "$f"
done

"$DB" curate --db e.db -o copy.db > out 2> err || fail "curate exited $?: $(cat err)"
[ -s err ] && fail "curate wrote to stderr: $(cat err)"
for f in "copy.db.tmp.$dead" "copy.db.tmp.$dead-wal" "copy.db.tmp.$dead-shm"; do
  [ -e "$f" ] && fail "the dead process's $f is still there"
done
for f in "copy.db.tmp.$live" "copy.db.tmp.$live-wal" "copy.db.tmp.$dead.12345" "other.db.tmp.$dead"; do
  [ "$(cat "$f" 2> /dev/null)" = stale ] || fail "$f was touched"
done
"$DB" verify --db copy.db > /dev/null || fail "the copy does not verify"
# And no temporary of its own is left behind.
ls copy.db.tmp.* | grep -qv -e "\.$live" -e "\.$dead\.12345" && fail "temporaries left: $(ls copy.db.tmp.*)"
echo "ok"
