#!/bin/bash
# label: browser
# The viewer page in headless Chromium (tests/browser/viewer_harness.sh):
# for arms, box and disc robots, a planned scenario with obstacles and its
# trace (compacted: the header must say what the plan was before), and an
# unsolved solution, the page's self-test must PASS (no script error,
# keyboard, play/pause, a drawn canvas, clicking a conflict mark shows its
# details) and the poses it draws at chosen steps and midpoints must match
# poses computed here from the solution file, within 1e-3.
# The harness must also fail: a page whose script throws or does not parse
# reports FAIL with the error, and poses compared at the wrong times do not
# match. 128 robots x 5,000 steps keep the page compact and frames cheap.
# Skipped (77) without Chromium (tools/setup.sh --tests) or jq.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
GEN="$BUILD/earc-scenario"
DATA="$SRC/tests/data"
source "$SRC/tests/browser/viewer_harness.sh"

if [ -z "$(harness_browser)" ]; then
  echo "skipped: no chromium (install it with tools/setup.sh --tests, or set EARC_CHROMIUM)"
  exit 77
fi
if ! command -v jq > /dev/null; then
  echo "skipped: no jq, which computes the expected poses (tools/setup.sh --tests)"
  exit 77
fi
[ -x "$PLAN" ] || { echo "FAIL: $PLAN not built"; exit 1; }

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# check NAME SCENARIO SOLUTION TIMES [view options...]: page, self-test, poses.
check() {
  local name=$1 scenario=$2 solution=$3 times=$4
  shift 4
  local page="$WORK/$name.html" dom="$WORK/$name.dom" verdict result
  if ! "$PLAN" view "$scenario" "$solution" "$@" -o "$page" > /dev/null; then
    fail "$name: earc-plan view failed"
    return
  fi
  if ! harness_run_selftest "$page" "$times" "$dom"; then
    fail "$name: chromium failed: $(tail -3 "$dom.stderr")"
    return
  fi
  verdict=$(harness_verdict "$dom")
  case "$verdict" in
    PASS*) echo "ok: $name self-test: $verdict" ;;
    *) fail "$name self-test: ${verdict:-no verdict (the page never finished its self-test)}" ;;
  esac
  harness_expected_poses "$scenario" "$solution" "$times" > "$WORK/$name.want.json"
  if result=$(harness_compare_poses "$WORK/$name.want.json" "$dom"); then
    echo "ok: $name poses at $times match the solution file"
  else
    fail "$name poses: $result"
  fi
}

# Arms: joint positions by forward kinematics, at steps and midpoints.
check arm "$DATA/scenarios/arm-fold.json" "$DATA/solutions/arm-fold__valid.json" 0,1,2.5,7,7.5,1000
# A box robot turning: headings interpolated along the shortest arc.
check box "$DATA/scenarios/box-rotation.json" "$DATA/solutions/box-rotation__valid.json" 0,3,3.5,6.5,1000
check discs "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" 0,4,4.5,9,9.5
check heading-wrap "$DATA/scenarios/open-disc.json" "$DATA/solutions/open-disc__heading-wrap.json" 0,0.5,1,1.5,2.5
# Unsolved: no paths, every robot at its start, play does nothing.
check unsolved "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__not-solved.json" 0,5
if ! grep -q '"solved":false' "$WORK/unsolved.html"; then fail "unsolved page does not say so"; fi

# A planned scenario with obstacles and a trace (conflicts to click).
if [ -x "$GEN" ]; then
  "$GEN" generate --family mobile -n 8 --obstacles --seed 3 -o "$WORK/gen.json" > /dev/null &&
    "$PLAN" plan "$WORK/gen.json" -o "$WORK/gen.sol.json" --method arc --seed 1 --trace "$WORK/gen.trace.json" --compact -q
  if [ -f "$WORK/gen.trace.json" ]; then
    last=$(jq '[.paths[].states | length] | max - 1' "$WORK/gen.sol.json")
    check planned "$WORK/gen.json" "$WORK/gen.sol.json" "0,1.5,$((last / 2)),$((last / 2)).5,$last" \
      --trace "$WORK/gen.trace.json"
    if [ "$(jq '[.events[] | select(.type == "conflict")] | length' "$WORK/gen.trace.json")" -gt 0 ] &&
       ! grep -q 'PASS.*clicked conflict' <(harness_verdict "$WORK/planned.dom"); then
      fail "planned: the self-test did not click a conflict although the trace has some"
    fi
    # The header says what the plan was before --compact.
    before=$(jq -r '"makespan \(.stats.compact.makespan_before), sum of costs \(.stats.compact.sum_of_costs_before)"' "$WORK/gen.sol.json")
    grep -qF "before --compact: $before" "$WORK/planned.dom" ||
      fail "planned: the page's header does not say 'before --compact: $before'"
  else
    fail "could not plan the generated scenario"
  fi
else
  echo "note: $GEN not built; the planned scenario with a trace was left out"
fi

# Scale: 128 robots (discs and boxes) x 5,000 steps. The page stays compact
# (states to 4 decimals, delta-coded) and a frame stays cheap. The bound is
# loose (a 60 Hz display allows 16 ms; a per-frame redraw of every whole
# path costs far more), so a busy machine does not fail it.
awk -v sc="$WORK/scale.json" -v sol="$WORK/scale.sol.json" 'BEGIN {
  R = 128; T = 5000; PI = 3.141592653589793
  printf "{\"format\":\"earc.scenario.v1\",\"name\":\"scale-128\",\"workspace\":{\"min\":[0,0],\"max\":[160,80]},\"obstacles\":[" > sc
  for (k = 0; k < 15; k++) printf "%s{\"type\":\"circle\",\"center\":[%d,40],\"radius\":0.8}", (k ? "," : ""), 10 + 10 * k > sc
  printf "],\"robots\":[" > sc
  printf "{\"format\":\"earc.solution.v1\",\"scenario\":\"scale-128\",\"method\":\"synthetic\",\"solved\":true,\"paths\":[" > sol
  for (i = 0; i < R; i++) {
    cx = 5 + (i % 16) * 10; cy = 5 + int(i / 16) * 10
    printf "%s{\"robot\":\"m%d\",\"states\":[", (i ? "," : ""), i > sol
    for (t = 0; t < T; t++) {
      a = t * 0.002 + i
      s = sprintf("[%.4f,%.4f,%.4f]", cx + 3 * cos(a), cy + 3 * sin(a), a + PI / 2)
      printf "%s%s", (t ? "," : ""), s > sol
      if (t == 0) first = s
    }
    printf "]}" > sol
    shape = i % 2 ? "{\"type\":\"box\",\"size\":[1.4,0.8]}" : "{\"type\":\"disc\",\"radius\":0.6}"
    printf "%s{\"name\":\"m%d\",\"type\":\"mobile\",\"shape\":%s,\"start\":%s,\"goal\":%s}", (i ? "," : ""), i, shape, first, s > sc
  }
  printf "]}\n" > sc
  printf "]}\n" > sol
}'
check scale "$WORK/scale.json" "$WORK/scale.sol.json" 0,1,2500,2500.5,4999
size=$(wc -c < "$WORK/scale.html")
if [ "$size" -gt 8000000 ]; then fail "scale: the page is $size bytes for 128 robots x 5,000 steps"; else echo "ok: scale page $size bytes"; fi
frame_ms=$(harness_verdict "$WORK/scale.dom" | sed -n 's/.*frame_ms=\([0-9.]*\).*/\1/p')
if [ -z "$frame_ms" ] || awk -v ms="$frame_ms" 'BEGIN { exit !(ms > 60) }'; then
  fail "scale: a frame took ${frame_ms:-?} ms"
elif [ "$frame_ms" = 0.00 ]; then
  echo "note: this Chromium's clock did not advance while drawing: frame time not measured"
else
  echo "ok: scale frame ${frame_ms} ms"
fi

# The harness must be able to fail.
page="$WORK/arm.html"
sed 's/const data = JSON.parse(/viewerDeliberatelyBroken(); &/' "$page" > "$WORK/throws.html"
sed 's/const data = JSON.parse(/const const data = JSON.parse(/' "$page" > "$WORK/syntax.html"
for broken in throws syntax; do
  if cmp -s "$page" "$WORK/$broken.html"; then fail "could not break the page ($broken)"; continue; fi
  harness_run_selftest "$WORK/$broken.html" 0 "$WORK/$broken.dom"
  verdict=$(harness_verdict "$WORK/$broken.dom")
  case "$verdict" in
    FAIL*script\ errors:*) echo "ok: a page whose script $broken reports: $verdict" ;;
    *) fail "a page whose script $broken was not reported: ${verdict:-no verdict}" ;;
  esac
done
grep -q 'viewerDeliberatelyBroken is not defined' <(harness_verdict "$WORK/throws.dom") ||
  fail "the thrown error's message is missing from the verdict"
harness_expected_poses "$DATA/scenarios/arm-fold.json" "$DATA/solutions/arm-fold__valid.json" 1,0,7.5,7,2.5,1000 |
  jq -c 'with_entries(.key |= {"1": "0", "0": "1", "7.5": "2.5", "2.5": "7.5", "7": "7", "1000": "1000"}[.])' \
    > "$WORK/shifted.json"
if result=$(harness_compare_poses "$WORK/shifted.json" "$WORK/arm.dom"); then
  fail "poses expected at other times were accepted"
else
  echo "ok: poses expected at other times are refused ($result)"
fi

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "all viewer browser checks passed"
