#!/bin/bash
# Bad input makes `earc-plan validate` exit 2 with one line on stderr naming
# the file, where in it (line and column, or JSON path) and the reason.
set -u
PLAN="$1/earc-plan"
DATA="$2/tests/data"
fail() { echo "FAIL: $*"; exit 1; }
ERR=$(mktemp)
OUT=$(mktemp)
trap 'rm -f "$ERR" "$OUT"' EXIT

# expect SCENARIO SOLUTION PATTERN: exit 2, nothing on stdout, and exactly one
# stderr line that matches PATTERN (grep -E).
expect() {
  "$PLAN" validate "$1" "$2" > "$OUT" 2> "$ERR"
  local rc=$?
  [ $rc -eq 2 ] || fail "$(basename "$1") + $(basename "$2"): exit $rc, expected 2; $(cat "$ERR")"
  [ ! -s "$OUT" ] || fail "$(basename "$1"): unexpected stdout: $(cat "$OUT")"
  [ "$(wc -l < "$ERR")" -eq 1 ] || fail "$(basename "$1"): expected one stderr line, got: $(cat "$ERR")"
  grep -Eq "$3" "$ERR" || fail "$(basename "$1"): '$(cat "$ERR")' does not match '$3'"
}

VALID="$DATA/solutions/swap-discs__valid.json"
SCEN="$DATA/scenarios/swap-discs.json"
# A robot name with a newline and a terminal escape, quoted by the error:
# still one line, the control characters shown as '?'.
EVIL=$(mktemp)
sed 's/"name": "m0"/"name": "evil\\nearc-plan: ok\\u001b[2J"/; s/^    2,$/    3,/' "$SCEN" > "$EVIL"
expect "$EVIL" "$VALID" 'robot "evil\?earc-plan: ok\?\[2J"'
rm -f "$EVIL"
# A file that never ends is read up to a bound, not until memory runs out.
expect /dev/zero "$VALID" '^earc-plan: error: /dev/zero: more than 256 MiB: too large to read'
expect "$DATA/bad/malformed.json" "$VALID" \
  '^earc-plan: error: .*bad/malformed\.json: line 4, column 35 \(.*\): malformed JSON: '
expect "$DATA/bad/nan.json" "$VALID" \
  'bad/nan\.json: line 3, column [0-9]+ \(\$\.robots\[0\]\.start\[1\]\): malformed JSON: .*invalid literal.*NaN'
# A hint only where the text looks like what it names: a comment is no NaN.
expect "$DATA/bad/comment.json" "$VALID" \
  'bad/comment\.json: line 1, column 1 \(\$\): malformed JSON: .*invalid literal.*\(JSON has no comments\)$'
grep -q 'NaN' "$ERR" && fail "comment.json: the NaN hint: $(cat "$ERR")"
expect "$DATA/bad/trailing-comma.json" "$VALID" \
  "bad/trailing-comma\.json: line 52, column 2 \(\\\$\.robots\[2\]\): malformed JSON: .*unexpected ']'.*\(a trailing comma: JSON allows none before ']'\)$"
expect "$DATA/bad/start-in-collision.json" "$VALID" \
  'bad/start-in-collision\.json: \$\.robots\[0\]\.start: start is in collision with obstacle 0 \(\$\.obstacles\[0\], box\), overlap 0\.35$'
expect "$DATA/bad/arm-base-outside.json" "$DATA/solutions/arm-fold__valid.json" \
  'bad/arm-base-outside\.json: \$\.robots\[0\]\.base: base is outside the workspace by 1\.06$'
expect "$DATA/bad/starts-touch.json" "$VALID" \
  '\$\.robots\[1\]\.start: start touches the start of robot "m0"'
expect "$DATA/bad/duplicate-key.json" "$VALID" '\$\.robots\[0\]\.start: duplicate key "start"'
expect "$DATA/bad/unknown-shape.json" "$VALID" '\$\.robots\[0\]\.shape\.type: unknown shape type "hexagon"'
expect "$SCEN" "$DATA/bad/swap-discs__wrong-dimension.json" \
  'swap-discs__wrong-dimension\.json: \$\.paths\[0\]\.states\[0\]: expected a state of 3 numbers'
expect "$SCEN" "$DATA/bad/swap-discs__infinite-number.json" '\$\.paths\[0\]\.states\[1\]\[2\]: malformed JSON: number overflow'
expect "$SCEN" "$DATA/bad/swap-discs__truncated.json" 'swap-discs__truncated\.json: line 2, column 56 '

# --json still gives a verdict on stdout.
"$PLAN" validate "$DATA/bad/nan.json" "$VALID" --json > "$OUT" 2> "$ERR"
rc=$?
[ $rc -eq 2 ] || fail "--json bad input: exit $rc"
/usr/bin/python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); assert r["valid"] is False and r["malformed"] is True and "nan.json" in r["error"], r' "$OUT" \
  || fail "--json bad input output: $(cat "$OUT")"
echo "ok"
