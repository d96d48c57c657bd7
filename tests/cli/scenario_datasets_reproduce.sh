#!/bin/bash
# Every committed dataset is reproduced byte for byte by the command that
# datasets/README.md gives for it, and every dataset has such a command.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
GEN="$BUILD/earc-scenario"
needBuilt earc-scenario
README="$SRC/datasets/README.md"

# The commands are the README lines that start with "earc-scenario ", run
# from the repository root with their -o target moved into $WORK.
grep '^earc-scenario ' "$README" > "$WORK/commands" || fail "no commands in $README"
count=0
while read -r line; do
  out=$(echo "$line" | sed -n 's/.* -o datasets\/\([^ ]*\.json\).*/\1/p')
  [ -n "$out" ] || fail "command without '-o datasets/NAME.json': $line"
  read -r -a args <<< "${line#earc-scenario }"
  for k in "${!args[@]}"; do
    [ "${args[$k]}" = "datasets/$out" ] && args[$k]="$WORK/$out"
  done
  (cd "$SRC" && "$GEN" "${args[@]}" > /dev/null) || fail "'$line' exited $?"
  cmp -s "$WORK/$out" "$SRC/datasets/$out" || fail "'$line' does not reproduce datasets/$out"
  count=$((count + 1))
done < "$WORK/commands"
for f in "$SRC"/datasets/*.json; do
  [ -e "$WORK/$(basename "$f")" ] || fail "datasets/$(basename "$f") has no command in $README"
done
echo "ok: $count datasets"
