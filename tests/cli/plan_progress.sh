#!/bin/bash
# On a terminal, `earc-plan plan` redraws one progress line on stderr
# (method, time of the limit, ARC's conflict and its step, the robots of
# the subproblem being solved) and clears it before the summary; into a
# file or a pipe, and with -q, it prints none. The terminal is script(1)'s
# pseudo-terminal; skipped (77) without script.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needBuilt earc-plan earc-scenario
command -v script > /dev/null || { echo "skipped: no script(1)"; exit 77; }
# 128 robots among obstacles: ARC is still resolving conflicts after a second.
"$BUILD/earc-scenario" generate --family mobile -n 128 --obstacles --seed 3 -o "$WORK/m128.json" > /dev/null ||
  fail "generate"
onTerminal() {  # command line -> what the terminal showed, in $WORK/tty
  script -qec "$1" /dev/null < /dev/null > "$WORK/tty" 2>&1
}

onTerminal "'$BUILD/earc-plan' plan '$WORK/m128.json' -o '$WORK/a.json' --method arc --time-limit 1.5"
grep -aq "planning (arc): [0-9.]* s of 1.5 s, conflict [0-9]* at step [0-9]* of [0-9]*: [0-9]* robots" "$WORK/tty" ||
  fail "no ARC progress line: $(tr '\r' '\n' < "$WORK/tty" | head -c 600)"
# Cleared (carriage return, erase line) right before the summary.
grep -aq $'\r\e\\[Knot solved (time_limit' "$WORK/tty" ||
  grep -aq $'\r\e\\[Ksolved: 128 robots' "$WORK/tty" ||
  fail "the progress line was not cleared before the summary: $(tr '\r' '\n' < "$WORK/tty" | tail -c 400)"

onTerminal "'$BUILD/earc-plan' plan '$WORK/m128.json' -o '$WORK/c.json' --method coupled --time-limit 1"
grep -aq "planning (coupled): [0-9.]* s of 1 s" "$WORK/tty" ||
  fail "no progress line for coupled: $(tr '\r' '\n' < "$WORK/tty" | head -c 600)"

onTerminal "'$BUILD/earc-plan' plan '$WORK/m128.json' -o '$WORK/q.json' --method arc --time-limit 1 -q"
grep -aq "planning (" "$WORK/tty" && fail "-q drew a progress line: $(head -c 300 "$WORK/tty")"

"$BUILD/earc-plan" plan "$WORK/m128.json" -o "$WORK/f.json" --method arc --time-limit 1 > "$WORK/out" 2> "$WORK/err"
grep -aq "planning (" "$WORK/out" "$WORK/err" && fail "a progress line went into a file: $(head -c 300 "$WORK/err")"
grep -q "solution: $WORK/f.json" "$WORK/out" || fail "no summary in the file: $(cat "$WORK/out")"
echo "ok"
