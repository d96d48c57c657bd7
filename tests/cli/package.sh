#!/bin/bash
# label: package
# The installed C++ package: `cmake --install` into a temporary prefix puts
# the headers, the libraries and earcConfig.cmake there; an outside program
# (tests/package) built with find_package(earc) against that prefix alone
# loads a scenario, plans it and validates the plan, and reports bad input
# in one line. Not in the sanitizer run: its libraries want the sanitizers'
# flags in every program that links them.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
failShowsOutput
PREFIX="$WORK/prefix"
cmake --install "$BUILD" --prefix "$PREFIX" > "$WORK/out" 2> "$WORK/err" || fail "cmake --install exited $?"
[ -f "$PREFIX/include/earc/earc.hpp" ] || fail "no include/earc/earc.hpp installed"
config=$(find "$PREFIX" -name earcConfig.cmake | head -1)
[ -n "$config" ] || fail "no earcConfig.cmake installed"
[ -f "$(dirname "$config")/earcConfigVersion.cmake" ] || fail "no earcConfigVersion.cmake beside $config"
ls "$PREFIX"/lib*/libearc_core.a > /dev/null 2>&1 || fail "no libearc_core.a installed"
# The package alone: the source and build trees stay out of the search.
cmake -S "$SRC/tests/package" -B "$WORK/user" -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_BUILD_TYPE=Release \
  > "$WORK/out" 2> "$WORK/err" || fail "configuring the outside program exited $?"
cmake --build "$WORK/user" -j2 > "$WORK/out" 2> "$WORK/err" || fail "building the outside program exited $?"
if grep -rq -- "$BUILD/layers\|$SRC/include" "$WORK/user/CMakeFiles" 2> /dev/null; then
  fail "the outside program was compiled against the build or source tree, not the installed headers"
fi

"$WORK/user/plan_one" "$SRC/datasets/mobile-4-s1.json" > "$WORK/out" 2> "$WORK/err" || fail "plan_one exited $?"
grep -q "solved, valid yes, robots 4, .*method arc" "$WORK/out" || fail "plan_one: $(cat "$WORK/out")"
planned=$(cat "$WORK/out")
# The same plan as earc-plan's with the same seed and budgets.
"$BUILD/earc-plan" plan "$SRC/datasets/mobile-4-s1.json" -o "$WORK/sol.json" --seed 7 --deterministic -q ||
  fail "earc-plan exited $?"
want=$("$PY" -c 'import json,sys; s=json.load(open(sys.argv[1]))["stats"]; print(s["makespan"], s["sum_of_costs"])' "$WORK/sol.json")
[[ $planned == *"makespan ${want% *}, sum of costs ${want#* },"* ]] ||
  fail "plan_one and earc-plan differ: $planned against makespan and sum of costs $want"

# Bad input: one line naming the file and the field, exit 2.
printf '{"format": "earc.scenario.v1", "name": "x", "workspace": {"min": [0, 0], "max": [1, 1]}, "robots": 3}' \
  > "$WORK/bad.json"
"$WORK/user/plan_one" "$WORK/bad.json" > "$WORK/out" 2> "$WORK/err"
rc=$?
[ $rc -eq 2 ] || fail "plan_one on a bad scenario exited $rc, not 2"
[ "$(wc -l < "$WORK/err")" -eq 1 ] && grep -q "bad.json" "$WORK/err" && grep -q '\$.robots' "$WORK/err" ||
  fail "plan_one on a bad scenario: $(cat "$WORK/err")"
echo "ok: $planned"
