#!/bin/bash
# No command overwrites one of its inputs, and no output path is a trap:
# an output that is also an input (or the other output) is refused before
# any work, with one line naming it and exit 2, and every file is left as
# it was; an output in a missing directory is refused before planning; a
# FIFO or a symbolic link given as the output stays what it is; a
# command-line parse error is one line and exit 2 too, and an unsigned
# option refuses a negative number.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
DB="$BUILD/earc-db"
GEN="$BUILD/earc-scenario"
cd "$WORK" || exit 1
cp "$SRC/tests/data/scenarios/swap-discs.json" s.json
cp "$SRC/datasets/movingai/random-32-32-20.map" m.map

"$PLAN" plan s.json -o sol.json -q || fail "plan exited $?"
"$DB" build --db e.db --count 20 --seed 1 > /dev/null 2>&1 || fail "build"
"$DB" export --db e.db -o e.jsonl > /dev/null || fail "export"
sha256sum s.json sol.json m.map e.db e.jsonl > sums

# refused CMD... : exit 2, one line on stderr naming the expected text,
# nothing on disk changed.
refused() {
  local expect=$1
  shift
  "$@" > out 2> err
  local rc=$?
  [ $rc -eq 2 ] || fail "$*: exit $rc, expected 2: $(cat err)"
  [ "$(wc -l < err)" -eq 1 ] || fail "$*: expected one line: $(cat err)"
  grep -qF -- "$expect" err || fail "$*: expected '$expect' in: $(cat err)"
  sha256sum --quiet -c sums || fail "$*: changed a file"
}

refused "s.json: -o: is the same file as the scenario" "$PLAN" plan s.json -o s.json
refused "s.json: --trace: is the same file as the scenario" "$PLAN" plan s.json -o new.json --trace s.json
refused "sol.json: --trace: is the same file as -o" "$PLAN" plan s.json -o sol.json --trace sol.json
refused "./s.json: -o: is the same file as the scenario (s.json)" "$PLAN" plan s.json -o ./s.json
refused "s.json: -o: is the same file as the scenario" "$PLAN" render s.json sol.json -o s.json
refused "sol.json: -o: is the same file as the solution" "$PLAN" view s.json sol.json -o sol.json
refused "e.db: -o: is the same file as --db" "$DB" export --db e.db -o e.db
refused "e.db: input: is the same file as --db" "$DB" import --db e.db e.db
refused "e.db: -o: is the same file as --db" "$DB" curate --db e.db -o e.db
refused "m.map: -o: is the same file as the map" "$GEN" movingai m.map -o m.map
refused "e.db: --report: is the same file as --db" "$DB" build --db e.db --report e.db --count 1
refused "./new.db: --report: is the same file as --db (new.db)" "$DB" build --db new.db --report ./new.db --count 1
refused "s.json: --report: is the same file as --scenario" "$DB" build --db new.db --scenario s.json --report s.json --count 1
[ -e new.db ] && fail "a refused build made new.db"
# A database's -wal and -shm files are part of it (committed rows, locks),
# whether they exist at the moment or not.
refused "e.db-wal: -o: is the -wal file of --db (e.db), part of that database" "$DB" export --db e.db -o e.db-wal
refused "e.db-shm: -o: is the -shm file of --db (e.db)" "$PLAN" plan s.json -o e.db-shm --method earc --db e.db --no-learn
refused "e.db-wal: --trace: is the -wal file of --db (e.db)" "$PLAN" plan s.json -o new.json --trace e.db-wal --method earc --db e.db
refused "e.db-journal: --report: is the -journal file of --db (e.db)" "$DB" build --db e.db --report e.db-journal --count 1
refused "new.db-wal: --db: is the -wal file of -o (new.db)" "$DB" curate --db new.db-wal -o new.db
# Through a link: SQLite keeps the -wal beside the real file.
mkdir real && cp e.db real/e.db && ln -s real/e.db linked.db
refused "real/e.db-wal: -o: is the -wal file of --db (linked.db)" "$DB" export --db linked.db -o real/e.db-wal
rm -rf real linked.db
[ -e e.db-wal ] || [ -e e.db-shm ] && fail "a refused command left e.db-wal or e.db-shm"
ln -s s.json link.json
refused "link.json: -o: is the same file as the scenario (s.json)" "$PLAN" plan s.json -o link.json
[ -e new.json ] && fail "a refused plan wrote new.json"

# A missing directory is found before planning, not after.
refused "nodir/x.json: -o: cannot write: no directory nodir" "$PLAN" plan s.json -o nodir/x.json
refused "nodir/t.json: --trace: cannot write: no directory nodir" "$PLAN" plan s.json -o new.json --trace nodir/t.json
[ -e new.json ] && fail "a refused plan wrote new.json"
# So is a directory that takes no new file, as /proc takes none even from
# root: it said "/proc/version: cannot write in /proc: No such file or
# directory" after planning, of a file that exists, without the option.
refused "/proc/version: -o: cannot replace it: cannot write in /proc: " "$PLAN" plan s.json -o /proc/version
grep -qF "No such file" err && fail "-o /proc/version: says a file is missing: $(cat err)"
refused "/proc/new.json: --trace: cannot write in /proc: " "$PLAN" plan s.json -o new.json --trace /proc/new.json
[ -e new.json ] && fail "a refused plan wrote new.json"
mkdir adir
refused "adir: -o: is a directory, not a file" "$PLAN" plan s.json -o adir
refused "adir: -o: is a directory, not a file" "$GEN" generate -n 2 -o adir
refused "adir: --report: is a directory, not a file" "$DB" build --db new.db --report adir --count 1
refused "nodir/r.txt: --report: cannot write: no directory nodir" "$DB" build --db new.db --report nodir/r.txt --count 1
[ -e new.db ] && fail "a refused build made new.db"

# Parse errors: one line, exit 2.
refused "earc-plan: error:" "$PLAN" plan s.json -o x.json --no-such-option
refused "--window" "$PLAN" plan s.json -o x.json --window 0
# An empty file name is refused as such, not found wanting after planning.
refused "--output: an empty file name" "$PLAN" plan s.json -o ""
refused "--db: an empty file name" "$PLAN" plan s.json -o x.json --method earc --db ""
refused "--db: an empty file name" "$DB" inspect --db ""
# Counts take digits only: CLI11 alone read 0x10 as 16 and called 1e3 out of range.
refused "--window: '0x10' is not a whole number in 1..1000000" "$PLAN" plan s.json -o x.json --window 0x10
refused "--window: '1e3' is not a whole number in 1..1000000" "$PLAN" plan s.json -o x.json --window 1e3
refused "--time-per-problem" "$DB" build --db other.db --time-per-problem nan
refused "--radius: is for --shape disc" "$DB" build --db other.db --radius 0.3
refused "--radius: is for --shape disc" "$DB" build --db other.db --size 1x1 --radius 0.3 --report r.txt
[ -e r.txt ] && fail "a refused build made its report"
# Unsigned options refuse a sign instead of wrapping -1 to 2^64-1.
refused "--seed: '-1' is not a whole number" "$DB" build --db other.db --seed -1
refused "--seed: '99999999999999999999999' is more than 18446744073709551615" "$PLAN" plan s.json -o x.json --seed 99999999999999999999999
refused "--seed: '-1' is not a whole number" "$PLAN" plan s.json -o x.json --seed -1
refused "--seed: '-1' is not a whole number" "$GEN" generate -n 2 -o x.json --seed -1
refused "--seed: '+3' is not a whole number" "$GEN" movingai m.map -n 2 -o x.json --seed +3
refused "--step: '-1' is not a whole number" "$PLAN" render s.json sol.json -o x.svg --step -1
refused "--seed: '-2' is not a whole number" "$BUILD/earc-bench" run --seed -2 --db x.sqlite
[ -e x.json ] && fail "a refused command wrote x.json"
[ -e other.db ] && fail "a refused build made other.db"

# A symbolic link given as the output stays a link; its target is written.
echo old > target.json
ln -s target.json out-link.json
"$PLAN" plan s.json -o out-link.json -q || fail "plan through a link exited $?"
[ -L out-link.json ] || fail "the link was replaced by a file"
"$PLAN" validate s.json target.json > /dev/null || fail "the link's target does not hold the solution"
# ... also when the target does not exist yet (it is created, as `> link`
# would), and a target in a missing directory is refused like any output.
ln -s new-target.json dangling.json
"$PLAN" plan s.json -o dangling.json -q || fail "plan through a dangling link exited $?"
[ -L dangling.json ] || fail "the dangling link was replaced by a file"
"$PLAN" validate s.json new-target.json > /dev/null || fail "the dangling link's new target does not hold the solution"
ln -s nodir/t.json nowhere.json
refused "nowhere.json: -o: cannot write: no directory nodir" "$PLAN" plan s.json -o nowhere.json
[ -L nowhere.json ] || fail "a refused plan replaced the link"

# A FIFO given as the output stays a FIFO, and its reader gets the solution.
mkfifo pipe
timeout 20 cat pipe > from-pipe &
reader=$!
"$PLAN" plan s.json -o pipe -q || fail "plan into a FIFO exited $?"
wait $reader
[ -p pipe ] || fail "the FIFO was replaced by a file"
"$PLAN" validate s.json from-pipe > /dev/null || fail "the FIFO's reader did not get the solution"

# -o /dev/stdout: the file is all that reaches stdout; the summary line,
# which used to follow it there, goes to stderr.
"$PLAN" plan s.json -o /dev/stdout > piped.json 2> err || fail "plan -o /dev/stdout exited $?"
"$PLAN" validate s.json piped.json > /dev/null || fail "plan -o /dev/stdout: stdout is not the solution"
grep -q "^solution: /dev/stdout" err || fail "plan -o /dev/stdout: no summary on stderr: $(cat err)"
"$GEN" generate -n 2 -o /dev/stdout > piped.json 2> /dev/null || fail "generate -o /dev/stdout exited $?"
/usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' piped.json || fail "generate -o /dev/stdout: not JSON"
"$DB" export --db e.db -o /dev/stdout > piped.jsonl 2> /dev/null || fail "export -o /dev/stdout exited $?"
cmp -s piped.jsonl e.jsonl || fail "export -o /dev/stdout: stdout is not the export"
"$PLAN" render s.json sol.json -o /dev/stdout > piped.svg 2> /dev/null || fail "render -o /dev/stdout exited $?"
[ "$(tail -n 1 piped.svg)" = "</svg>" ] || fail "render -o /dev/stdout: stdout does not end with the picture"
# A regular output still reports on stdout.
"$PLAN" plan s.json -o again.json > out 2> err || fail "plan exited $?"
grep -q "^solution: again.json" out || fail "plan: the summary left stdout: $(cat out)"
echo "ok"
