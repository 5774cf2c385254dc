#!/usr/bin/env bash
# Runs every libFuzzer target of a fuzz build for SECONDS each, seeded from the
# conformance vectors (container, coded, tiled, PT and reconstruction) and the
# committed corpus. New inputs go to a scratch corpus; crashes are written to
# fuzz/findings/ and fail the run.
# Usage: fuzz/run_fuzz.sh BUILD_DIR SECONDS [TARGET...]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$1 seconds=$2
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_container fuzz_grid_decode fuzz_pm_decode fuzz_pt_decode fuzz_stream_decode fuzz_reconstruct fuzz_mesh_read fuzz_tet_read fuzz_grid_read)
findings=$here/findings
mkdir -p "$findings"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for t in "${targets[@]}"; do
  mkdir -p "$scratch/$t"
  echo "fuzz: $t for $seconds s"
  if ! "$build/fuzz/$t" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
      -artifact_prefix="$findings/$t-" -print_final_stats=1 \
      "$scratch/$t" "$here/../conformance/vectors/valid" "$here/../conformance/vectors/invalid" \
      "$here/../conformance/vectors/coded_valid" "$here/../conformance/vectors/coded_invalid" \
      "$here/../conformance/vectors/tiled_valid" "$here/../conformance/vectors/tiled_invalid" \
      "$here/../conformance/vectors/pt_valid" "$here/../conformance/vectors/pt_invalid" \
      "$here/../conformance/vectors/quadtree" "$here/../conformance/vectors/reconstruct" \
      "$here/../conformance/vectors/reconstruct3" \
      "$here/corpus" "$here/corpus_mesh" "$here/corpus_pt" "$here/corpus_tet" "$here/corpus_grid" "$here/corpus_stream" >"$scratch/$t.log" 2>&1; then
    echo "fuzz: $t FOUND A PROBLEM; input saved under fuzz/findings/"
    tail -40 "$scratch/$t.log"
    status=1
  else
    grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$scratch/$t.log" | sed "s/^/fuzz: $t /"
  fi
done
exit $status
