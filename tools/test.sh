#!/usr/bin/env bash
# Quick start, part two: install what is missing, build, and run every test:
# the whole suite on the Release build, then the unit and command-line tests
# again under AddressSanitizer and UndefinedBehaviorSanitizer.
#   tools/test.sh            everything CI runs
#   EARC_TEST_SLOW=1 tools/test.sh   also the long stress and crash tests
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc 2>/dev/null || echo 2)
# Tests run two to a core: most spend much of their time waiting (on
# services, sockets, PostgreSQL, Chromium, their own time limits), so one
# job per core leaves the cores part idle. plan_limits, with the tightest
# wall-clock bounds, runs beside one other test (tests/CMakeLists.txt).
test_jobs=$((2 * jobs))
bash "$src/tools/setup.sh" --tests

label_args=()
if [[ "${EARC_TEST_SLOW:-0}" != "1" ]]; then
  label_args=(-LE slow)
fi

# took PHASE: says how long PHASE took since the last call.
since=$SECONDS
took() { echo "-- $1: $((SECONDS - since)) s"; since=$SECONDS; }
took setup

echo "== Release build and tests"
bash "$src/tools/build.sh" "$src/build"
took "Release build"
(cd "$src/build" && ctest -j"$test_jobs" --output-on-failure "${label_args[@]}")
took "Release tests"

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
# -O1 and line tables only (-g1): what the sanitizers' reports need, at
# about half the compile time of -O2 -g (docs/performance-log.md).
# Both builds are unity builds (tools/build.sh), which halves them again.
# The tests' own code, and there the programs', is compiled at -O0
# (tests/CMakeLists.txt, CMakeLists.txt); the libraries keep these flags.
# No Python module there: its tests and the package's are not run under
# the sanitizers (labels python and package).
bash "$src/tools/build.sh" "$src/build-asan" -DEARC_SANITIZE=ON -DEARC_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
took "sanitizer build"
# The unit tests (one per source file there, tests/CMakeLists.txt) and the
# command-line tests that run C++ (label unsanitized: those that do not).
# The stress, crash and damaged-file loops run the same code paths as in
# the Release half, in fewer rounds: the sanitizers need a path run, and
# the Release half keeps the rounds that look for rare interleavings.
# One job per core here: the instrumented tests keep the cores busy, and
# at two per core serve_crash's service was killed before its first answer.
(cd "$src/build-asan" && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
   UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
   EARC_STRESS_SECONDS=${EARC_STRESS_SECONDS:-15} EARC_CRASH_KILLS=${EARC_CRASH_KILLS:-20} \
   EARC_HOSTILE_FLIPS=${EARC_HOSTILE_FLIPS:-5} \
   ctest -j"$jobs" --output-on-failure -L "unit|cli" -LE "slow|browser|bench|package|python|unsanitized")
took "sanitizer tests"
