#!/bin/bash
# `earc-plan view` writes one self-contained page (no external resource,
# the data inline), refuses a solution of another scenario or a trace with
# robots the scenario lacks (one line, exit 2), shows an unsolved solution;
# `earc-plan render` draws arms and mobile robots at a step and as a strip,
# as SVG and (with rsvg-convert) PNG.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
PLAN="$BUILD/earc-plan"
DATA="$SRC/tests/data"
[ -x "$PLAN" ] || { echo "FAIL: $PLAN not built"; exit 1; }

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }

# expect_bad_input NAME GREP_PATTERN COMMAND...: exit 2 and one line on stderr.
expect_bad_input() {
  local name=$1 pattern=$2
  shift 2
  "$@" > "$WORK/out" 2> "$WORK/err"
  local status=$?
  if [ $status -ne 2 ]; then fail "$name: exit $status, expected 2"; return; fi
  if [ "$(wc -l < "$WORK/err")" -ne 1 ]; then fail "$name: expected one line on stderr, got: $(cat "$WORK/err")"; return; fi
  if ! grep -q -- "$pattern" "$WORK/err"; then fail "$name: message lacks '$pattern': $(cat "$WORK/err")"; return; fi
  ok "$name: $(cat "$WORK/err")"
}

# A page, self-contained.
"$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" -o "$WORK/p.html" > /dev/null ||
  fail "view of a valid solution failed"
if [ -s "$WORK/p.html" ]; then
  grep -q '<script type="application/json" id="earc-data">{' "$WORK/p.html" || fail "no inline data in the page"
  grep -Eq '(src|href)=|https?:|@import|url\(' "$WORK/p.html" && fail "the page refers to something outside itself"
  grep -q "default-src 'none'" "$WORK/p.html" || fail "the page does not forbid network access"
  ok "the page is self-contained ($(wc -c < "$WORK/p.html") bytes)"
fi

# With a trace from the planner.
if "$PLAN" plan "$DATA/scenarios/swap-discs.json" -o "$WORK/s.json" --method arc --seed 1 --trace "$WORK/t.json" -q; then
  if "$PLAN" view "$DATA/scenarios/swap-discs.json" "$WORK/s.json" --trace "$WORK/t.json" -o "$WORK/t.html" > /dev/null &&
     grep -q '"trace":{"conflicts":\[' "$WORK/t.html"; then
    ok "a page with the planner's trace"
  else
    fail "view with the planner's trace"
  fi
else
  fail "planning swap-discs failed"
fi

# Bad input: one line, exit 2.
expect_bad_input "solution of another scenario" '\$\.scenario: the solution is for scenario' \
  "$PLAN" view "$DATA/scenarios/open-disc.json" "$DATA/solutions/swap-discs__valid.json" -o "$WORK/x.html"
expect_bad_input "paths out of order" '\$\.paths\[0\]\.robot' \
  "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__wrong-order.json" -o "$WORK/x.html"
expect_bad_input "wrong dimension" 'swap-discs__wrong-dimension.json' \
  "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/bad/swap-discs__wrong-dimension.json" -o "$WORK/x.html"
echo '{"format": "earc.trace.v1", "events": [{"type": "conflict", "id": 0, "robots": [0, 9], "t": 2, "place": [1, 1]}]}' \
  > "$WORK/bad-trace.json"
expect_bad_input "trace of another scenario" 'robots\[1\]: robot index 9 does not exist' \
  "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" --trace "$WORK/bad-trace.json" \
  -o "$WORK/x.html"
expect_bad_input "missing trace file" 'cannot open file' \
  "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" --trace "$WORK/none.json" \
  -o "$WORK/x.html"
expect_bad_input "an output not named .html" 'x.svg: -o: must end in .html or .htm' \
  "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__valid.json" -o "$WORK/x.svg"
[ -e "$WORK/x.svg" ] && fail "view wrote HTML into x.svg"
[ -e "$WORK/x.html" ] && fail "a refused view still wrote its page"

# Unsolved: the scenario with a banner (the page says so in its data).
if "$PLAN" view "$DATA/scenarios/swap-discs.json" "$DATA/solutions/swap-discs__not-solved.json" -o "$WORK/u.html" > /dev/null &&
   grep -q '"solved":false' "$WORK/u.html"; then
  ok "an unsolved solution gives a page"
else
  fail "view of an unsolved solution"
fi

# Stills: arms and mobile robots, one step and a strip, SVG and PNG.
svg_panels() { grep -o '<g class="panel"' "$1" | wc -l; }
for case in arm-fold box-rotation; do
  sc="$DATA/scenarios/$case.json" sol="$DATA/solutions/${case}__valid.json"
  if "$PLAN" render "$sc" "$sol" --step 3 -o "$WORK/$case.svg" > /dev/null && [ "$(svg_panels "$WORK/$case.svg")" -eq 1 ] &&
     grep -q 't = 3 of [0-9]*<' "$WORK/$case.svg"; then
    ok "render $case --step 3"
  else
    fail "render $case --step 3"
  fi
  if "$PLAN" render "$sc" "$sol" --strip 0,2,5 -o "$WORK/$case-strip.svg" > /dev/null &&
     [ "$(svg_panels "$WORK/$case-strip.svg")" -eq 3 ]; then
    ok "render $case --strip 0,2,5"
  else
    fail "render $case --strip 0,2,5"
  fi
  if command -v rsvg-convert > /dev/null; then
    if "$PLAN" render "$sc" "$sol" --step 3 -o "$WORK/$case.png" > /dev/null &&
       [ "$(head -c 8 "$WORK/$case.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; then
      ok "render $case --step 3 as PNG"
    else
      fail "render $case --step 3 as PNG"
    fi
  fi
done
# Arms are drawn link by link: one capsule (path) per link at the step.
links=$(jq '.robots[0].links | length' "$DATA/scenarios/arm-fold.json" 2> /dev/null || echo 0)
if [ "$links" -gt 0 ] && [ "$(grep -o '<path d="M' "$WORK/arm-fold.svg" | wc -l)" -lt "$links" ]; then
  fail "render arm-fold --step 3 does not draw the arm's $links links"
fi

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "all viewer command-line checks passed"
