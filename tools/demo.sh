#!/usr/bin/env bash
# Quick start, part one: install what is missing, build, and run the main
# job on the default scenario (16 mobile robots among obstacles): plan it
# with ARC, check the solution with the validator, and draw it.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
bash "$src/tools/setup.sh"
bash "$src/tools/build.sh" "$src/build"
out=$src/out
mkdir -p "$out"
scenario=$src/datasets/mobile-obst-16-s1.json
bin=$src/build
"$bin/earc-plan" plan "$scenario" -o "$out/mobile-obst-16-s1.solution.json" --method arc --time-limit 60 --seed 1
"$bin/earc-plan" validate "$scenario" "$out/mobile-obst-16-s1.solution.json"
"$bin/earc-plan" render "$scenario" "$out/mobile-obst-16-s1.solution.json" -o "$out/mobile-obst-16-s1.svg"
echo "picture: $out/mobile-obst-16-s1.svg"
