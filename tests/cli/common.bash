# Shared by the command-line tests (not a test itself: CTest runs *.sh).
# Sourced right after `BUILD=$1`: sets PY, a default fail, a scratch
# directory $WORK removed on exit (a test that sets its own EXIT trap
# removes it there), and the checks below.
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# Skipped (77) without /usr/bin/python3.
needPython() { [ -x "$PY" ] || { echo "skipped: no $PY"; exit 77; }; }
# FAIL unless every program named is built in $BUILD.
needBuilt() {
  local p
  for p in "$@"; do
    [ -x "$BUILD/$p" ] || { echo "FAIL: $p not built in $BUILD"; exit 1; }
  done
}
# FAIL unless nothing is left beside the SQLite file $1 (no -wal, no
# -shm) after the step named $2: reading a closed file of ours leaves none.
leftNothingBeside() {
  local f
  for f in "$1-wal" "$1-shm"; do
    [ -e "$f" ] && fail "$2 left $(basename "$f") beside $(basename "$1")"
  done
  return 0
}
