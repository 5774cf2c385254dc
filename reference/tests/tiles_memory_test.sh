#!/usr/bin/env bash
# Issue 24: a grid larger than the memory allowed is encoded out of core and
# decoded by region under a limit set by ulimit -v, on real data: the bonsai
# CT scan (../shared/data/volume) mirrored four times along z, 256x256x1024
# uint8 (64 MiB). The limit is what a tiny encode needs plus half the grid's
# raw size (the out-of-core encode needs about 18 MiB above a tiny one: a row
# of tiles, the tiles in flight and the allocator's slack; tile_bench measures
# the share on large grids); the in-memory encode and the canonical whole decode must fail under
# it (the limit bites), the out-of-core encode, the region decode and the
# whole decodes to raw and NRRD (written a row of tiles at a time) must not,
# and the out-of-core stream must equal the in-memory one.
set -uo pipefail
mrsv=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "tiles_memory_test: $*" >&2; exit 1; }

zstd -dqf "$data/volume/ct_bonsai_256x256x256_uint8.raw.zst" -o "$work/b.raw" || fail "cannot read the bonsai scan"
# Mirrored copies along z: slices 0..255, 255..0, 0..255, 255..0.
for ((z = 255; z >= 0; z--)); do tail -c +$((z * 65536 + 1)) "$work/b.raw" | head -c 65536; done >"$work/r.raw"
cat "$work/b.raw" "$work/r.raw" "$work/b.raw" "$work/r.raw" >"$work/big.raw"
rm "$work/r.raw"
head -c $((64 * 64 * 128)) "$work/b.raw" >"$work/tiny.raw"
raw_kb=$(( $(stat -c %s "$work/big.raw") / 1024 ))
enc=(encode --quiet --type uint8 --tile 64 --step 8 --threads 2)

# The smallest limit (KB of virtual memory) under which a tiny encode runs:
# two tiles, so that it starts the second thread (its stack and malloc arena
# are address space) as the large encode does.
runs_under() { (ulimit -v "$1"; "$mrsv" "${enc[@]}" --dims 64,64,128 --out-of-core "$work/tiny.raw" "$work/t.mrsv") 2>/dev/null; }
lo=16384 hi=8388608
runs_under $hi || fail "even $hi KB is not enough for a tiny encode"
while ((hi - lo > 2048)); do mid=$(((lo + hi) / 2)); if runs_under $mid; then hi=$mid; else lo=$mid; fi; done
limit=$((hi + raw_kb / 2))
echo "tiles_memory_test: baseline $hi KB, limit $limit KB for a grid of $raw_kb KB"

(ulimit -v $limit; "$mrsv" "${enc[@]}" --dims 256,256,1024 --out-of-core "$work/big.raw" "$work/ooc.mrsv") ||
  fail "the out-of-core encode failed under the limit"
(ulimit -v $limit; "$mrsv" "${enc[@]}" --dims 256,256,1024 "$work/big.raw" "$work/mem.mrsv") 2>"$work/err" &&
  fail "the in-memory encode ran under the limit: the limit does not bite"
grep -q "out of memory" "$work/err" || fail "the in-memory encode did not say it ran out of memory: $(cat "$work/err")"
[ ! -e "$work/mem.mrsv" ] || fail "a failed encode left an output file"
"$mrsv" "${enc[@]}" --dims 256,256,1024 "$work/big.raw" "$work/mem.mrsv" || fail "the in-memory encode failed"
cmp -s "$work/ooc.mrsv" "$work/mem.mrsv" || fail "the out-of-core stream differs from the in-memory one"

(ulimit -v $limit; "$mrsv" decode --quiet --region 100,50,300,164,178,428 "$work/ooc.mrsv" "$work/region.raw") ||
  fail "the region decode failed under the limit"
# A whole decode to the canonical output gathers the grid in memory: the
# limit bites. To raw and NRRD, the grid is written a row of tiles at a time
# (DecodeOptions::tile_rows): they run under the limit, with the same samples.
(ulimit -v $limit; "$mrsv" decode --quiet --canonical "$work/ooc.mrsv" "$work/whole.canon") 2>/dev/null &&
  fail "the whole decode to the canonical output ran under the limit: the limit does not bite"
"$mrsv" decode --quiet --canonical "$work/ooc.mrsv" "$work/whole.canon" || fail "the canonical whole decode failed"
(ulimit -v $limit; "$mrsv" decode --quiet "$work/ooc.mrsv" "$work/whole.raw") ||
  fail "the whole decode to raw, a row of tiles at a time, failed under the limit"
(ulimit -v $limit; "$mrsv" decode --quiet "$work/ooc.mrsv" "$work/whole.nrrd") ||
  fail "the whole decode to NRRD, a row of tiles at a time, failed under the limit"
tail -c 67108864 "$work/whole.canon" | cmp -s - "$work/whole.raw" || fail "the decodes to raw and canonical differ"
tail -c 67108864 "$work/whole.nrrd" | cmp -s - "$work/whole.raw" || fail "the decodes to raw and NRRD differ"
# The region equals the same box of the whole decode.
for ((z = 300; z < 428; z += 37)); do
  for ((y = 50; y < 178; y += 41)); do
    a=$(tail -c +$(( (z * 65536 + y * 256 + 100) + 1 )) "$work/whole.raw" | head -c 64 | od -An -tx1 | tr -d ' \n')
    b=$(tail -c +$(( ((z - 300) * 128 * 64 + (y - 50) * 64) + 1 )) "$work/region.raw" | head -c 64 | od -An -tx1 | tr -d ' \n')
    [ "$a" = "$b" ] || fail "region row y=$y z=$z differs from the whole decode"
  done
done
echo "tiles_memory_test: passed"
