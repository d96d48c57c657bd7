#!/bin/bash
# `earc-plan validate` and the independent checker (shared/tools/
# check_solution.py) must give the same verdict, exit status and violation
# count on every fixture pair: solutions/NAME__CASE.json (and bad/NAME__CASE.json)
# against scenarios/NAME.json; a bad scenario bad/NAME.json against a stub
# solution. Fixtures are found below tests/data (any subfolder, so generated
# sets dropped there are included) and below each folder in
# $EARC_AGREEMENT_DIRS (colon-separated). Skipped (77) without the checker
# or without numpy for /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
CHECKER="$SRC/../shared/tools/check_solution.py"
PLAN="$BUILD/earc-plan"

if [ ! -f "$CHECKER" ]; then
  echo "skipped: no independent checker at $CHECKER (../shared is missing)"
  exit 77
fi
if ! "$PY" -c "import numpy" 2>/dev/null; then
  echo "skipped: $PY has no numpy, which the checker needs"
  exit 77
fi
[ -x "$PLAN" ] || { echo "FAIL: $PLAN not built"; exit 1; }

STUB="$WORK/stub-solution.json"
echo '{"format": "earc.solution.v1", "solved": false, "paths": []}' > "$STUB"

DIRS=("$SRC/tests/data")
IFS=: read -r -a EXTRA <<< "${EARC_AGREEMENT_DIRS:-}"
for d in "${EXTRA[@]}"; do [ -n "$d" ] && DIRS+=("$d"); done

# The scenario of NAME__CASE.json: NAME.json in the same folder, else in
# a sibling scenarios/ folder.
scenario_for() {
  local sol=$1 dir name
  dir=$(dirname "$sol")
  name=$(basename "$sol" .json)
  name=${name%%__*}
  for cand in "$dir/$name.json" "$dir/../scenarios/$name.json"; do
    [ -f "$cand" ] && { echo "$cand"; return 0; }
  done
  return 1
}

pairs=0
failures=0
compare() {
  local scen=$1 sol=$2
  pairs=$((pairs + 1))
  "$PLAN" validate "$scen" "$sol" --json > "$WORK/mine.json" 2> "$WORK/mine.err"
  local mine=$?
  "$PY" "$CHECKER" "$scen" "$sol" --json > "$WORK/ref.json" 2> "$WORK/ref.err"
  local ref=$?
  local verdicts
  verdicts=$("$PY" - "$WORK/mine.json" "$WORK/ref.json" <<'EOF'
import json, sys
def load(p):
    try:
        with open(p) as f:
            return json.load(f)
    except Exception as e:
        return {"unreadable": str(e)}
a, b = load(sys.argv[1]), load(sys.argv[2])
va, vb = a.get("valid"), b.get("valid")
ca, cb = a.get("violation_count"), b.get("violation_count")
same = va == vb and (a.get("malformed") or b.get("malformed") or ca == cb)
print("%s valid %s/%s count %s/%s" % ("same" if same else "DIFFERENT", va, vb, ca, cb))
EOF
)
  if [ "$mine" != "$ref" ] || [[ "$verdicts" != same* ]]; then
    failures=$((failures + 1))
    echo "DISAGREE: $(basename "$scen") + $(basename "$sol"): exit $mine (earc-plan) vs $ref (checker); $verdicts"
    sed 's/^/  earc-plan: /' "$WORK/mine.err" | head -3
  fi
}

shopt -s globstar nullglob
for dir in "${DIRS[@]}"; do
  for f in "$dir"/**/*.json; do
    base=$(basename "$f" .json)
    if [[ "$base" == *__* ]]; then
      if scen=$(scenario_for "$f"); then
        compare "$scen" "$f"
      else
        echo "note: no scenario for $f"
      fi
    elif [[ "$(basename "$(dirname "$f")")" == bad ]]; then
      compare "$f" "$STUB"
    fi
  done
done

echo "$pairs fixture pairs, $failures disagreement(s)"
[ "$pairs" -gt 0 ] || { echo "FAIL: no fixture pairs found"; exit 1; }
[ "$failures" -eq 0 ]
