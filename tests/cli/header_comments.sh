#!/bin/bash
# label: unsanitized
# House style: a declaration's comment in every public header (include/)
# and the programs' and the Python module's headers (tools/, python/) is
# at most three lines (tools/check_header_comments.py).
# The checker itself flags a long comment above a declaration and passes
# one inside an inline function's body.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needPython
CHECK="$SRC/tools/check_header_comments.py"
cat > "$WORK/t.hpp" <<'HPP'
// A file's opening comment
// may be long:
// it describes the file,
// not a declaration.
#pragma once
namespace t {
// one
// two
// three
// four
int f();
inline int g() {
  // inside a body:
  // the reasoning may
  // stand here, next to
  // the code.
  return 1;
}
}  // namespace t
HPP
"$PY" "$CHECK" "$WORK/t.hpp" > "$WORK/out" && fail "a four-line comment above int f() passed"
[ "$(wc -l < "$WORK/out")" -eq 1 ] && grep -q "t.hpp:7: 4 comment lines above a declaration" "$WORK/out" ||
  fail "not the one block expected: $(cat "$WORK/out")"
"$PY" "$CHECK" "$SRC/include" "$SRC/src" "$SRC/tools" "$SRC/python" > "$WORK/out" || fail "$(cat "$WORK/out")"
echo "ok"
