#!/usr/bin/env bash
# Issue 24, decision D91: a terrain in precincts is encoded out of core under a
# memory limit set by ulimit -v, on real data: the three SRTM tiles of
# ../shared/data/terrain laid out 8 x 8 with mirroring (each copy reflected so
# that neighbours meet along equal edges, voids set to their tile's median),
# 9608 x 9608 int16 (176 MiB). The limit is what a tiny out-of-core encode on
# two threads needs plus a quarter of the grid's raw size (the issue's goal:
# peak memory below 25 % of the raw size); the in-memory encode must fail
# under it (the limit bites), the out-of-core lossless encode must not, its
# stream must decode to the grid exactly, and a region of it must decode
# under the limit to the grid's samples. (The unit tests check that the
# thread count does not change the bytes.)
set -uo pipefail
mrsv=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "precinct_memory_test: $*" >&2; exit 1; }

for t in everest rainier fuji; do
  zstd -dqf "$data"/terrain/srtm3_*_mt_${t}_1201x1201_int16le.raw.zst -o "$work/$t.raw" ||
    fail "cannot read the $t tile"
done
/usr/bin/python3 - "$work" <<'EOF' || fail "cannot build the mosaic (numpy)"
import sys
import numpy as np
work = sys.argv[1]
tiles = []
for name in ("everest", "rainier", "fuji"):
    a = np.fromfile(f"{work}/{name}.raw", dtype="<i2").reshape(1201, 1201).copy()
    voids = a == -32768
    if voids.any():
        a[voids] = int(np.median(a[~voids]))
    tiles.append(a)
rows = []
for j in range(8):
    row = []
    for i in range(8):
        t = tiles[(i + 2 * j) % 3]
        t = t[:, ::-1] if i % 2 else t
        t = t[::-1, :] if j % 2 else t
        row.append(t)
    rows.append(np.hstack(row))
np.vstack(rows).astype("<i2").tofile(f"{work}/big.raw")
EOF
head -c $((512 * 512 * 2)) "$work/big.raw" >"$work/tiny.raw"
raw_kb=$(( $(stat -c %s "$work/big.raw") / 1024 ))
enc=(encode --quiet --type int16 --precinct 256 --lossless)

# The smallest limit (KB of virtual memory) under which a tiny out-of-core
# encode runs on two threads (their stacks and malloc arenas are address space).
runs_under() { (ulimit -v "$1"; "$mrsv" "${enc[@]}" --threads 2 --dims 512,512 --out-of-core "$work/tiny.raw" "$work/t.mrsv") 2>/dev/null; }
lo=16384 hi=8388608
runs_under $hi || fail "even $hi KB is not enough for a tiny encode"
while ((hi - lo > 2048)); do mid=$(((lo + hi) / 2)); if runs_under $mid; then hi=$mid; else lo=$mid; fi; done
limit=$((hi + raw_kb / 4))
echo "precinct_memory_test: baseline $hi KB, limit $limit KB for a grid of $raw_kb KB"

(ulimit -v $limit; "$mrsv" "${enc[@]}" --threads 2 --dims 9608,9608 --out-of-core "$work/big.raw" "$work/ooc.mrsv") ||
  fail "the out-of-core encode failed under the limit"
(ulimit -v $limit; "$mrsv" "${enc[@]}" --threads 2 --dims 9608,9608 "$work/big.raw" "$work/mem.mrsv") 2>"$work/err" &&
  fail "the in-memory encode ran under the limit: the limit does not bite"
grep -q "out of memory" "$work/err" || fail "the in-memory encode did not say it ran out of memory: $(cat "$work/err")"
[ ! -e "$work/mem.mrsv" ] || fail "a failed encode left an output file"
"$mrsv" decode --quiet "$work/ooc.mrsv" "$work/back.raw" || fail "the out-of-core stream does not decode"
cmp -s "$work/back.raw" "$work/big.raw" || fail "the lossless out-of-core stream does not give the grid back"
# A region decodes under the limit too, from the blocks it reaches (5.7.6):
# rows 5000 to 5299 of columns 3000 to 3999, the input's own samples.
(ulimit -v $limit; "$mrsv" decode --quiet --region 3000,5000,4000,5300 "$work/ooc.mrsv" "$work/region.raw") ||
  fail "the region decode failed under the limit"
for ((y = 0; y < 300; y += 37)); do
  cmp -s <(tail -c +$(( ((5000 + y) * 9608 + 3000) * 2 + 1 )) "$work/big.raw" | head -c 2000) \
         <(tail -c +$(( y * 2000 + 1 )) "$work/region.raw" | head -c 2000) ||
    fail "region row $y differs from the grid"
done
echo "precinct_memory_test: passed"
