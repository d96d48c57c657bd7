#!/bin/bash
# label: bench
# Trials that crash, hang or return an invalid solution are failures, and
# the run goes on: a planner child that dies of SIGSEGV and one that never
# returns (test faults, EARC_BENCH_FAULT=METHOD:crash|hang), and a planner
# (a stand-in for earc-plan) whose solution teleports, which must be
# reported loudly. Bad options and unusable databases, on the other hand,
# are refused before any trial runs, and recorded nowhere. Skipped (77)
# without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
PLAN="$BUILD/earc-plan"
needPython
needBuilt earc-bench earc-plan
query() {
  "$PY" -c 'import sqlite3,sys
c = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
for r in c.execute(sys.argv[2]): print("|".join("" if v is None else str(v) for v in r))' "$1" "$2"
}
BASE=(run --suites mobile --robots 2 --trials 1 --seed 5)

# A crash.
EARC_BENCH_FAULT=arc:crash "$BENCH" "${BASE[@]}" --methods arc,prioritized --time-limit 10 \
  --results "$WORK/crash.sqlite" > "$WORK/crash.out" 2>&1 || fail "run with a crashing trial exited $?"
got=$(query "$WORK/crash.sqlite" "SELECT method, success, term_signal, failure FROM trials ORDER BY method")
echo "$got" | grep -q "^arc|0|11|crashed: SIGSEGV" || fail "crash not recorded as such: $got"
echo "$got" | grep -q "^prioritized|" || fail "the run stopped at the crash: $got"

# A hang, killed at the time limit plus the margin.
start=$(date +%s)
EARC_BENCH_FAULT=prioritized:hang "$BENCH" "${BASE[@]}" --methods prioritized --time-limit 1 --wall-margin 1 \
  --results "$WORK/hang.sqlite" > "$WORK/hang.out" 2>&1 || fail "run with a hanging trial exited $?"
[ $(( $(date +%s) - start )) -lt 30 ] || fail "the hanging trial was not killed in time"
got=$(query "$WORK/hang.sqlite" "SELECT success, term_signal, failure, wall_time_s < 5 FROM trials")
echo "$got" | grep -q "^0|9|killed at the wall-clock limit (2 s)|1" || fail "hang not recorded as such: $got"

# An invalid solution: every robot jumps from start to goal in one step.
writeTeleportingPlanner "$WORK/fake-plan"
"$BENCH" "${BASE[@]}" --methods arc --time-limit 10 --plan-program "$WORK/fake-plan" \
  --results "$WORK/invalid.sqlite" > "$WORK/invalid.out" 2> "$WORK/invalid.err"
rc=$?
[ $rc -eq 1 ] || fail "a run with an invalid solution exited $rc, not 1"
grep -q "^INVALID SOLUTION: mobile, 2 robots, method arc, trial 0: INVALID" "$WORK/invalid.err" \
  || fail "no loud report: $(cat "$WORK/invalid.err")"
got=$(query "$WORK/invalid.sqlite" "SELECT success, failure FROM trials")
echo "$got" | grep -q "^0|invalid solution: INVALID" || fail "invalid solution not recorded as a failure: $got"

# A planner whose exit status disagrees with its solution, and one that
# writes none: trial failures that say which (compare shares the check).
for how in exit1 silent; do
  writeMisreportingPlanner "$WORK/$how-plan" $how
  "$BENCH" "${BASE[@]}" --methods arc --time-limit 10 --plan-program "$WORK/$how-plan" \
    --results "$WORK/$how.sqlite" > "$WORK/$how.out" 2>&1 || fail "a run with a planner that misreports ($how) exited $?"
done
got=$(query "$WORK/exit1.sqlite" "SELECT success, exit_status, failure FROM trials")
[ "$got" = "0|1|exit status 1 disagrees with the solution's solved flag" ] || fail "exit 1 with a solved plan: $got"
got=$(query "$WORK/silent.sqlite" "SELECT success, exit_status, failure FROM trials")
[ "$got" = "0|1|exit 1 without a readable solution: out of luck" ] || fail "exit 1 without a solution: $got"

# Configuration errors are not trial failures: bad options, and an E-ARC
# database that was given but cannot be read (a foreign SQLite file, a
# newer schema), end the run before any trial with one line naming the
# option or file and exit status 2, and record nothing, so that a resumed
# run does not skip trials that never ran.
refused() {  # refused TEXT ARGS...: exit 2, one line on stderr containing TEXT
  local want=$1
  shift
  timeout 120 "$BENCH" "$@" > "$WORK/bad.out" 2> "$WORK/bad.err"
  local rc=$?
  [ $rc -eq 2 ] || fail "earc-bench $* exited $rc, not 2: $(cat "$WORK/bad.err")"
  [ "$(wc -l < "$WORK/bad.err")" -eq 1 ] || fail "earc-bench $*: not one line: $(cat "$WORK/bad.err")"
  grep -qF -- "$want" "$WORK/bad.err" || fail "earc-bench $*: the error does not say '$want': $(cat "$WORK/bad.err")"
}
"$PY" -c 'import sqlite3,sys
c = sqlite3.connect(sys.argv[1]); c.execute("CREATE TABLE t(x)"); c.commit()
c = sqlite3.connect(sys.argv[2]); c.execute("CREATE TABLE t(x)")
c.execute("PRAGMA application_id = %d" % 0x45415243); c.execute("PRAGMA user_version = 99"); c.commit()' \
  "$WORK/foreign.db" "$WORK/newer.db"
R=(run --suites mobile --methods earc,arc --trials 1 --results "$WORK/bad.sqlite")
refused "$WORK/foreign.db: --db-mobile: not a usable E-ARC database: not an earc experience database" \
  "${R[@]}" --robots 2 --db-mobile "$WORK/foreign.db"
refused "$WORK/newer.db: --db-mobile: not a usable E-ARC database: schema version 99 is newer" \
  "${R[@]}" --robots 2 --db-mobile "$WORK/newer.db"
refused "/nonexistent: --plan-program: no such file" "${R[@]}" --robots 2 --plan-program /nonexistent
refused "$WORK/foreign.db: --plan-program: not an executable program" "${R[@]}" --robots 2 --plan-program "$WORK/foreign.db"
refused "--robots: empty item in '2,,4'" "${R[@]}" --robots 2,,4
refused "--robots: no suite of this run has 1000 robots (mobile: 2, 4, 8, 16, 32)" "${R[@]}" --robots 1000
refused "--robots: no suite of this run has 3 robots (mobile: 2, 4, 8, 16, 32; arms: 2, 4, 8, 16)" \
  run --suites mobile,arms --robots 2,3 --results "$WORK/bad.sqlite"
refused "--methods: empty item in 'arc,'" run --suites mobile --robots 2 --methods arc, --results "$WORK/bad.sqlite"
for bad in "--memory-limit-mb 0" "--memory-limit-mb -5" "--wall-margin -5" "--wall-margin nan" "--earc-db-count 0" "--earc-db-count -3" \
           "--lightning-problems -1" "--lightning-problems-per-robot 0" "--lightning-problem-time-limit -1" \
           "--lightning-problem-time-limit nan" "--time-limit nan" "--time-limit -1" "--time-limit inf" "--trials 0" "--jobs 0" \
           "--trials -2" "--lightning-problems 0"; do
  # shellcheck disable=SC2086  # "--option value" splits in two
  refused "${bad% *}:" "${R[@]}" --robots 2 $bad
done
# A count for the E-ARC databases the run builds, beside one it is given
# (which it uses as it is, or builds with earc-db's default count): it
# would be ignored for that one, so the pair is refused.
for db in --db-mobile --db-arms; do
  refused "--earc-db-count: is for the E-ARC databases the run builds itself, and $db names one instead" \
    "${R[@]}" --robots 2 $db "$WORK/given.db" --earc-db-count 5
done
[ -e "$WORK/given.db" ] && fail "a refused run built the E-ARC database it was given"
# E-ARC's database options where nothing would use them: no earc trials,
# or no robots of that kind.
refused "--earc-db-count: is for method earc, which this run does not plan with (--methods)" \
  run --suites mobile --robots 2 --methods arc --earc-db-count 5 --results "$WORK/bad.sqlite"
refused "--db-mobile: is for method earc, which this run does not plan with (--methods)" \
  run --suites mobile --robots 2 --methods arc,prioritized --db-mobile "$WORK/given.db" --results "$WORK/bad.sqlite"
refused "--db-arms: this run plans for no arms (its suites or scenario files), so it would not be used" \
  run --suites mobile --robots 2 --methods earc --db-arms "$WORK/given.db" --results "$WORK/bad.sqlite"
refused "--db-mobile: this run plans for no mobile robots (its suites or scenario files), so it would not be used" \
  run --suites arms --robots 2 --methods earc --db-mobile "$WORK/given.db" --results "$WORK/bad.sqlite"
[ -e "$WORK/bad.sqlite" ] && fail "a refused run created its results database"
[ -e "$WORK/bad.sqlite.work" ] && fail "a refused run created its work directory"

# The same for lightning-db: the option named as given, and the results
# database checked before the Lightning database is built.
refused "--suite: unknown suite 'bogus'" lightning-db --suite bogus -o "$WORK/l.lightning"
refused "$WORK/foreign.db: not an earc-bench results database" \
  lightning-db --suite mobile --robots 2 --count 1 -o "$WORK/l.lightning" --results "$WORK/foreign.db"
[ -e "$WORK/l.lightning" ] && fail "lightning-db built its database before refusing --results"
refused "--count: '0' is not a whole number >= 1" lightning-db --suite mobile --count 0 -o "$WORK/l.lightning"
refused "--problem-time-limit: 'nan' is not a finite number" \
  lightning-db --suite mobile --problem-time-limit nan -o "$WORK/l.lightning"
refused "$WORK/l.lightning: -o: is the --results file" lightning-db --suite mobile -o "$WORK/l.lightning" --results "$WORK/l.lightning"
# No micro benchmark of 0 batches or of batches 0 s long ("inf checks/s").
refused "--repeats: '0' is not a whole number >= 1" micro --repeats 0
for bad in 0 nan -1 0.000001; do refused "--batch-seconds:" micro --batch-seconds $bad; done
echo "ok: crash, hang and invalid solution are failures; configuration errors are not"
