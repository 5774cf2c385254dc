#!/usr/bin/env bash
# README command 2: every test of MRSV.
#   1. set-up and the Release build, then ctest: every test (unit tests, CLI
#      tests, the conformance suite, fuzz-corpus replays, vector regeneration);
#   2. the tests of the code that reads untrusted bytes (decoders, reconstructors,
#      file readers, the CLI, the conformance suite through it: ctest label
#      "sanitize") again under AddressSanitizer + UBSan, without the few cases that
#      repeat the same code on the largest real data (SANITIZE_SKIP below);
#   3. the decode library built alone (no CGAL, no TetGen) with clang, libFuzzer,
#      ASan + UBSan and -Werror: its tests, then a short run of every fuzz target
#      (MRSV_FUZZ_SECONDS per target, default 10).
# Stages 2 and 3 build at -O1 with line tables only, and stage 2 builds only what its
# tests run: that cuts their compile time to a third, so that CI stays within 30 minutes
# on 2 cores.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)
fuzz_seconds=${MRSV_FUZZ_SECONDS:-10}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

step() { echo; echo "=== $* ==="; }
# Builds a tree (and targets) quietly; a failed build stops the script with its errors shown.
build() {
  local log
  log=$(mktemp)
  if ! cmake --build "$@" -j "$jobs" >"$log" 2>&1; then
    grep -E "error|Error" "$log" | head -40
    rm -f "$log"
    echo "test.sh: the build in $1 failed" >&2
    exit 1
  fi
  rm -f "$log"
}

step "set-up and Release build"
"$root/tools/setup.sh"

step "ctest (Release)"
ctest --test-dir "$root/build" --output-on-failure -j "$jobs"

# The sanitizer builds: -O1 and line tables (half the compile time of -O2 -g, the
# tests about a tenth slower).
quick_flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
             -DMRSV_SANITIZE=ON -DMRSV_WERROR=ON)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Cases left out under the sanitizers (the Release stage runs them): every prefix of
# every valid vector (200 s there; the fuzz targets truncate too), the SRTM tiles'
# quadtree counts (94 s), PT on the two largest PLOT3D meshes (13 s each; the CT crop,
# the hand and the bunny still run), the removal passes over three terrain crops at four
# bounds (26 s and 22 s; cli_tests and the border clean-up test still run that code).
SANITIZE_SKIP=ConformanceVectors.EveryPrefixOfAValidVectorIsHandled:Quadtree.SrtmTileCounts
SANITIZE_SKIP+=:PtRealData.BluntFin:PtRealData.CombustionChamber
SANITIZE_SKIP+=:Quadtree.RemovalPassKeepsTheBoundAndTheBorder:TerrainInsertion.RemovalPassKeepsTheBoundAndTheBorder

step "ctest -L sanitize under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S "$root" -B "$root/build-asan" "${generator[@]}" "${quick_flags[@]}" >/dev/null
build "$root/build-asan" --target sanitize_tests
GTEST_FILTER="-$SANITIZE_SKIP" ctest --test-dir "$root/build-asan" --output-on-failure -j "$jobs" -L sanitize

step "decode library alone (MRSV_DECODER_ONLY: no CGAL, no TetGen; clang, ASan + UBSan)"
CC=clang CXX=clang++ cmake -S "$root" -B "$root/build-fuzz" "${generator[@]}" "${quick_flags[@]}" \
  -DMRSV_DECODER_ONLY=ON -DMRSV_FUZZ=ON >/dev/null
build "$root/build-fuzz"
GTEST_FILTER="-$SANITIZE_SKIP" ctest --test-dir "$root/build-fuzz" --output-on-failure -j "$jobs"

step "fuzz smoke: ${fuzz_seconds} s per target (libFuzzer, ASan + UBSan)"
"$root/fuzz/run_fuzz.sh" "$root/build-fuzz" "$fuzz_seconds"

echo
echo "test.sh: 3 stages passed"
