#!/usr/bin/env bash
# Retrieval benchmark of the experience store's two engines (not a test):
# k = 10 retrieval from an SQLite file, from PostgreSQL over the Unix
# socket and over TCP 127.0.0.1 (a server of its own, tools/postgres-dev.sh),
# interleaved, each REPEATS times; prints every run and the medians.
#   tools/pg-retrieval-bench.sh BUILD_DIR uniform [ENTRIES] [QUERIES] [REPEATS]
#     earc-db bench-retrieval: ENTRIES synthetic rows in each of 4 classes
#     (default 25000), QUERIES uniformly random queries per class (1000),
#     the row cache on (its default bound) and off. ENGINES (default
#     "sqlite socket tcp"; socket-cold and tcp-cold: --no-warm-rows, no
#     background copy) and CACHES (default "64 0", MiB) choose the runs.
#   tools/pg-retrieval-bench.sh BUILD_DIR stream [REPEATS]
#     the queries of real plans: a store learned from E-ARC plans of
#     mobile-obst 32 scenarios (seeds 2-4), copied exactly into PostgreSQL
#     (export, import), then E-ARC plans without learning of seeds 1, 5 and
#     6 read from each copy: retrieval time per query and row cache hits
#     (db_retrieval_time_s, db_row_cache_hits in the solution's stats).
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR uniform|stream ...}" && pwd)
mode=${2:?usage: $0 BUILD_DIR uniform|stream ...}
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
pg=$(mktemp -u /tmp/earc-pg-rbench.XXXXXX)  # not under $work: the server user must reach it
trap 'bash "$src/tools/postgres-dev.sh" stop "$pg" > /dev/null 2>&1; rm -rf "$work"' EXIT
bash "$src/tools/postgres-dev.sh" start "$pg" > /dev/null
socket=$(cat "$pg/uri-socket")
tcp=$(cat "$pg/uri-tcp")
# newDb: a new empty database on the server; its name.
newDb() {
  local name=b$(date +%s%N)
  psql -X -q "$tcp" -c "CREATE DATABASE $name" > /dev/null
  echo "$name"
}
at() { echo "${1%/*}/$2"; }  # at URI DBNAME: the URI naming another database
echo "$(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start"

case $mode in
  uniform)
    entries=${3:-25000}
    queries=${4:-1000}
    repeats=${5:-3}
    for r in $(seq 1 "$repeats"); do
      for cache in ${CACHES:-64 0}; do
        for engine in ${ENGINES:-sqlite socket tcp}; do
          name=$(newDb)
          case $engine in
            sqlite) db=() ;;
            socket) db=(--db "$(at "$socket" "$name")") ;;
            tcp) db=(--db "$(at "$tcp" "$name")") ;;
            socket-cold) db=(--db "$(at "$socket" "$name")" --no-warm-rows) ;;
            tcp-cold) db=(--db "$(at "$tcp" "$name")" --no-warm-rows) ;;
            *) echo "$0: unknown engine $engine" >&2; exit 2 ;;
          esac
          out="$work/uniform-$engine-cache$cache-$r.txt"
          "$build/earc-db" bench-retrieval --entries "$entries" --queries "$queries" --row-cache-mb "$cache" \
            "${db[@]}" > "$out"
          echo "== $engine, row cache $cache MiB, run $r"
          cat "$out"
        done
      done
    done
    /usr/bin/python3 - "$work" "$repeats" "${ENGINES:-sqlite socket tcp}" "${CACHES:-64 0}" <<'PY'
import glob, os, re, statistics, sys
work, repeats, engines, caches = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(), sys.argv[4].split()
rows = {}  # (engine, cache, class) -> list of (median, cpu, hit, again)
for f in glob.glob(os.path.join(work, "uniform-*.txt")):
    engine, cache = re.match(r"uniform-([\w-]+)-cache(\d+)-\d+\.txt", os.path.basename(f)).groups()
    for line in open(f):
        m = re.match(r"^((?:mobile|manipulator) [^0-9]*\S*(?: facing)?)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)", line)
        if m:
            rows.setdefault((engine, cache, m.group(1).strip()), []).append(
                (float(m.group(4)), float(m.group(6)), float(m.group(7)), float(m.group(8))))
classes = sorted({k[2] for k in rows}, key=lambda c: (c.startswith("manip"), c))
print("\nmedians over %d runs, us (first pass | asked again); ratio to SQLite with the same cache setting" % repeats)
pg = [e for e in engines if e != "sqlite"]
for cache in caches:
    print("\nrow cache %s MiB" % cache)
    print("%-22s %16s" % ("class", "sqlite") + "".join(" %26s" % e for e in pg) + "".join(" %6s" % ("hit% " + e[:6]) for e in pg))
    for c in classes:
        def med(engine, i):
            v = rows.get((engine, cache, c))
            return statistics.median(x[i] for x in v) if v else float("nan")
        s, s2 = med("sqlite", 0), med("sqlite", 3)
        cells = ["%7.0f | %6.0f" % (s, s2)]
        for e in pg:
            cells.append("%7.0f (%.2fx) | %5.0f (%.2fx)" % (med(e, 0), med(e, 0) / s, med(e, 3), med(e, 3) / s2))
        print("%-22s %16s" % (c, cells[0]) + "".join(" %26s" % x for x in cells[1:]) + "".join(" %6.1f" % med(e, 2) for e in pg))
PY
    ;;
  stream)
    repeats=${3:-3}
    for seed in 1 2 3 4 5 6; do
      "$build/earc-scenario" generate --family mobile --robots 32 --obstacles --seed $seed -o "$work/s$seed.json" > /dev/null
    done
    "$build/earc-db" build --db "$work/learned.db" --scenario "$work/s1.json" -q > /dev/null
    for seed in 2 3 4; do
      "$build/earc-plan" plan "$work/s$seed.json" -o "$work/train.json" --method earc --db "$work/learned.db" \
        --seed 1 -q > /dev/null 2>&1 || true
    done
    "$build/earc-db" export --db "$work/learned.db" -o "$work/learned.jsonl" > /dev/null
    name=$(newDb)  # one server database, two ways in
    tcp_db=$(at "$tcp" "$name")
    sock_db=$(at "$socket" "$name")
    "$build/earc-db" import --db "$tcp_db" "$work/learned.jsonl" > /dev/null
    echo "learned store: $(wc -l < "$work/learned.jsonl") rows"
    for r in $(seq 1 "$repeats"); do
      for engine in sqlite socket tcp; do
        case $engine in
          sqlite) db=$work/learned.db ;;
          socket) db=$sock_db ;;
          tcp) db=$tcp_db ;;
        esac
        for seed in 1 5 6; do
          "$build/earc-plan" plan "$work/s$seed.json" -o "$work/out.json" --method earc --db "$db" --no-learn \
            --seed 1 -q > /dev/null 2>&1 || true
          jq -r --arg e "$engine" --arg s "$seed" --arg r "$r" \
            '[$e, $s, $r, .stats.db_queries, .stats.db_retrieval_time_s, .stats.db_row_cache_hits, .stats.db_row_cache_misses, .stats.planning_time_s // 0] | @tsv' \
            "$work/out.json" | tee -a "$work/stream.tsv"
        done
      done
    done
    /usr/bin/python3 - "$work/stream.tsv" <<'PY'
import statistics, sys
runs = {}  # engine -> list of (per query us, hits, misses) per run (all three scenarios)
by = {}
for line in open(sys.argv[1]):
    e, s, r, q, t, h, m, _ = line.split("\t")
    by.setdefault((e, r), []).append((int(q), float(t), int(h), int(m)))
for (e, r), v in by.items():
    q = sum(x[0] for x in v); t = sum(x[1] for x in v); h = sum(x[2] for x in v); m = sum(x[3] for x in v)
    runs.setdefault(e, []).append((1e6 * t / max(q, 1), q, h, m))
print("\nretrieval wall time per query, median of runs (all three plans), and the row cache's hit rate")
base = statistics.median(x[0] for x in runs["sqlite"])
for e in ("sqlite", "socket", "tcp"):
    v = runs[e]
    us = statistics.median(x[0] for x in v)
    hits = sum(x[2] for x in v); misses = sum(x[3] for x in v)
    print("%-7s %8.1f us/query (%.2fx SQLite)  queries/run %s  row cache hit %.1f %%" %
          (e, us, us / base, "/".join(str(x[1]) for x in v), 100.0 * hits / max(hits + misses, 1)))
PY
    ;;
  *) echo "$0: mode is uniform or stream" >&2; exit 2 ;;
esac
echo "load average $(cut -d' ' -f1-3 /proc/loadavg) at the end"
