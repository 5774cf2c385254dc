#!/usr/bin/env bash
# README command 2: every test of MRSV.
#   1. set-up and the Release build, then ctest (unit tests, CLI tests, the
#      conformance suite, fuzz-corpus replays, vector regeneration check);
#   2. the unit and replay tests again under AddressSanitizer + UBSan;
#   3. the decode library built alone (no CGAL, no TetGen) and its tests;
#   4. a short libFuzzer run of every fuzz target under ASan + UBSan
#      (MRSV_FUZZ_SECONDS per target, default 20: ten targets keep CI under 30 minutes).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)
fuzz_seconds=${MRSV_FUZZ_SECONDS:-20}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

step() { echo; echo "=== $* ==="; }
# Builds a tree quietly; a failed build stops the script with its errors shown.
build() {
  local log
  log=$(mktemp)
  if ! cmake --build "$1" -j "$jobs" >"$log" 2>&1; then
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

step "ctest under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S "$root" -B "$root/build-asan" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMRSV_SANITIZE=ON -DMRSV_WERROR=ON >/dev/null
build "$root/build-asan"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir "$root/build-asan" --output-on-failure -j "$jobs"

step "decode library alone (MRSV_DECODER_ONLY: no CGAL, no TetGen)"
cmake -S "$root" -B "$root/build-decoder" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DMRSV_DECODER_ONLY=ON -DMRSV_WERROR=ON >/dev/null
build "$root/build-decoder"
ctest --test-dir "$root/build-decoder" --output-on-failure -j "$jobs"

step "fuzz smoke: ${fuzz_seconds} s per target (libFuzzer, ASan + UBSan)"
CC=clang CXX=clang++ cmake -S "$root" -B "$root/build-fuzz" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMRSV_DECODER_ONLY=ON -DMRSV_FUZZ=ON -DMRSV_SANITIZE=ON >/dev/null
build "$root/build-fuzz"
"$root/fuzz/run_fuzz.sh" "$root/build-fuzz" "$fuzz_seconds"

echo
echo "test.sh: 4 passed, 0 failed"
