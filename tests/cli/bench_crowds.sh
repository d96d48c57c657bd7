#!/bin/bash
# label: bench
# The crowd suites end to end on a tiny run: prioritized planning of the
# first 4 and 8 agents of empty-16-16-random-1 (compiled in, run from an
# empty directory), every solution validated; the table has the crowd
# columns, and the lower bound it divides by is the one computed here
# independently (breadth-first search on the map's free cells, 20 steps a
# move). A method that fails a count is not run at larger ones (--cutoff),
# an invalid solution is a failure, a refined plan's stats.refine are
# recorded and tabled, and plot draws the crowd figure.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needPython
needBuilt earc-bench earc-plan
failShowsOutput
cd "$WORK" || exit 1

"$BENCH" run --suites crowd-empty-16-16 --robots 4,8 --methods prioritized --trials 1 --time-limit 20 \
  --seed 3 --results r.sqlite > out 2> err || fail "earc-bench run exited $?"
grep -q "INVALID SOLUTION" out err && fail "a planner produced an invalid solution"

# The bound, independently: BFS on the .map from each agent's start cell.
"$PY" - "$SRC/datasets/movingai/empty-16-16.map" "$SRC/datasets/movingai/empty-16-16-random-1.scen" r.sqlite \
  > bounds <<'PYEOF' || fail "the recorded trials"
import collections, sqlite3, sys
rows = open(sys.argv[1]).read().split("\n")
h, w = int(rows[1].split()[1]), int(rows[2].split()[1])
grid = rows[4:4 + h]
agents = [l.split("\t") for l in open(sys.argv[2]).read().split("\n")[1:] if l]
def bfs(sc, sr, gc, gr):
    dist = {(sc, sr): 0}
    q = collections.deque([(sc, sr)])
    while q:
        c, r = q.popleft()
        if (c, r) == (gc, gr):
            return dist[(c, r)]
        for nc, nr in ((c + 1, r), (c - 1, r), (c, r + 1), (c, r - 1)):
            if 0 <= nc < w and 0 <= nr < h and grid[nr][nc] in ".G" and (nc, nr) not in dist:
                dist[(nc, nr)] = dist[(c, r)] + 1
                q.append((nc, nr))
    raise SystemExit("unreachable")
con = sqlite3.connect("file:%s?mode=ro" % sys.argv[3], uri=True)
got = con.execute("SELECT robots, success, lower_bound, sum_of_costs FROM trials ORDER BY robots").fetchall()
assert [r[0] for r in got] == [4, 8], got
for n, ok, bound, soc in got:
    want = 20 * sum(bfs(*map(int, a[4:8])) for a in agents[:n])
    assert bound == want, (n, bound, want)
    assert ok == 1, got
    print(n, bound, soc)
PYEOF

# The table: the crowd columns, and a row per count with the bound and
# the ratio the recorded figures make.
"$BENCH" table --results r.sqlite > table || fail "earc-bench table exited $?"
grep -qF "### Crowds: crowd-empty-16-16 (empty-16-16-random-1.scen)" table || fail "no crowd table: $(cat table)"
grep -qF "| robots | method | solved | time to first solution (s) | sum of costs | makespan | lower bound | sum of costs / lower bound |" table ||
  fail "the crowd table lacks its columns: $(cat table)"
while read -r n bound soc; do
  ratio=$("$PY" -c "print('%.2f' % ($soc / $bound))")
  grep -qE "^\| $n \| prioritized \| 1/1 \| [0-9.e-]+ \| $soc \| [0-9]+ \| $bound \| $ratio \|$" table ||
    fail "no row '$n prioritized ... $soc ... $bound $ratio': $(cat table)"
done < bounds
grep -qF "Lower bound: the sum over robots of each one's shortest path" table || fail "the table does not define its bound"

# --cutoff: a method that failed 4 robots is not run at 8.
EARC_BENCH_FAULT=prioritized:crash "$BENCH" run --suites crowd-empty-16-16 --robots 4,8 --methods prioritized \
  --trials 1 --time-limit 20 --cutoff --results cut.sqlite > out 2> err || fail "the --cutoff run exited $?"
[ "$(sqlValue cut.sqlite "SELECT COUNT(*) FROM trials")" -eq 1 ] || fail "--cutoff ran 8 robots after failing 4"
grep -qF "cut off: prioritized on crowd-empty-16-16 from 8 robots (solved 0 of 1 at 4)" out || fail "no cut-off note"

# A crowd trial's solution is validated: one that teleports is a failure.
writeTeleportingPlanner "$WORK/teleports"
"$BENCH" run --suites crowd-empty-16-16 --robots 4 --methods arc --trials 1 --time-limit 20 \
  --plan-program "$WORK/teleports" --results bad.sqlite > out 2> err
[ "$(sqlValue bad.sqlite "SELECT success FROM trials")" -eq 0 ] || fail "an invalid crowd solution counted as solved"
sqlValue bad.sqlite "SELECT failure FROM trials" | grep -q "^invalid solution" || fail "not failed as invalid"

# A refined plan's stats.refine are recorded and tabled: a stand-in for
# earc-plan that plans and then adds them as --refine would.
cat > "$WORK/refines" <<FAKE
#!/bin/bash
"$BUILD/earc-plan" "\$@" || exit \$?
[ "\$1" = plan ] || exit 0
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
exec "$PY" -c 'import json, sys
d = json.load(open(sys.argv[1]))
st = d["stats"]
st["refine"] = {"first_s": 0.125, "first_sum_of_costs": st["sum_of_costs"] + 100,
                "final_sum_of_costs": st["sum_of_costs"], "final_makespan": st["makespan"]}
json.dump(d, open(sys.argv[1], "w"))' "\$out"
FAKE
chmod +x "$WORK/refines"
"$BENCH" run --suites crowd-empty-16-16 --robots 4 --methods prioritized --trials 1 --time-limit 20 \
  --plan-program "$WORK/refines" --results refined.sqlite > out 2> err || fail "the refined run exited $?"
read -r soc first final < <(sqlValue refined.sqlite \
  "SELECT sum_of_costs || ' ' || refine_first_sum_of_costs || ' ' || refine_final_sum_of_costs FROM trials")
[ "$first" = $((soc + 100)) ] && [ "$final" = "$soc" ] || fail "refine stats not recorded: $soc $first $final"
"$BENCH" table --results refined.sqlite > table || fail "table of the refined run exited $?"
grep -qE "^\| 4 \| prioritized \| 1/1 \| 0.125 \| $first \| [0-9]+ \| [0-9]+ \| [0-9.]+ \| $final \| [0-9.]+ \|$" table ||
  fail "no refined columns: $(cat table)"

# A count the file does not have is refused, naming the suite's range.
refusedInOneLine "--robots: no suite of this run has 129 robots (crowd-empty-16-16: 2 to 128)" \
  "$BENCH" run --suites crowd-empty-16-16 --robots 129 --methods arc --results x.sqlite

if hasMatplotlib; then
  "$BENCH" plot --results r.sqlite -o fig > out 2> err || fail "earc-bench plot exited $?"
  [ -s fig/crowds.png ] || fail "no crowds.png"
fi
echo "ok: crowd suite on 4 and 8 robots, bounds agree"
