#!/bin/bash
# label: unsanitized
# House style (issue 50): no source file over 600 lines, the README within
# 250 (the rest lives in docs/). Fails naming each file over its limit.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
cd "$SRC" || fail "no source directory $SRC"
over=$(find include src tools python tests \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.py' \
         -o -name '*.sh' -o -name '*.bash' -o -name '*.cmake' -o -name '*.js' \) -type f -print0 |
       xargs -0 wc -l | awk '$2 != "total" && $1 > 600 { print $2 " (" $1 " lines)" }')
[ -z "$over" ] || fail "over 600 lines: $over"
readme=$(wc -l < README.md)
[ "$readme" -le 250 ] || fail "README.md has $readme lines, more than 250"
echo "ok"
