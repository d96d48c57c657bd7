#!/usr/bin/env bash
# Configures and builds earc into a build directory.
#   tools/build.sh [BUILD_DIR] [extra cmake args...]
# A unity build: CMake compiles each target's sources in batches of 32, so
# the heavy header-only libraries (CLI11, nlohmann::json) are parsed, and
# their templates instantiated, once per batch, not once per file: about
# half the time of a clean build (docs/performance-log.md). For a tree
# rebuilt after small edits, file by file is quicker: pass
# -DCMAKE_UNITY_BUILD=OFF.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$src/build}
shift || true
jobs=$(nproc 2>/dev/null || echo 2)
# Ninja, where installed, for a new build directory: it compiles a target's
# files without waiting for the libraries it links to be archived, so the
# layers' libraries, the programs and the tests compile side by side (Make
# builds them one target after another). A directory keeps its generator.
generator=()
if [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja > /dev/null; then
  generator=(-G Ninja)
fi
cmake -S "$src" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=32 "$@" >/dev/null
cmake --build "$build" -j"$jobs"
