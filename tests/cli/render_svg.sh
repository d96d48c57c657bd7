#!/bin/bash
# earc-plan render: a scenario and a solution become well-formed SVG with
# one group per robot and one panel per requested step; PNG output needs
# rsvg-convert and says so when it is missing.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
GEN="$BUILD/earc-scenario"
needBuilt earc-plan earc-scenario
needPython
wellformed() { "$PY" -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$1"; }
count() { grep -o "$2" "$1" | wc -l; }

"$GEN" generate --family mobile --robots 4 --obstacles --seed 2 -o "$WORK/s.json" > /dev/null || fail "generate exited $?"
"$GEN" generate --family arms --robots 4 --seed 2 -o "$WORK/arms.json" > /dev/null || fail "generate arms exited $?"
# A straight-line "solution" in 21 steps: render draws, it does not validate.
for f in s arms; do
  "$PY" - "$WORK/$f.json" "$WORK/$f.sol.json" <<'PYEOF' || fail "could not write a solution"
import json, sys
sc = json.load(open(sys.argv[1]))
paths = [{"robot": r["name"],
          "states": [[a + (b - a) * t / 20 for a, b in zip(r["start"], r["goal"])] for t in range(21)]}
         for r in sc["robots"]]
json.dump({"format": "earc.solution.v1", "scenario": sc["name"], "method": "line", "solved": True,
           "paths": paths, "stats": {"planning_time_s": 0}}, open(sys.argv[2], "w"))
PYEOF
done

# A scenario whose geometry plan refuses (a start inside an obstacle) is
# still drawn, with one warning line that says what plan would say.
"$PY" - "$WORK/s.json" "$WORK/broken-geometry.json" <<'PYEOF' || fail "could not write the broken scenario"
import json, sys
sc = json.load(open(sys.argv[1]))
sc["obstacles"].append({"type": "circle", "center": sc["robots"][0]["start"][:2], "radius": 0.5})
json.dump(sc, open(sys.argv[2], "w"))
PYEOF
"$PLAN" render "$WORK/broken-geometry.json" -o "$WORK/broken-geometry.svg" > /dev/null 2> "$WORK/err" ||
  fail "render of a scenario with a start in an obstacle exited $?"
grep -q "^earc-plan: warning: $WORK/broken-geometry.json: \$.robots\[0\].start: start is in collision .*(drawn as it is; plan refuses it)$" \
  "$WORK/err" || fail "no warning for a start in an obstacle: $(cat "$WORK/err")"
[ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "more than one line: $(cat "$WORK/err")"
wellformed "$WORK/broken-geometry.svg" || fail "the broken scenario's picture is not well-formed"
"$PLAN" render "$WORK/s.json" -o "$WORK/clean.svg" > /dev/null 2> "$WORK/err" || fail "render of a clean scenario exited $?"
[ -s "$WORK/err" ] && fail "a clean scenario warned: $(cat "$WORK/err")"

"$PLAN" render "$WORK/s.json" -o "$WORK/scenario.svg" > /dev/null || fail "scenario render exited $?"
wellformed "$WORK/scenario.svg" || fail "scenario SVG is not well-formed"
[ "$(count "$WORK/scenario.svg" 'class="robot"')" -eq 4 ] || fail "scenario SVG does not have 4 robot groups"

# A MovingAI map's obstacles (merged cells, many abutting) are one path,
# filled as their union: filled one by one, each box's anti-aliased edge
# left a light seam along the next.
"$GEN" movingai random-32-32-10 --robots 2 --seed 1 -o "$WORK/map.json" > /dev/null || fail "movingai exited $?"
"$PLAN" render "$WORK/map.json" -o "$WORK/map.svg" > /dev/null || fail "map render exited $?"
wellformed "$WORK/map.svg" || fail "map SVG is not well-formed"
[ "$(count "$WORK/map.svg" '<path class="obstacles"')" -eq 1 ] || fail "the map's obstacles are not one path"
[ "$(count "$WORK/map.svg" '<polygon points')" -eq 4 ] || fail "the map's obstacles are drawn one by one (or robots are missing)"

# Names may hold any character JSON can escape; the picture still parses:
# what XML 1.0 forbids (C0 controls, even as &#1;; U+FFFF) is drawn as U+FFFD.
"$PY" - "$WORK/s.json" "$WORK/ctl.json" "$WORK/ctl.sol.json" <<'PYEOF' || fail "could not write the control-character scenario"
import json, sys
sc = json.load(open(sys.argv[1]))
sc["name"] = "title\u0007\uffff"
for r, name in zip(sc["robots"], ["ctl\u0001x", "\u0000", "tab\tlf\ncr\r", "<&'\">"]):
    r["name"] = name
json.dump(sc, open(sys.argv[2], "w"))
paths = [{"robot": r["name"], "states": [r["start"], r["goal"]]} for r in sc["robots"]]
json.dump({"format": "earc.solution.v1", "scenario": sc["name"], "method": "line", "solved": True,
           "paths": paths, "stats": {"planning_time_s": 0}}, open(sys.argv[3], "w"))
PYEOF
"$PLAN" render "$WORK/ctl.json" "$WORK/ctl.sol.json" -o "$WORK/ctl.svg" --step 1 > /dev/null || fail "control-character render exited $?"
wellformed "$WORK/ctl.svg" || fail "names with control characters make SVG that is not XML"
grep -q 'data-robot="ctl'$'\xef\xbf\xbd''x"' "$WORK/ctl.svg" || fail "U+0001 in a name is not drawn as U+FFFD"
if command -v rsvg-convert > /dev/null; then
  "$PLAN" render "$WORK/ctl.json" -o "$WORK/ctl.png" > /dev/null || fail "control-character PNG render exited $?"
fi

"$PLAN" render "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/step.svg" --step 10 > /dev/null || fail "--step exited $?"
wellformed "$WORK/step.svg" || fail "solution SVG is not well-formed"
[ "$(count "$WORK/step.svg" 'class="path"')" -eq 4 ] || fail "solution SVG does not have 4 paths"
grep -q "t = 10" "$WORK/step.svg" || fail "the step is not shown"

"$PLAN" render "$WORK/arms.json" "$WORK/arms.sol.json" -o "$WORK/strip.svg" --strip 0,10,20 > /dev/null || fail "--strip exited $?"
wellformed "$WORK/strip.svg" || fail "strip SVG is not well-formed"
[ "$(count "$WORK/strip.svg" 'class="panel"')" -eq 3 ] || fail "strip does not have 3 panels"
[ "$(count "$WORK/strip.svg" 'class="robot"')" -eq 12 ] || fail "strip does not have 4 robots in each panel"
# An empty or non-numeric item is refused, not dropped.
for bad in 0,,20 0,x,20; do
  "$PLAN" render "$WORK/arms.json" "$WORK/arms.sol.json" -o "$WORK/bad.svg" --strip $bad > /dev/null 2> "$WORK/err" &&
    fail "--strip $bad was taken"
  grep -q -- "--strip: " "$WORK/err" || fail "--strip $bad: $(cat "$WORK/err")"
done

"$PLAN" render "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --step 1 --strip 1,2 > /dev/null 2>&1 \
  && fail "--step and --strip together accepted"
"$PLAN" render "$WORK/s.json" -o "$WORK/x.svg" --step 1 > /dev/null 2>&1
[ $? -eq 2 ] || fail "--step without a solution is not bad input"
# A step past the makespan (20) is refused, naming it; the makespan itself is the last.
bad_step() {  # bad_step TEXT ARGS...: exit 2 and one line containing TEXT
  local want=$1
  shift
  "$PLAN" render "$@" > /dev/null 2> "$WORK/err"
  [ $? -eq 2 ] || fail "render $* is not bad input: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF -- "$want" "$WORK/err" || fail "render $*: $(cat "$WORK/err")"
}
# An empty file name is named as such (it said "cannot open file: No such
# file or directory", naming nothing); likewise for validate and view.
bad_step "an empty file name" "" -o "$WORK/x.svg"
bad_step "an empty file name" "$WORK/s.json" "" -o "$WORK/x.svg"
for sub in validate "view -o $WORK/x.html"; do
  refusedInOneLine "an empty file name" "$PLAN" $sub "" "$WORK/s.sol.json"
  refusedInOneLine "an empty file name" "$PLAN" $sub "$WORK/s.json" ""
done
bad_step "s.sol.json: --step: step 21 is beyond the solution's makespan 20 (steps 0 to 20)" \
  "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --step 21
bad_step "--strip: step 99 is beyond the solution's makespan 20" "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --strip 0,99
bad_step "--strip: '-1' is not a whole number" "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --strip 0,-1
bad_step "--strip: a time step needs a SOLUTION file" "$WORK/s.json" -o "$WORK/x.svg" --strip 1,2
# Panels go left to right in the order given: a strip out of order drew
# the robots moving back, and a repeated step drew the same panel twice.
bad_step "--strip: step 5 after step 10: the steps must increase from left to right" \
  "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --strip 0,10,5
bad_step "--strip: step 10 after step 10: the steps must increase" "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/x.svg" --strip 10,10
"$PLAN" render "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/last.svg" --step 20 > /dev/null || fail "--step 20 (the makespan) exited $?"
# An unsolved solution without paths: the picture says so under the title
# (it once came out byte for byte the scenario's), and a time step is
# refused as having no paths, not as past a "makespan 0".
"$PY" - "$WORK/s.json" "$WORK/uns.sol.json" <<'PYEOF' || fail "could not write the unsolved solution"
import json, sys
sc = json.load(open(sys.argv[1]))
json.dump({"format": "earc.solution.v1", "scenario": sc["name"], "method": "arc", "solved": False,
           "stats": {"planning_time_s": 0.02, "failure": ["time_limit"]}}, open(sys.argv[2], "w"))
PYEOF
"$PLAN" render "$WORK/s.json" "$WORK/uns.sol.json" -o "$WORK/uns.svg" > /dev/null || fail "unsolved render exited $?"
wellformed "$WORK/uns.svg" || fail "the unsolved SVG is not well-formed"
cmp -s "$WORK/uns.svg" "$WORK/scenario.svg" && fail "an unsolved plan's picture is the scenario's"
"$PY" - "$WORK/uns.svg" <<'PYEOF' || fail "the unsolved picture does not say it is not solved"
import sys, xml.dom.minidom
doc = xml.dom.minidom.parse(sys.argv[1])
texts = ["".join(n.data for n in t.getElementsByTagName("tspan")[0].childNodes) if t.getElementsByTagName("tspan")
         else "" for t in doc.getElementsByTagName("text") if t.getAttribute("class") == "facts"]
assert "not solved: time_limit" in texts, texts
PYEOF
for steps in "--step 0" "--strip 0,10"; do
  bad_step "uns.sol.json: ${steps%% *}: the solution is not solved (time_limit) and has no paths, so there are no time steps to draw" \
    "$WORK/s.json" "$WORK/uns.sol.json" -o "$WORK/x.svg" $steps
  grep -q makespan "$WORK/err" && fail "render $steps of an unsolved plan talks of a makespan: $(cat "$WORK/err")"
done
# --width refuses NaN as every numeric option does (CLI11's range let it
# through, and the picture was width="nan").
for w in nan -nan; do
  bad_step "--width: '$w' is not a finite number" "$WORK/s.json" -o "$WORK/x.svg" --width $w
done
echo '{"format": "earc.scenario.v1"}' > "$WORK/bad.json"
"$PLAN" render "$WORK/bad.json" -o "$WORK/x.svg" > /dev/null 2>&1
[ $? -eq 2 ] || fail "a broken scenario is not bad input"
"$PLAN" render "$WORK/s.json" "$WORK/arms.sol.json" -o "$WORK/x.svg" > /dev/null 2>&1
[ $? -eq 2 ] || fail "a solution of another scenario is not bad input"
[ -e "$WORK/x.svg" ] && fail "a failed render left a picture"

# The output's name says its format: one that ends in neither .svg nor
# .png is refused (one line, exit 2) before the inputs are read; the case
# of the extension does not matter, and a device gets SVG.
for bad in x.txt x svg; do
  "$PLAN" render "$WORK/bad.json" -o "$WORK/$bad" > /dev/null 2> "$WORK/err"
  [ $? -eq 2 ] || fail "-o $bad is not bad input"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -qF "$WORK/$bad: -o: must end in .svg or .png" "$WORK/err" ||
    fail "-o $bad: unexpected error: $(cat "$WORK/err")"
  [ -e "$WORK/$bad" ] && fail "a refused render wrote $bad"
done
"$PLAN" render "$WORK/s.json" -o "$WORK/upper.SVG" > /dev/null && wellformed "$WORK/upper.SVG" || fail "-o upper.SVG is not SVG"
"$PLAN" render "$WORK/s.json" -o /dev/stdout | grep -q "^<svg" || fail "-o /dev/stdout into a pipe did not write SVG"

env PATH=/nonexistent "$PLAN" render "$WORK/s.json" -o "$WORK/x.png" > /dev/null 2> "$WORK/err"
[ $? -eq 1 ] || fail "PNG without rsvg-convert did not exit 1"
grep -q "librsvg2-bin" "$WORK/err" || fail "PNG error does not name librsvg2-bin: $(cat "$WORK/err")"
[ -e "$WORK/x.png" ] && fail "a failed PNG render left a file"
if command -v rsvg-convert > /dev/null; then
  "$PLAN" render "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/ok.png" --step 5 > /dev/null || fail "PNG render exited $?"
  head -c 8 "$WORK/ok.png" | grep -q PNG || fail "ok.png is not a PNG"
  # librsvg makes no PNG of more than 32767 pixels a side; past it, render
  # failed (exit 1) with librsvg's three lines. Too wide is known from the
  # options, before the files are read; too tall from the workspace's shape.
  bad_step "x.png: --width: 2 panels (--strip) of --width 20000 make a PNG 40016 pixels wide, more than librsvg's limit of 32767 pixels a side" \
    "$WORK/bad.json" "$WORK/s.sol.json" -o "$WORK/x.png" --width 20000 --strip 0,10
  { printf 'type octile\nheight 64\nwidth 2\nmap\n'; for _ in $(seq 64); do echo ..; done; } > "$WORK/tall.map"
  "$GEN" movingai "$WORK/tall.map" --robots 2 --shape disc --radius 0.3 -o "$WORK/tall.json" > /dev/null ||
    fail "the tall map's scenario exited $?"
  bad_step "x.png: --width: --width 1200 makes a PNG 37713 pixels tall for this workspace, more than librsvg's limit of 32767 pixels a side" \
    "$WORK/tall.json" -o "$WORK/x.png" --width 1200
  [ -e "$WORK/x.png" ] && fail "a refused PNG render left a file"
  # SVG has no such limit.
  "$PLAN" render "$WORK/s.json" "$WORK/s.sol.json" -o "$WORK/wide.svg" --width 20000 --strip 0,10 > /dev/null ||
    fail "an SVG 40016 pixels wide exited $?"
fi
echo "ok"
