#!/bin/bash
# label: unsanitized
# --version: every program prints one line, its name and the same build
# version, and exits 0; built from a git checkout, the version names the
# checkout's commit (".dirty" allowed: tracked files may differ from it).
# A plan's solution reports the same version in its stats, so a result can
# be traced to its code. A word that is no command is named, with the
# program's commands.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needBuilt earc-plan earc-db earc-scenario earc-bench
want=""
for prog in earc-plan earc-db earc-scenario earc-bench; do
  "$BUILD/$prog" --version > "$WORK/out" 2> "$WORK/err" || fail "$prog --version exited $?: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/out")" -eq 1 ] && [ ! -s "$WORK/err" ] || fail "$prog --version: not one line: $(cat "$WORK/out" "$WORK/err")"
  line=$(cat "$WORK/out")
  [[ $line =~ ^$prog\ ([0-9]+\.[0-9]+\.[0-9]+(\+[0-9a-f]{7,}(\.dirty)?)?)$ ]] || fail "$prog --version: '$line'"
  version=${BASH_REMATCH[1]}
  [ -z "$want" ] || [ "$version" = "$want" ] || fail "$prog says $version, earc-plan $want"
  want=$version
done
# After a subcommand too, without its required arguments.
for cmd in "earc-plan plan" "earc-db build" "earc-scenario generate" "earc-bench compare"; do
  $BUILD/$cmd --version > "$WORK/out" 2> "$WORK/err" || fail "$cmd --version exited $?: $(cat "$WORK/err")"
  [ "$(cat "$WORK/out")" = "${cmd%% *} $want" ] && [ ! -s "$WORK/err" ] ||
    fail "$cmd --version: $(cat "$WORK/out" "$WORK/err")"
done
# The version of the project's CMakeLists.txt.
project=$(sed -n 's/^project(earc VERSION \([0-9.]*\) .*/\1/p' "$SRC/CMakeLists.txt")
[ "${want%%+*}" = "$project" ] || fail "version $want is not the project's $project"
# The commit, when the source is a git checkout (a clean clone in CI).
if command -v git > /dev/null && [ "$(git -C "$SRC" rev-parse --show-toplevel 2> /dev/null)" = "$(cd "$SRC" && pwd -P)" ]; then
  commit=$(git -C "$SRC" rev-parse --short=7 HEAD)
  case $want in
    "$project+$commit" | "$project+$commit.dirty") ;;
    *) fail "version $want does not name the checkout's commit $commit (rebuild after committing)" ;;
  esac
fi

# A solution says which build made it.
"$BUILD/earc-scenario" generate --family mobile --robots 2 --seed 3 -o "$WORK/s.json" > /dev/null 2>&1 ||
  fail "earc-scenario generate exited $?"
"$BUILD/earc-plan" plan "$WORK/s.json" -o "$WORK/sol.json" --method arc --seed 3 -q > /dev/null 2>&1 ||
  fail "earc-plan plan exited $?"
grep -q "\"earc_version\": *\"$want\"" "$WORK/sol.json" || fail "the solution does not say earc_version $want"

# A word that is no command, or an option before any, is named with the
# program's commands: one line, exit 2.
for prog in earc-plan earc-db earc-scenario earc-bench; do
  for word in frobnicate --frobnicate; do
    "$BUILD/$prog" $word > "$WORK/out" 2> "$WORK/err"
    rc=$?
    [ $rc -eq 2 ] || fail "$prog $word: exit $rc, expected 2"
    [ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -q -- "unknown .* $word (commands: " "$WORK/err" ||
      fail "$prog $word: $(cat "$WORK/err")"
  done
done
