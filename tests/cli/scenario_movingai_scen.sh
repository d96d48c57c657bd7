#!/bin/bash
# earc-scenario movingai MAP --scen FILE: the first N agents of a MovingAI
# scenario file at their cells' centres, discs of radius 0.3 unless a
# footprint is given; the benchmark's files are compiled in and their
# instances valid. A file that does not fit the map is bad input (exit 2)
# in one line naming the file and its line.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
GEN="$BUILD/earc-scenario"
needBuilt earc-scenario
cd "$WORK" || exit 1

# A 4 x 3 map with one blocked cell, (column 1, row 1).
printf 'type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n' > tiny.map
line() { printf '0\ttiny.map\t4\t3\t%s\t%s\t%s\t%s\t0\n' "$@"; }
{ echo "version 1"; line 0 0 3 2; line 2 1 0 1; line 3 0 1 2; } > tiny.scen

"$GEN" movingai tiny.map --scen tiny.scen --robots 2 -o a.json > out 2> err || fail "movingai --scen exited $?: $(cat err)"
if [ -x "$PY" ]; then
  "$PY" - a.json <<'PYEOF' || fail "the scenario is not the file's first agents"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["name"] == "movingai-tiny-disc-2", d["name"]
r = d["robots"]
assert len(r) == 2, r
assert r[0]["shape"] == {"type": "disc", "radius": 0.3}, r[0]
assert r[0]["start"] == [0.5, 2.5, 0] and r[0]["goal"] == [3.5, 0.5, 0], r[0]
assert r[1]["start"] == [2.5, 1.5, 0] and r[1]["goal"] == [0.5, 1.5, 0], r[1]
assert len(d["obstacles"]) == 1
PYEOF
fi
# Boxes when asked for; a radius with --scen's default disc.
"$GEN" movingai tiny.map --scen tiny.scen --robots 3 --shape box -o b.json > /dev/null || fail "--shape box exited $?"
grep -q '"type":"box"' b.json || fail "--shape box did not make boxes"
"$GEN" movingai tiny.map --scen tiny.scen --robots 3 --radius 0.45 -o c.json > /dev/null || fail "--radius exited $?"
grep -q '"radius":0.45' c.json || fail "--radius 0.45 not used: $(grep radius c.json | head -2)"

# The benchmark's files, compiled in, from a directory without them: 100
# robots on room-32-32-4, a valid scenario (earc-plan plan reads it).
"$GEN" movingai room-32-32-4 --scen room-32-32-4-random-1 --robots 100 -o room.json > /dev/null ||
  fail "the compiled-in room-32-32-4-random-1 was not found"
[ "$(grep -o '"name":"m[0-9]*"' room.json | wc -l)" -eq 100 ] || fail "not 100 robots"
if [ -f "$SRC/../shared/datasets/movingai/room-32-32-4-random-1.scen" ]; then
  "$GEN" movingai "$SRC/../shared/datasets/movingai/room-32-32-4.map" \
    --scen "$SRC/../shared/datasets/movingai/room-32-32-4-random-1.scen" --robots 100 -o room2.json > /dev/null ||
    fail "../shared's room file was refused"
  cmp -s room.json room2.json ||
    fail "the compiled-in file and ../shared's give other robots"
fi

# Refusals: one line naming the file and the line, exit 2.
bad() {  # NAME WANT [--robots N]: tiny.map with the file NAME.scen
  local name=$1 want=$2
  shift 2
  refusedInOneLine "$name.scen: $want" "$GEN" movingai tiny.map --scen "$name.scen" -o x.json "$@"
}
{ echo "version 2"; line 0 0 3 2; } > header.scen
bad header "line 1: expected the header 'version 1', got 'version 2'" --robots 1
{ echo "version 1"; line 0 0 3 2; printf '0\ttiny.map\t4\t3\t0\t0\n'; } > short.scen
bad short "line 3: expected 9 tab-separated fields" --robots 1
{ echo "version 1"; line 0 0 3 2; printf '0\ttiny.map\t4\t3\t0\tx\t1\t1\t0\n'; } > word.scen
bad word "line 3: start row: expected a whole number" --robots 1
{ echo "version 1"; line 0 0 3 2; line 0 0 4 2; } > outside.scen
bad outside "line 3: goal column 4 is outside the map's 4 columns" --robots 1
{ echo "version 1"; line 0 0 3 2; line 1 1 0 1; } > blocked.scen
bad blocked "line 3: start cell (column 1, row 1) is blocked on map tiny" --robots 1
{ echo "version 1"; line 0 0 3 2; line 2 0 1 1; } > blockedgoal.scen
bad blockedgoal "line 3: goal cell (column 1, row 1) is blocked on map tiny" --robots 1
bad tiny "the file has 3 agents, fewer than the 4 robots asked for" --robots 4
{ echo "version 1"; line 0 0 3 2; line 0 0 2 2; } > samestart.scen
bad samestart "line 3: start cell (column 0, row 0) is also the start of line 2" --robots 2
{ echo "version 1"; line 0 0 3 2; line 2 2 3 2; } > samegoal.scen
bad samegoal "line 3: goal cell (column 3, row 2) is also the goal of line 2" --robots 2
{ echo "version 1"; printf '0\tother.map\t4\t3\t0\t0\t3\t2\t0\n'; } > othermap.scen
bad othermap "line 2: its agents are on map other.map of 4 x 3 cells, not on tiny of 4 x 3" --robots 1
{ echo "version 1"; printf '0\ttiny.map\t5\t3\t0\t0\t3\t2\t0\n'; } > othersize.scen
bad othersize "line 2: its agents are on map tiny.map of 5 x 3 cells, not on tiny of 4 x 3" --robots 1
# The README's robots fit their cells: a larger disc is refused as an option.
refusedInOneLine "tiny.scen: --radius: must be at most 0.5" "$GEN" movingai tiny.map --scen tiny.scen --radius 0.6 -o x.json
# A file that is not there nor compiled in; --seed, which nothing would use.
refusedInOneLine "nowhere.scen: no such file, nor a compiled-in scenario file (empty-16-16-random-1," \
  "$GEN" movingai tiny.map --scen nowhere.scen -o x.json
refusedInOneLine "--seed: applies to random robots, not to --scen" \
  "$GEN" movingai tiny.map --scen tiny.scen --seed 3 -o x.json
# The map's file as the scenario file (and the scenario as the output).
"$GEN" movingai tiny.map --scen tiny.map -o x.json > /dev/null 2> err
[ $? -eq 2 ] || fail "a .map as --scen was not refused"
grep -qF "tiny.map: line 1: expected the header 'version 1', got 'type octile'" err || fail "a .map as --scen: $(cat err)"
[ -e x.json ] && fail "a refused run left an output file"
echo "ok"
