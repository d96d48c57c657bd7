#!/bin/bash
# label: unsanitized
# The layers (CMakeLists.txt): every public header compiles with only the
# include roots of its own layer and the layers below it, so that no header
# reaches up a layer (the sources are held to it by the build itself). And
# the check bites: a core file that includes a methods header is caught.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needCompiler
ls "$BUILD"/layers/*.roots > /dev/null 2>&1 || fail "no layer roots in $BUILD/layers (configure first)"

# upward ROOTS_FILE FILE...: "FILE: HEADER" for each earc/ header a FILE
# includes that none of the roots holds (-MG lists it unresolved).
upward() {
  local roots=$1 args=() r
  shift
  while read -r r; do [ -n "$r" ] && args+=(-I "$r"); done < "$roots"
  "$CXX" -std=c++20 -MM -MG "${args[@]}" -x c++ "$@" 2> "$WORK/err" | sed -e ':a' -e '/\\$/N; s/\\\n//; ta' |
    awk '{ for (i = 2; i <= NF; i++) if ($i ~ /^earc\//) print $1 " " $i }'
}

checked=0
for roots in "$BUILD"/layers/*.roots; do
  layer=$(basename "$roots" .roots)
  mapfile -t headers < <(find -L "$BUILD/layers/$layer/earc" -name '*.hpp' | sort)
  bad=$(upward "$roots" "${headers[@]}")
  [ -z "$bad" ] || fail "layer $layer: headers including a header of a higher layer: $bad"
  checked=$((checked + ${#headers[@]}))
done
[ "$checked" -gt 50 ] || fail "only $checked headers checked"

printf '#include "earc/scene/scenario.hpp"\n#include "earc/methods/plan.hpp"\n' > "$WORK/upward.cpp"
[ "$(upward "$BUILD/layers/core.roots" "$WORK/upward.cpp")" = "upward.o: earc/methods/plan.hpp" ] ||
  fail "a core file including earc/methods/plan.hpp was not caught"
echo "ok: $checked headers, each within its layer"
