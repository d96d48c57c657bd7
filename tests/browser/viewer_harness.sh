#!/bin/bash
# Functions for driving a viewer page (earc-plan view) in headless Chromium,
# sourced by tests/cli/view_browser.sh and usable by hand:
#   source tests/browser/viewer_harness.sh
#   harness_run_selftest plan.html 0,10,10.5 out.dom   # loads plan.html#selftest=...
#   harness_verdict out.dom                            # PASS ... / FAIL ...
#   harness_expected_poses scenario.json solution.json 0,10,10.5 > want.json
#   harness_compare_poses want.json out.dom            # prints "ok" or the worst error
#   harness_screenshot plan.html out.png 1200 900
# Only bash, Chromium and jq: no Node, no Python. The expected poses are
# computed here from the solution file (never read back from the page), so
# a page that reports its own numbers cannot pass.

# The browser: $EARC_CHROMIUM, else chromium (Debian) or chromium-browser;
# nothing when it is not an executable.
harness_browser() {
  if [ -n "${EARC_CHROMIUM:-}" ]; then
    command -v "$EARC_CHROMIUM" || true
    return
  fi
  command -v chromium || command -v chromium-browser || true
}

# Runs headless Chromium with a fresh profile and no network chatter; the
# arguments follow the common flags. Gives up after 120 s.
harness_chromium() {
  local browser profile status
  browser=$(harness_browser)
  profile=$(mktemp -d)
  timeout 120 "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync --disable-dev-shm-usage \
    --disable-extensions --mute-audio --hide-scrollbars --user-data-dir="$profile" "$@"
  status=$?
  rm -rf "$profile"
  return $status
}

# harness_run_selftest PAGE TIMES OUT_DOM: loads PAGE#selftest=TIMES with
# virtual time (timers and frames run without waiting in real time) and
# writes the DOM after the self-test to OUT_DOM.
harness_run_selftest() {
  local page=$1 times=$2 out=$3
  harness_chromium --window-size=1200,900 --virtual-time-budget=5000 --run-all-compositor-stages-before-draw \
    --dump-dom "file://$(realpath "$page")#selftest=$times" > "$out" 2> "$out.stderr"
}

# The self-test's verdict line from a dumped DOM (empty if it never ran).
harness_verdict() {
  sed -n 's:.*<pre id="selftest"[^>]*>\([^<]*\)</pre>.*:\1:p' "$1" |
    sed 's/&amp;/\&/g; s/&lt;/</g; s/&gt;/>/g; s/&quot;/"/g'
}

# The poses the page wrote, as JSON.
harness_page_poses() {
  sed -n 's:.*<pre id="selftest-poses"[^>]*>\([^<]*\)</pre>.*:\1:p' "$1"
}

# jq definitions shared by the two jq programs below.
HARNESS_JQ_LIB='
def pi: 3.141592653589793;
def wrap: . as $a | ($a + pi) - 2 * pi * ((($a + pi) / (2 * pi)) | floor) - pi;
# Configuration at time s: linear between steps, headings along the
# shortest arc (the contract midpoint rule); after its end a robot waits.
def config($r; $states; $s):
  ($states | length) as $n | ($s | floor) as $t
  | if $t >= $n - 1 then $states[$n - 1]
    else ($s - $t) as $f | $states[$t] as $a | $states[$t + 1] as $b
      | [range(0; $a | length) as $j | $a[$j] + ($b[$j] - $a[$j]) * $f]
      | if $r.type == "mobile" then .[2] = $a[2] + (($b[2] - $a[2]) | wrap) * $f else . end
    end;
# Forward kinematics of a planar arm: joint positions, the base first.
def joints($r; $q):
  reduce range(0; $r.links | length) as $k
    ({x: $r.base[0], y: $r.base[1], a: $r.base[2], pts: [[$r.base[0], $r.base[1]]]};
     .a += $q[$k] | .x += $r.links[$k] * (.a | cos) | .y += $r.links[$k] * (.a | sin) | .pts += [[.x, .y]])
  | .pts;
'

# harness_expected_poses SCENARIO SOLUTION TIMES: {"T": [pose per robot]}
# for each time in the comma-separated TIMES (as the page clamps them).
harness_expected_poses() {
  jq -n -c --slurpfile sc "$1" --slurpfile sol "$2" --arg times "$3" "$HARNESS_JQ_LIB"'
    $sc[0] as $sc | $sol[0] as $sol
    | ($sol.paths // []) as $paths
    | ([$paths[] | (.states | length) - 1] | max // 0) as $last
    | reduce ($times | split(",")[]) as $key ({};
        ($key | tonumber) as $T | ([[$T, 0] | max, $last] | min) as $s
        | .[$key] = [range(0; $sc.robots | length) as $i | $sc.robots[$i] as $r
            | (if ($paths | length) > 0 then config($r; $paths[$i].states; $s) else $r.start end) as $q
            | if $r.type == "mobile" then $q else joints($r; $q) end])'
}

# harness_compare_poses EXPECTED_JSON DOM: "ok" when every pose the page
# wrote is within 1e-3 of the expected one (headings modulo 2 pi), else
# the worst mismatch. Exit status 0 only for "ok".
harness_compare_poses() {
  local got
  got=$(harness_page_poses "$2")
  [ -n "$got" ] || { echo "the page wrote no poses"; return 1; }
  jq -n -r --slurpfile want "$1" --argjson got "$got" "$HARNESS_JQ_LIB"'
    $want[0] as $want
    | [ $want | keys_unsorted[] as $k
        | if ($got[$k] | type) != "array" or ($got[$k] | length) != ($want[$k] | length)
          then {err: 1e9, at: "time \($k): \($got[$k] | length) poses, expected \($want[$k] | length)"}
          else range(0; $want[$k] | length) as $i | $want[$k][$i] as $w | $got[$k][$i] as $g
            | if ($g | flatten | length) != ($w | flatten | length)
              then {err: 1e9, at: "time \($k) robot \($i): pose \($g), expected \($w)"}
              else ($w | flatten) as $wf | ($g | flatten) as $gf
                | {err: ([range(0; $wf | length) as $j
                          | if ($w[0] | type) == "number" and $j == 2
                            then ($gf[$j] - $wf[$j]) | wrap | fabs
                            else ($gf[$j] - $wf[$j]) | fabs end] | max),
                   at: "time \($k) robot \($i): pose \($g), expected \($w)"}
              end
          end ]
    | (max_by(.err) // {err: 0}) as $worst
    | if $worst.err <= 1e-3 then "ok" else "worst error \($worst.err) at \($worst.at)" end' |
    { read -r line; echo "$line"; [ "$line" = ok ]; }
}

# harness_screenshot PAGE OUT_PNG WIDTH HEIGHT [FRAGMENT]
harness_screenshot() {
  local page=$1 out=$2 w=$3 h=$4 frag=${5:-}
  harness_chromium --window-size="$w,$h" --virtual-time-budget=3000 --run-all-compositor-stages-before-draw \
    --screenshot="$(realpath -m "$out")" "file://$(realpath "$page")${frag:+#$frag}" > /dev/null 2>&1
}
