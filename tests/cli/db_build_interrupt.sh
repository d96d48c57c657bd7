#!/bin/bash
# earc-db build and Ctrl-C: SIGINT, once a build that would run for
# minutes has committed rows, stops it within seconds with exit 130 and
# one line saying how many entries were kept; the file verifies and
# holds them, they are those of a whole build of the problems it got
# through, and --report logged each of them. SIGTERM exits 143 and adds
# to the file. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-db
failShowsOutput
cd "$WORK" || exit 1
DB="$BUILD/earc-db"

# interrupt SIGNAL EXPECTED_STATUS REPORT ARGS...: starts `earc-db build
# --report REPORT ARGS`, sends SIGNAL once it has committed rows, and
# leaves its stderr in err, the kept count in $kept and the problems it
# got through in $through.
interrupt() {
  local sig=$1 want=$2 report=$3
  shift 3
  "$DB" build --report "$report" "$@" > out 2> err &
  local pid=$!
  for _ in $(seq 1 600); do
    [ -s "$report" ] && break
    kill -0 $pid 2> /dev/null || fail "the build ended before $sig"
    sleep 0.1
  done
  [ -s "$report" ] || fail "no rows committed within 60 s"
  kill -"$sig" $pid
  endsWithin $pid 15 "the build, after $sig,"
  wait $pid
  local status=$?
  [ $status -eq "$want" ] || fail "exit $status after $sig, not $want"
  local said
  said=$(grep -c "interrupted" err)
  [ "$said" -eq 1 ] || fail "$said lines say interrupted, not one"
  line=$(grep "interrupted" err)
  [[ $line == "earc-db build: interrupted (SIG$sig): kept "*" entries from the first "*" of 1000000 problems in "* ]] ||
    fail "unexpected line: $line"
  kept=$(sed -E 's/.*kept ([0-9]+) entries.*/\1/' <<< "$line")
  through=$(sed -E 's/.*the first ([0-9]+) of.*/\1/' <<< "$line")
  [ "$kept" -gt 0 ] || fail "nothing kept after rows were committed: $line"
}

interrupt INT 130 ids --db b.db --count 1000000 --threads 2 --deterministic --seed 5 -q
first=$kept
"$DB" verify --db b.db > out 2> err || fail "verify after SIGINT"
rows=$("$DB" inspect --db b.db --json | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["entries"])') ||
  fail "inspect after SIGINT"
[ "$rows" -eq "$first" ] || fail "inspect shows $rows entries, the build said it kept $first"
logged=$(wc -w < ids)
[ "$logged" -eq "$first" ] || fail "--report logged $logged ids for $first entries kept"

# The kept rows are those of a whole build of the problems it got through.
"$DB" build --db whole.db --count "$through" --threads 2 --deterministic --seed 5 -q || fail "the whole build"
whole=$("$DB" inspect --db whole.db --json | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["entries"])')
[ "$whole" -eq "$first" ] || fail "a whole build of $through problems holds $whole entries, the interrupted $first"

interrupt TERM 143 ids2 --db b.db --count 1000000 --threads 1 --seed 6 -q
"$DB" verify --db b.db > out 2> err || fail "verify after SIGTERM"
rows=$("$DB" inspect --db b.db --json | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["entries"])')
[ "$rows" -eq $((first + kept)) ] || fail "$rows entries after SIGTERM, not $first + $kept"
echo "ok: SIGINT kept $first entries (exit 130), SIGTERM $kept more (exit 143); the file verifies"
