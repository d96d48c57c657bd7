#!/usr/bin/env bash
# Side by side: earc's crowd solver (earc-plan --method lacam --refine S)
# and LaCAM3 (Okumura 2024; built separately, one thread) on the MovingAI
# files' first N agents, one run after the other, R repeats; prints the
# median sum of costs over the grid lower bound (LaCAM3's soc_lb) per row.
#   tools/bench-lacam3.sh BUILD LACAM3_BIN [SECONDS] [REPEATS] [MAP:N ...]
# LaCAM3: github.com/Kei18/lacam3 (cmake -B build && make -C build), binary build/main.
set -euo pipefail
build=${1:?build directory}; lacam3=${2:?LaCAM3 binary}; secs=${3:-5}; reps=${4:-3}
shift $(( $# < 4 ? $# : 4 ))
cases=("$@")
[[ ${#cases[@]} -gt 0 ]] || cases=(empty-16-16:100 empty-16-16:128 random-32-32-20:200 random-32-32-20:300
  room-32-32-4:100 room-32-32-4:150 room-32-32-4:200 warehouse-10-20-10-2-1:300 warehouse-10-20-10-2-1:500)
src=$(cd "$(dirname "$0")/.." && pwd)
data=${EARC_MOVINGAI:-$src/../shared/datasets/movingai}
[[ -d $data ]] || { echo "bench-lacam3: $data: no MovingAI maps (set EARC_MOVINGAI)" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "| map | robots | earc lacam --refine $secs: SOC / LB | LaCAM3 -t $secs, one thread: SOC / LB | earc / LaCAM3 |"
echo "|---|---:|---:|---:|---:|"
for c in "${cases[@]}"; do
  map=${c%:*}; n=${c#*:}
  "$build/earc-scenario" movingai "$map" --scen "$map-random-1" --robots "$n" -o "$tmp/s.json" >/dev/null
  e=(); l=(); lb=0
  for ((r = 1; r <= reps; r++)); do
    "$lacam3" -m "$data/$map.map" -i "$data/$map-random-1.scen" -N "$n" -t "$secs" --no-multi-thread \
      -s "$r" -o "$tmp/l.txt" >/dev/null 2>&1 || true
    lb=$(sed -n 's/^soc_lb=//p' "$tmp/l.txt"); l+=("$(sed -n 's/^soc=//p' "$tmp/l.txt")")
    "$build/earc-plan" plan "$tmp/s.json" --method lacam --refine "$secs" --seed "$r" -o "$tmp/e.json" >/dev/null 2>&1 || true
    e+=("$(python3 -c "import json,sys; s = json.load(open(sys.argv[1]))['stats']; print(s['sum_of_costs'] / s['lacam']['steps_per_roadmap_step'])" "$tmp/e.json" 2>/dev/null || echo nan)")
  done
  python3 - "$map" "$n" "$lb" "${e[*]}" "${l[*]}" <<'PY'
import statistics, sys
m, n, lb = sys.argv[1], sys.argv[2], float(sys.argv[3] or "nan")
e = [float(x) for x in sys.argv[4].split()]; l = [float(x) for x in sys.argv[5].split() if x]
me, ml = statistics.median(e), (statistics.median(l) if l else float("nan"))
print(f"| {m} | {n} | {me / lb:.2f} | {ml / lb:.2f} | {me / ml:.2f} |")
PY
done
