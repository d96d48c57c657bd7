#!/usr/bin/env bash
# Regenerates the docs/ pictures in this folder from a build directory:
#   tools/viewer/examples/make_examples.sh [BUILD_DIR]   (default: build)
# viewer-mobile-32.png: the viewer on a 32-robot mobile plan with obstacles
#   and its trace, at step 255 with conflict 19 selected (headless Chromium);
# render-arms-8.png: `earc-plan render --step 60` of an 8-arm plan.
# Both plans are deterministic (fixed seeds), but planner changes can move
# the conflicts: look at the pictures after regenerating them.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
source "$src/tests/browser/viewer_harness.sh"
[ -n "$(harness_browser)" ] || { echo "needs chromium (tools/setup.sh --tests)" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$build/earc-scenario" generate --family mobile -n 32 --obstacles --seed 1 -o "$work/m32.json"
"$build/earc-plan" plan "$work/m32.json" -o "$work/m32.sol.json" --method arc --seed 1 --trace "$work/m32.trace.json" -q
"$build/earc-plan" view "$work/m32.json" "$work/m32.sol.json" --trace "$work/m32.trace.json" -o "$work/m32.html" > /dev/null
harness_screenshot "$work/m32.html" "$here/viewer-mobile-32.png" 1200 900 "t=255&conflict=19"

"$build/earc-scenario" generate --family arms -n 8 --seed 1 -o "$work/a8.json"
"$build/earc-plan" plan "$work/a8.json" -o "$work/a8.sol.json" --method arc --seed 1 -q
"$build/earc-plan" render "$work/a8.json" "$work/a8.sol.json" --step 60 --width 900 -o "$here/render-arms-8.png" > /dev/null

ls -l "$here"/*.png
