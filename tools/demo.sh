#!/usr/bin/env bash
# Quick start, part one: install what is missing, build, and run the main
# job on the default scenario (16 mobile robots among obstacles): build an
# experience database for its robots (once; later runs reuse it, and it
# keeps what each plan learned), plan the scenario with E-ARC, check the
# solution with the validator, and draw it.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
bash "$src/tools/setup.sh"
bash "$src/tools/build.sh" "$src/build"
out=$src/out
mkdir -p "$out"
scenario=$src/datasets/mobile-obst-16-s1.json
db=$out/earc-mobile.sqlite
bin=$src/build
# Built aside and moved into place when complete: an interrupted build
# leaves no half-filled database for the next run to take as finished.
if [ ! -e "$db" ]; then
  rm -f "$db.partial" "$db.partial-wal" "$db.partial-shm"
  "$bin/earc-db" build --db "$db.partial" --scenario "$scenario" --seed 1
  mv "$db.partial" "$db"
fi
"$bin/earc-plan" plan "$scenario" -o "$out/mobile-obst-16-s1.solution.json" --method earc --db "$db" \
  --time-limit 60 --seed 1
"$bin/earc-plan" validate "$scenario" "$out/mobile-obst-16-s1.solution.json"
"$bin/earc-plan" render "$scenario" "$out/mobile-obst-16-s1.solution.json" -o "$out/mobile-obst-16-s1.svg"
echo "picture: $out/mobile-obst-16-s1.svg"
echo "experience database: $db ($bin/earc-db inspect --db $db)"
