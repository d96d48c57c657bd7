#!/bin/bash
# label: bench
# A quick benchmark end to end: mobile robots, 2 and 4 of them, methods arc,
# prioritized and lightning, 2 trials per cell under a short limit (the
# Lightning databases are built on the way); then the table, the CSV and
# the OMPL benchmark logs must be well formed (a CSV on stdout alone, its
# summary on stderr; trials of two time limits in tables of their own),
# plot must draw the figures and refuse bad input (a value no run writes
# too) in one line, and a second run must find nothing left
# to do. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
fail() { echo "FAIL: $*"; sed 's/^/  run: /' "$WORK/run.out" "$WORK/run.err" 2>/dev/null | tail -40; exit 1; }
# Writes $2: a copy of the results file $1 changed by the SQL statements
# that follow, as other runs or a hand edit may leave a file.
changedCopy() {
  "$PY" - "$@" <<'PYEOF' || fail "could not make $2"
import sqlite3, sys
src, dst = sqlite3.connect(sys.argv[1]), sqlite3.connect(sys.argv[2])
src.backup(dst)
for statement in sys.argv[3:]:
    dst.execute(statement)
dst.commit()
PYEOF
}

RUN=(run --suites mobile --robots 2,4 --methods arc,prioritized,lightning --trials 2 --time-limit 10 --seed 7
     --results "$WORK/r.sqlite" --lightning-problems 3 --lightning-problem-time-limit 5)
"$BENCH" "${RUN[@]}" > "$WORK/run.out" 2> "$WORK/run.err" || fail "earc-bench run exited $?"
grep -q "INVALID SOLUTION" "$WORK/run.err" && fail "a planner produced an invalid solution"
grep -q "^### mobile" "$WORK/run.out" || fail "no table after the run"

# Every trial records the build that planned it (earc-plan's --version)
# and the one that ran and timed it (earc-bench's).
version=$("$BUILD/earc-plan" --version) || fail "earc-plan --version exited $?"
bench_version=$("$BENCH" --version) || fail "earc-bench --version exited $?"
"$PY" - "$WORK/r.sqlite" "${version#earc-plan }" "${bench_version#earc-bench }" <<'PYEOF' || fail "results database"
import sqlite3, sys
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[1], uri=True)
assert con.execute("PRAGMA application_id").fetchone()[0] == 0x45424E43
assert con.execute("PRAGMA user_version").fetchone()[0] == 9
assert {j for (j,) in con.execute("SELECT jobs FROM trials")} == {1}, "trials must record --jobs 1"
versions = {v for (v,) in con.execute("SELECT planner_version FROM trials")}
assert versions == {sys.argv[2]}, (versions, sys.argv[2])
benches = {v for (v,) in con.execute("SELECT bench_version FROM trials")}
assert benches == {sys.argv[3]}, (benches, sys.argv[3])
assert con.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
rows = con.execute("SELECT robots, method, trial, success, planning_time_s, failure, peak_memory_kb FROM trials").fetchall()
assert len(rows) == 12, rows
assert len({(r[0], r[1], r[2]) for r in rows}) == 12, "a cell ran twice"
for robots, method, trial, success, t, failure, mem in rows:
    assert (success == 1) == (failure is None), (method, failure)
    assert mem is not None and mem > 0
    if success:
        assert t is not None and 0 <= t <= 10.1, t
# One job: the methods take turns, trial by trial, within each robot count.
order = [(r, m, t) for r, m, t in con.execute("SELECT robots, method, trial FROM trials ORDER BY rowid")]
assert order == [(r, m, t) for r in (2, 4) for t in (0, 1) for m in ("arc", "prioritized", "lightning")], order
solved = sum(r[3] for r in rows)
assert solved >= 6, "only %d of 12 trials solved: %s" % (solved, rows)
dbs = con.execute("SELECT method, suite, robots, construction_time_s, entries, size_bytes, problems FROM databases").fetchall()
assert sorted(d[2] for d in dbs) == [2, 4], dbs
for d in dbs:
    assert d[0] == "lightning" and d[1] == "mobile" and d[3] > 0 and d[5] > 0 and d[6] == 3, d
PYEOF

"$BENCH" table --results "$WORK/r.sqlite" > "$WORK/table.md" || fail "table exited $?"
grep -q "| 4 | lightning | ./2 " "$WORK/table.md" || fail "no lightning row for 4 robots: $(cat "$WORK/table.md")"
grep -q "^### Databases" "$WORK/table.md" || fail "no database table"
# Reading the closed results leaves no empty -wal and -shm beside them.
leftNothingBeside "$WORK/r.sqlite" table

# Trials under another time limit, as a second run with --time-limit 20
# into the same file leaves them, are another experiment: a table each,
# named by its limit; --time-limit takes one.
changedCopy "$WORK/r.sqlite" "$WORK/limits.sqlite" "UPDATE trials SET time_limit_s = 20 WHERE trial = 1"
for wide in "" --wide; do
  "$BENCH" table --results "$WORK/limits.sqlite" $wide > "$WORK/limits.md" ||
    fail "table $wide of two time limits exited $?"
  [ "$(grep -c "^### mobile" "$WORK/limits.md")" -eq 2 ] && grep -qx "### mobile, time limit 10 s" "$WORK/limits.md" &&
    grep -qx "### mobile, time limit 20 s" "$WORK/limits.md" ||
    fail "table $wide mixed two time limits: $(cat "$WORK/limits.md")"
done
"$BENCH" table --results "$WORK/limits.sqlite" --time-limit 20 > "$WORK/limits.md" || fail "table --time-limit exited $?"
grep -qx "### mobile" "$WORK/limits.md" && grep -q "| 4 | lightning | ./1 " "$WORK/limits.md" ||
  fail "table --time-limit 20: $(cat "$WORK/limits.md")"
# A filter that matches no trial is a mistake to point out, not an empty
# table (exit 0): said with the values the file has.
refusedInOneLine "limits.sqlite: --time-limit: no trials with a time limit of 15 s (its trials' limits: 10 s, 20 s)" \
  "$BENCH" table --results "$WORK/limits.sqlite" --time-limit 15
refusedInOneLine "r.sqlite: --seed: no trials of run seed 8 (its trials' seeds: 7)" \
  "$BENCH" export --results "$WORK/r.sqlite" --seed 8 --csv "$WORK/none.csv"
[ -e "$WORK/none.csv" ] && fail "a refused export wrote its CSV"
refusedInOneLine "r.sqlite: --time-limit: no trials with a time limit of 15 s" \
  "$BENCH" plot --results "$WORK/r.sqlite" --time-limit 15 -o "$WORK/none-plots"

"$BENCH" export --results "$WORK/r.sqlite" --csv "$WORK/r.csv" --databases-csv "$WORK/dbs.csv" \
  --ompl-log "$WORK/logs" > /dev/null || fail "export exited $?"
"$PY" - "$WORK/r.csv" "$WORK/dbs.csv" "$WORK/logs" <<'PYEOF' || fail "exports are malformed"
import csv, glob, os, sys
with open(sys.argv[1], newline="") as f:
    rows = list(csv.reader(f))
assert rows[0][:4] == ["suite", "robots", "method", "trial"], rows[0]
assert len(rows) == 13 and all(len(r) == len(rows[0]) for r in rows), [len(r) for r in rows]
with open(sys.argv[2], newline="") as f:
    assert len(list(csv.reader(f))) == 3

# The reading side of OMPL's benchmark log format, as
# ompl_benchmark_statistics.py walks it.
def read_log(path):
    lines = open(path).read().split("\n")
    i = 0
    def take():
        nonlocal i
        i += 1
        return lines[i - 1]
    assert take().split()[1] == "version"
    name = take().split()[-1]
    for _ in range(int(take().split()[0])):
        assert " = " in take()
    assert take().startswith("Running on ")
    assert take().startswith("Starting at ")
    for _ in range(2):
        assert take() == "<<<|"
        while take() != "|>>>":
            pass
    assert take().split()[-2:] == ["random", "seed"]
    limit = float(take().split()[0])
    assert take().split()[-3:] == ["MB", "per", "run"]
    assert take().split()[-3:] == ["runs", "per", "planner"]
    assert take().split()[-3:] == ["collect", "the", "data"]
    for _ in range(int(take().split()[0])):
        assert take().startswith("status|")
    planners = {}
    for _ in range(int(take().split()[0])):
        planner = take()
        for _ in range(int(take().split()[0])):
            take()
        props = ["_".join(take().split()[:-1]) for _ in range(int(take().split()[0]))]
        runs = []
        for _ in range(int(take().split()[0])):
            values = take().split("; ")[:-1]
            assert len(values) == len(props), (values, props)
            runs.append(dict(zip(props, values)))
        assert take() == "."
        planners[planner] = runs
    return name, limit, planners

logs = sorted(glob.glob(os.path.join(sys.argv[3], "*.log")))
assert [os.path.basename(p) for p in logs] == ["mobile-2.log", "mobile-4.log"], logs
for p in logs:
    name, limit, planners = read_log(p)
    assert limit == 10 and sorted(planners) == ["arc", "lightning", "prioritized"], (name, planners.keys())
    for runs in planners.values():
        assert len(runs) == 2
        for r in runs:
            assert r["solved"] in ("0", "1") and float(r["time"]) >= 0
PYEOF

# An output that is stdout itself holds the CSV alone: the summary lines
# go to stderr, whether stdout is a file or a pipe (as earc-plan's do).
"$BENCH" export --results "$WORK/r.sqlite" --csv /dev/stdout > "$WORK/stdout.csv" 2> "$WORK/export.err" ||
  fail "export --csv /dev/stdout exited $?"
cmp -s "$WORK/stdout.csv" "$WORK/r.csv" || fail "export --csv /dev/stdout > FILE: $(head -2 "$WORK/stdout.csv")"
grep -qx "/dev/stdout: 12 trials" "$WORK/export.err" || fail "export --csv /dev/stdout said: $(cat "$WORK/export.err")"
# Appended to a log: the log's earlier lines stay (through the link to the
# file, the export used to replace it).
echo "earlier line" > "$WORK/log.txt"
"$BENCH" export --results "$WORK/r.sqlite" --csv /dev/stdout >> "$WORK/log.txt" 2> /dev/null ||
  fail "export --csv /dev/stdout >> log exited $?"
"$BENCH" export --results "$WORK/r.sqlite" --csv /dev/fd/1 >> "$WORK/log.txt" 2> /dev/null ||
  fail "export --csv /dev/fd/1 >> log exited $?"
{ echo "earlier line"; cat "$WORK/r.csv" "$WORK/r.csv"; } | cmp -s - "$WORK/log.txt" ||
  fail "export --csv /dev/stdout, then /dev/fd/1, >> log: $(head -n 2 "$WORK/log.txt")"
"$BENCH" export --results "$WORK/r.sqlite" --databases-csv /dev/stdout --csv "$WORK/r2.csv" 2> "$WORK/export.err" |
  cat > "$WORK/stdout.csv"
rc=${PIPESTATUS[0]}
[ $rc -eq 0 ] || fail "export --databases-csv /dev/stdout exited $rc"
cmp -s "$WORK/stdout.csv" "$WORK/dbs.csv" || fail "export --databases-csv /dev/stdout | ...: $(head -2 "$WORK/stdout.csv")"
[ "$(cat "$WORK/export.err")" = "$WORK/r2.csv: 12 trials
/dev/stdout: 2 databases" ] || fail "export --databases-csv /dev/stdout said: $(cat "$WORK/export.err")"

# Suite names come from the results database: one no run writes, like
# '../../escaped', refuses the file (a row no run writes, see
# bench_refuses_nonsense_rows.sh) before any log is written.
changedCopy "$WORK/r.sqlite" "$WORK/odd.sqlite" "UPDATE trials SET suite = '../../escaped' WHERE robots = 2"
mkdir -p "$WORK/deep/a/b"
refusedInOneLine "$WORK/odd.sqlite: trials row id 1, column suite: '../../escaped' is not a suite earc-bench runs" \
  "$BENCH" export --results "$WORK/odd.sqlite" --ompl-log "$WORK/deep/a/b/logs"
[ -z "$(find "$WORK" -name '*escaped*')" ] && [ ! -e "$WORK/deep/a/b/logs" ] || fail "a refused export wrote logs"

# Bad input: exit 2 and one line naming the file and the option; the
# results database survives every refusal.
refused() {  # refused TEXT ARGS...
  local want=$1
  shift
  "$BENCH" "$@" > "$WORK/bad.out" 2> "$WORK/bad.err"
  local rc=$?
  [ $rc -eq 2 ] || fail "earc-bench $* exited $rc, not 2: $(cat "$WORK/bad.err")"
  [ "$(wc -l < "$WORK/bad.err")" -eq 1 ] || fail "earc-bench $*: not one line: $(cat "$WORK/bad.err")"
  grep -qF -- "$want" "$WORK/bad.err" || fail "earc-bench $*: the error does not say '$want': $(cat "$WORK/bad.err")"
}
# export refuses to overwrite the results or one output with another.
refused "$WORK/r.sqlite: --csv: is the --results file" export --results "$WORK/r.sqlite" --csv "$WORK/r.sqlite"
refused "$WORK/./r.sqlite: --databases-csv: is the --results file" \
  export --results "$WORK/r.sqlite" --databases-csv "$WORK/./r.sqlite"
"$BENCH" table --results "$WORK/r.sqlite" > /dev/null || fail "the results database did not survive export"
refused "$WORK/x/../same.csv: --databases-csv: is the same file as --csv $WORK/same.csv" \
  export --results "$WORK/r.sqlite" --csv "$WORK/same.csv" --databases-csv "$WORK/x/../same.csv"
[ -e "$WORK/same.csv" ] && fail "export wrote an output before refusing another"
refused "$WORK/logs/mobile-2.log: --ompl-log: is the same file as --csv $WORK/logs/mobile-2.log" \
  export --results "$WORK/r.sqlite" --ompl-log "$WORK/logs" --csv "$WORK/logs/mobile-2.log"

if hasMatplotlib; then
  "$BENCH" plot --results "$WORK/r.sqlite" -o "$WORK/fig" > /dev/null 2> "$WORK/plot.err" || fail "plot exited $?: $(cat "$WORK/plot.err")"
  [ -s "$WORK/fig/time_mobile.png" ] && [ -s "$WORK/fig/success_mobile.svg" ] || fail "plot wrote no figures"
  leftNothingBeside "$WORK/r.sqlite" plot
  # A value no run writes refuses the file in one line naming the row and
  # the column, in earc-bench and in the script on its own: no traceback,
  # no figure.
  cat > "$WORK/odd-values.py" <<'PYEOF'
import sqlite3, sys
src, dst = sqlite3.connect(sys.argv[1]), sqlite3.connect(sys.argv[2])
src.backup(dst)
ids = [r[0] for r in dst.execute("SELECT id FROM trials WHERE success = 1 ORDER BY id")]
dst.execute("UPDATE trials SET planning_time_s = 'abc' WHERE id = ?", (ids[0],))
dst.execute("UPDATE trials SET planning_time_s = 1e308 WHERE id = ?", (ids[1],))
dst.execute("UPDATE trials SET robots = 0 WHERE id = ?", (ids[2],))
dst.execute("UPDATE databases SET construction_time_s = 'slow'")
dst.commit()
print(ids[0])
PYEOF
  first=$("$PY" "$WORK/odd-values.py" "$WORK/r.sqlite" "$WORK/odd-values.sqlite") || fail "could not make odd values"
  want="$WORK/odd-values.sqlite: trials row id $first, column planning_time_s: 'abc' is not a number of seconds (0 or more)"
  refused "$want" plot --results "$WORK/odd-values.sqlite" -o "$WORK/fig2"
  refusedInOneLine "plot_results.py: $want" "$PY" "$SRC/tools/plots/plot_results.py" \
    --results "$WORK/odd-values.sqlite" -o "$WORK/fig2"
  [ -e "$WORK/fig2" ] && fail "a refused plot created its output directory"
  touch "$WORK/a-file"
  refused "$WORK/a-file: -o: exists and is not a directory" plot --results "$WORK/r.sqlite" -o "$WORK/a-file"
  "$PY" -c 'import sqlite3,sys
c = sqlite3.connect(sys.argv[1]); c.execute("PRAGMA user_version = 99"); c.commit()' "$WORK/odd.sqlite"
  refused "$WORK/odd.sqlite: schema version 99 is newer than this program's version 9; use a newer earc-bench" \
    plot --results "$WORK/odd.sqlite" -o "$WORK/fig3"
  echo "not a database" > "$WORK/text.txt"
  refused "$WORK/text.txt: cannot open the results database: not a SQLite database" plot --results "$WORK/text.txt" -o "$WORK/fig3"
  # The script on its own says the same, in one line, naming the file.
  "$PY" "$SRC/tools/plots/plot_results.py" --results "$WORK/odd.sqlite" -o "$WORK/fig3" 2> "$WORK/bad.err"
  [ $? -eq 2 ] && [ "$(wc -l < "$WORK/bad.err")" -eq 1 ] && grep -qF "$WORK/odd.sqlite: results schema version 99" "$WORK/bad.err" ||
    fail "plot_results.py accepted a newer schema: $(cat "$WORK/bad.err")"
  "$PY" "$SRC/tools/plots/plot_results.py" --results "$WORK/text.txt" -o "$WORK/fig3" 2> "$WORK/bad.err"
  [ $? -eq 2 ] && [ "$(wc -l < "$WORK/bad.err")" -eq 1 ] && grep -qF "$WORK/text.txt: " "$WORK/bad.err" ||
    fail "plot_results.py on a text file: $(cat "$WORK/bad.err")"
  [ -e "$WORK/fig3" ] && fail "a refused plot created its output directory"
else
  echo "note: no matplotlib for $PY: plot not tested"
fi

"$BENCH" "${RUN[@]}" > "$WORK/again.out" 2>&1 || fail "second run exited $?"
grep -q "nothing to run" "$WORK/again.out" || fail "second run did not skip the finished trials: $(head -3 "$WORK/again.out")"
echo "ok: quick benchmark, table, CSV and OMPL logs"
