#!/usr/bin/env bash
# mrsv-mpi (issue 24): streams written by 2 and 3 MPI ranks with MPI-IO are
# byte-identical to 'mrsv encode --tile' (or 'mrsv encode --precinct
# --out-of-core', decision D92) of the same input and options, and decoding
# by ranks gives the samples of 'mrsv decode'; on real data.
# Usage: mpi_test.sh MRSV MRSV_MPI SHARED_DATA
set -uo pipefail
mrsv=$1 mpi=$2 data=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
run() { mpirun --allow-run-as-root --oversubscribe -np "$1" "$mpi" "${@:2}"; }

zstd -dqf "$data/terrain/mt_st_helens_317x460_int16le.raw.zst" -o "$work/sh.raw"
zstd -dqf "$data"/terrain/srtm3_*_mt_rainier_1201x1201_int16le.raw.zst -o "$work/rainier.raw"
vol=$root/demo/data/ct_head_64x64x32_uint8.raw
# input | options | what | what mrsv encode adds | rank counts (each mpirun
# costs about a second)
cases=(
  "sh.raw|--dims 317,460 --type int16 --tile 64|lossless, partial tiles||2"
  "sh.raw|--dims 317,460 --type int16 --tile 100,77 --max-error 3 --nodata 0 --meta value_units=m|error bound, no-data, meta||2 3"
  "vol|--dims 64,64,32 --type uint8 --tile 32,32,8 --step 4|a CT volume in bricks, a step||2 3"
  "vol|--dims 64,64,32 --type uint8 --tile 32 --step 4|one row of bricks along z||2"
  "rainier.raw|--dims 1201,1201 --type int16 --precinct 128 --nodata -32768 --lossless|precincts: SRTM voids, lossless|--out-of-core|2 3"
  "sh.raw|--dims 317,460 --type int16 --precinct 64 --bits-per-sample 1.5 --threads 2|precincts: a rate|--out-of-core|2"
  "vol|--dims 64,64,32 --type uint8 --precinct 16 --max-error 2 --meta source=ct|precincts: a volume, a bound|--out-of-core|3"
)
for c in "${cases[@]}"; do
  IFS='|' read -r input opts what single nps <<<"$c"
  [ "$input" = vol ] && input=$vol || input=$work/$input
  # shellcheck disable=SC2086
  "$mrsv" encode --quiet $opts $single "$input" "$work/one.mrsv" || { bad "$what: mrsv encode failed"; continue; }
  "$mrsv" decode --quiet "$work/one.mrsv" "$work/one.raw"
  for np in $nps; do
    # shellcheck disable=SC2086
    if ! run $np encode $opts "$input" "$work/ranks.mrsv" 2>"$work/err"; then bad "$what: $np ranks: $(cat "$work/err")"; continue; fi
    cmp -s "$work/one.mrsv" "$work/ranks.mrsv" && passed=$((passed + 1)) || bad "$what: the stream of $np ranks differs"
    run $np decode "$work/ranks.mrsv" "$work/ranks.raw" 2>/dev/null || { bad "$what: decode by $np ranks failed"; continue; }
    cmp -s "$work/one.raw" "$work/ranks.raw" && passed=$((passed + 1)) || bad "$what: decoding by $np ranks differs"
  done
done
# Errors: one line from one rank, a non-zero status, no output left.
run 2 encode --dims 317,460 --type int16 --tile 64 "$work/missing.raw" "$work/x.mrsv" 2>"$work/err"
# (mpirun adds its own report of the exit status; ours is one line.)
[ $? -eq 3 ] && [ "$(grep -c '^mrsv-mpi:' "$work/err")" -eq 1 ] && [ ! -e "$work/x.mrsv" ] && passed=$((passed + 1)) ||
  bad "a missing input: $(cat "$work/err")"
run 2 decode "$root/conformance/vectors/tiled_invalid/index_length_disagrees.mrsv" "$work/x.raw" 2>"$work/err"
[ $? -eq 1 ] && [ "$(grep -c '^mrsv-mpi:.*E208' "$work/err")" -eq 1 ] && [ ! -e "$work/x.raw" ] && passed=$((passed + 1)) ||
  bad "an invalid stream: $(cat "$work/err")"
# Scratch files of the precinct team: none left behind.
leftover=$(find "$work" -name '.mrsv-mpi-scratch-*' | wc -l)
[ "$leftover" -eq 0 ] && passed=$((passed + 1)) || bad "$leftover scratch files left"
# A precinct encode that fails (NaN samples): one line, no output, no scratch.
/usr/bin/python3 -c "import sys; sys.stdout.buffer.write(b'\x00\x00\xc0\x7f' * 4096)" >"$work/nan.raw"
run 2 encode --dims 64,64 --type float32 --precinct 16 --step 1 "$work/nan.raw" "$work/x.mrsv" 2>"$work/err"
[ $? -eq 1 ] && [ "$(grep -c '^mrsv-mpi:.*NaN' "$work/err")" -eq 1 ] && [ ! -e "$work/x.mrsv" ] &&
  [ "$(find "$work" -name '.mrsv-mpi-*' | wc -l)" -eq 0 ] && passed=$((passed + 1)) ||
  bad "NaN samples in precincts: $(cat "$work/err")"
echo "mpi: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
