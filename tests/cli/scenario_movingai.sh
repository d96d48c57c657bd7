#!/bin/bash
# earc-scenario movingai: a benchmark map becomes a deterministic scenario
# with the map's size; malformed maps are bad input (exit 2) naming the
# file and the line; a compiled-in map is found by its name.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
GEN="$BUILD/earc-scenario"
needBuilt earc-scenario
MAP="$SRC/datasets/movingai/random-32-32-10.map"

"$GEN" movingai "$MAP" --robots 8 --seed 1 -o "$WORK/a.json" > /dev/null || fail "movingai exited $?"
"$GEN" movingai "$MAP" --robots 8 --seed 1 -o "$WORK/b.json" > /dev/null || fail "second run exited $?"
"$GEN" movingai "$MAP" --robots 8 --seed 2 -o "$WORK/c.json" > /dev/null || fail "seed 2 exited $?"
cmp -s "$WORK/a.json" "$WORK/b.json" || fail "same seed, different files"
cmp -s "$WORK/a.json" "$WORK/c.json" && fail "different seeds, same file"
grep -q '"name": "movingai-random-32-32-10-8-s1"' "$WORK/a.json" || fail "unexpected scenario name"
if [ -x /usr/bin/python3 ]; then
  ws=$(/usr/bin/python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["workspace"]; print(w["min"]+w["max"])' "$WORK/a.json")
  [ "$ws" = "[0.0, 0.0, 32.0, 32.0]" ] || [ "$ws" = "[0, 0, 32, 32]" ] || fail "workspace is $ws, not [0,32]x[0,32]"
fi
"$GEN" movingai "$MAP" --robots 4 --shape disc --radius 0.3 -o "$WORK/d.json" > /dev/null || fail "disc exited $?"

printf 'type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n' > "$WORK/bad.map"
"$GEN" movingai "$WORK/bad.map" --robots 1 -o "$WORK/x.json" > /dev/null 2> "$WORK/err"
[ $? -eq 2 ] || fail "a malformed map did not exit 2"
grep -q "bad.map: line 6: column 2: unknown terrain character 'x'" "$WORK/err" || fail "unhelpful error: $(cat "$WORK/err")"
# A NUL byte (or another control byte) is named by line, column and value,
# and the message goes on past it: a NUL in the text cut it short.
printf 'type octile\nheight 2\nwidth 3\nmap\n...\n.\0.\n' > "$WORK/nul.map"
"$GEN" movingai "$WORK/nul.map" --robots 1 -o "$WORK/x.json" > /dev/null 2> "$WORK/err"
[ $? -eq 2 ] || fail "a map with a NUL did not exit 2"
grep -qxF "earc-scenario: error: $WORK/nul.map: line 6: column 2: unknown terrain character byte 0x00" "$WORK/err" \
  || fail "a NUL in a map: $(cat -v "$WORK/err")"
"$GEN" movingai "$WORK/missing.map" --robots 1 -o "$WORK/x.json" > /dev/null 2>&1
[ $? -eq 2 ] || fail "a missing map did not exit 2"
# Robots that do not fit, and a radius for boxes, are bad input too.
printf 'type octile\nheight 2\nwidth 2\nmap\n@@\n@@\n' > "$WORK/blocked.map"
for args in "$WORK/blocked.map --robots 1" "random-32-32-20 --radius 0.2"; do
  # shellcheck disable=SC2086  # map and options
  "$GEN" movingai $args -o "$WORK/x.json" > /dev/null 2> "$WORK/err"
  [ $? -eq 2 ] || fail "movingai $args did not exit 2: $(cat "$WORK/err")"
  [ "$(wc -l < "$WORK/err")" -eq 1 ] || fail "movingai $args: not one line: $(cat "$WORK/err")"
done
grep -qF -- "--radius: applies to --shape disc only" "$WORK/err" || fail "--radius with boxes: $(cat "$WORK/err")"
# A disc radius has the bounds generate gives it: at least 0.01, at most a
# quarter of the map's smaller side (a 1e-300 radius used to be placed).
for r in 1e-300 20; do
  "$GEN" movingai random-32-32-20 --robots 2 --shape disc --radius $r -o "$WORK/x.json" > /dev/null 2> "$WORK/err"
  [ $? -eq 2 ] || fail "--radius $r did not exit 2: $(cat "$WORK/err")"
  grep -qF -- "--radius: must be in [0.01, 8], got $r" "$WORK/err" || fail "--radius $r: $(cat "$WORK/err")"
done
# A map too small for the 0.6 x 0.4 box is said in terms of the options
# there are (the box's size is none: it read "--box length: must be in
# [0.01, 0.5], got 0.6"), and the disc it suggests fits.
printf 'type octile\nheight 1\nwidth 1\nmap\n.\n' > "$WORK/tiny.map"
printf 'type octile\nheight 1\nwidth 5\nmap\n.....\n' > "$WORK/strip.map"
for m in tiny:1x1 strip:5x1; do
  name=${m%%:*} size=${m#*:}
  refusedInOneLine "$WORK/$name.map: --shape: the ${size/x/ x } map is too small for the 0.6 x 0.4 box footprint" \
    "$GEN" movingai "$WORK/$name.map" --robots 1 -o "$WORK/x.json"
  grep -qF -- "use --shape disc with --radius at most 0.25" "$WORK/err" || fail "$name.map: no way out: $(cat "$WORK/err")"
  grep -qF -- "--box" "$WORK/err" && fail "$name.map: names an option that does not exist: $(cat "$WORK/err")"
  "$GEN" movingai "$WORK/$name.map" --robots 1 --shape disc --radius 0.25 -o "$WORK/$name.json" > /dev/null ||
    fail "$name.map: the suggested disc does not fit"
done
# Only octile maps are read (a hex map's cells are not squares), and an
# empty file lacks line 1 (it said "line 0"): lines count from 1.
for type in hex whatever; do
  printf 'type %s\nheight 1\nwidth 1\nmap\n.\n' "$type" > "$WORK/$type.map"
  refusedInOneLine "$type.map: line 1: expected the header 'type octile', got 'type $type'" \
    "$GEN" movingai "$WORK/$type.map" --shape disc --radius 0.25 -o "$WORK/x.json"
done
: > "$WORK/empty.map"
refusedInOneLine "empty.map: line 1: the file is empty" "$GEN" movingai "$WORK/empty.map" -o "$WORK/x.json"
# An empty name is refused as such, naming the argument (the error named nothing).
refusedInOneLine "map: an empty file name" "$GEN" movingai "" -o "$WORK/x.json"
# A name that is neither a file nor a compiled-in map says both, listing
# the compiled-in maps (it said only "cannot open file").
refusedInOneLine "empty-32-32: no such file, nor a compiled-in map (den520d, empty-16-16, random-32-32-10, random-32-32-20, room-32-32-4, warehouse-10-20-10-2-1)" \
  "$GEN" movingai empty-32-32 --robots 2 -o "$WORK/x.json"
# A compiled-in map by name, from a directory without it: the same scenario.
(cd "$WORK" && "$GEN" movingai random-32-32-10 --robots 8 --seed 1 -o "$WORK/e.json" > /dev/null) ||
  fail "the compiled-in map random-32-32-10 was not found by name"
cmp -s "$WORK/a.json" "$WORK/e.json" || fail "the compiled-in map gave another scenario than the file"
[ -e "$WORK/x.json" ] && fail "a failed run left an output file"
echo "ok"
