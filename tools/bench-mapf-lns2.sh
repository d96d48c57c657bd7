#!/usr/bin/env bash
# Side by side: MAPF-LNS2 (Li et al. 2022, anytime LNS after its first
# solution, one thread) and earc's crowd solver (earc-plan --method lacam
# --refine S) on the MovingAI files' first N agents, R repeats (seeds 1..R),
# one run after the other; prints a markdown table of the median sum of costs
# over the lower bound (sum of shortest path lengths, MAPF-LNS2's figure).
#   tools/bench-mapf-lns2.sh BUILD_OR_- LNS2_BIN [SECONDS] [REPEATS] [MAP:N ...]
# BUILD "-" leaves earc out. Set EARC_LACAM3=path/to/lacam3/main to add
# LaCAM3 (one thread) as a third column, and LNS2_OPTS to change MAPF-LNS2's
# options (default: --maxIterations 1000000000, so that it keeps improving
# until the time limit; its own default stops at the first solution).
# MAPF-LNS2: github.com/Jiaoyang-Li/MAPF-LNS2, needs Boost (program_options,
# system, filesystem) and Eigen 3: cmake -B build -DCMAKE_BUILD_TYPE=RELEASE
# && make -C build; binary build/lns. Its -t does not count its heuristic
# tables; earc's and LaCAM3's times do. BALANCE (Phan et
# al. 2024, github.com/thomyphan/anytime-mapf, binary build/balance) takes
# the same command line and writes the same CSV.
set -euo pipefail
build=${1:?build directory or -}; lns2=${2:?MAPF-LNS2 binary}; secs=${3:-5}; reps=${4:-3}
shift $(( $# < 4 ? $# : 4 ))
cases=("$@")
[[ ${#cases[@]} -gt 0 ]] || cases=(room-32-32-4:150 room-32-32-4:200 random-32-32-20:200
  random-32-32-20:300 warehouse-10-20-10-2-1:300 warehouse-10-20-10-2-1:500)
read -r -a lns2_opts <<< "${LNS2_OPTS:---maxIterations 1000000000}"
lacam3=${EARC_LACAM3:-}
[[ $build == - ]] && build=
src=$(cd "$(dirname "$0")/.." && pwd)
data=${EARC_MOVINGAI:-$src/../shared/datasets/movingai}
[[ -d $data ]] || { echo "bench-mapf-lns2: $data: no MovingAI maps (set EARC_MOVINGAI)" >&2; exit 2; }
[[ -x $lns2 ]] || { echo "bench-mapf-lns2: $lns2: not an executable" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
head="| map | robots | LB | MAPF-LNS2 -t $secs: SOC / LB | its first solution, s"
rule="|---|---:|---:|---:|---:"
[[ -n $build ]] && { head+=" | earc lacam --refine $secs: SOC / LB | earc / MAPF-LNS2"; rule+="|---:|---:"; }
[[ -n $lacam3 ]] && { head+=" | LaCAM3 -t $secs: SOC / LB"; rule+="|---:"; }
echo "$head |"; echo "$rule|"
for c in "${cases[@]}"; do
  map=${c%:*}; n=${c#*:}
  [[ -n $build ]] && "$build/earc-scenario" movingai "$map" --scen "$map-random-1" --robots "$n" -o "$tmp/s.json" >/dev/null
  : > "$tmp/rows"
  for ((r = 1; r <= reps; r++)); do
    # MAPF-LNS2 appends a CSV row per run: 2 SOC, 5 sum of distances, 8 first solution time.
    rm -f "$tmp/m-LNS.csv"
    "$lns2" -m "$data/$map.map" -a "$data/$map-random-1.scen" -k "$n" -t "$secs" --seed "$r" \
      "${lns2_opts[@]}" -o "$tmp/m" >/dev/null 2>&1 || true
    row=$(tail -n 1 "$tmp/m-LNS.csv" 2>/dev/null | awk -F, '{print $2, $5, $8}')
    e=nan l=nan
    if [[ -n $build ]]; then
      "$build/earc-plan" plan "$tmp/s.json" --method lacam --refine "$secs" --seed "$r" -o "$tmp/e.json" >/dev/null 2>&1 || true
      e=$(python3 -c "import json,sys; s = json.load(open(sys.argv[1]))['stats']; print(s['sum_of_costs'] / s['lacam']['steps_per_roadmap_step'])" "$tmp/e.json" 2>/dev/null || echo nan)
    fi
    if [[ -n $lacam3 ]]; then
      rm -f "$tmp/l.txt"
      "$lacam3" -m "$data/$map.map" -i "$data/$map-random-1.scen" -N "$n" -t "$secs" --no-multi-thread \
        -s "$r" -o "$tmp/l.txt" >/dev/null 2>&1 || true
      l=$(sed -n 's/^soc=//p' "$tmp/l.txt" 2>/dev/null); l=${l:-nan}
      lb3=$(sed -n 's/^soc_lb=//p' "$tmp/l.txt" 2>/dev/null)
      [[ -z $lb3 || -z $row || $lb3 == "$(cut -d' ' -f2 <<< "$row")" ]] ||
        echo "bench-mapf-lns2: $map $n: LaCAM3's soc_lb $lb3 differs from MAPF-LNS2's LB" >&2
    fi
    echo "${row:-0 0 nan} $e $l" >> "$tmp/rows"
  done
  python3 - "$map" "$n" "$tmp/rows" "$build" "$lacam3" <<'PY'
import math, statistics, sys
m, n, rows, with_earc, with_lacam3 = sys.argv[1:6]
rows = [[float(x) for x in line.split()] for line in open(rows)]
lb = max(r[1] for r in rows) or math.nan
med = lambda xs: statistics.median(xs) if xs else math.nan
ok = [r for r in rows if r[0] > 0]  # MAPF-LNS2 writes 0 when it found no solution
ms, mt = med([r[0] for r in ok]), med([r[2] for r in ok])
solved = "" if len(ok) == len(rows) else f" ({len(ok)}/{len(rows)} solved)"
out = [m, n, f"{lb:.0f}", f"{ms / lb:.2f}{solved}", f"{mt:.2f}"]
if with_earc:
    me = med([r[3] for r in rows if not math.isnan(r[3])])
    out += [f"{me / lb:.2f}", f"{me / ms:.2f}"]
if with_lacam3:
    out.append(f"{med([r[4] for r in rows if not math.isnan(r[4])]) / lb:.2f}")
print("| " + " | ".join(out) + " |")
PY
done
