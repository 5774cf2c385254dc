#!/usr/bin/env bash
# The paper's section 7 experiments in one command: 7.1 (surface approximation on a
# 256 x 256 crop of Mt St Helens: quadtree, insertion, PM with the paper's and the
# quadric cost; Metro-style errors; Figure 5 error pictures) and 7.2 (volume
# approximation on the 32^3 CT head crop: PT with and without the intersection test,
# 3-D insertion; PSNR and reconstruction times, Figure 3). Writes report.md,
# results.json and the PNGs into OUT_DIR (default build/experiments/).
#
#   tools/experiments/section7.sh [--quick] [--keep-work] [OUT_DIR]
#
# Builds build/mrsv when it is missing or stale (Release, at most 2 jobs). About 3 to 5
# minutes on 2 cores; --quick (small crops, two levels) takes seconds and is what the
# ctest picture test runs. Needs ../shared/data, zstd, and /usr/bin/python3 with numpy and
# matplotlib (Debian: python3-numpy python3-matplotlib).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
die() { echo "section7: error: $*" >&2; exit 1; }

quick=()
keep=()
out=
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=(--quick) ;;
    --keep-work) keep=(--keep-work) ;;
    -h|--help) sed -n '2,14p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1" ;;
    *) [ -z "$out" ] || die "one OUT_DIR only"; out=$1 ;;
  esac
  shift
done
out=${out:-$root/build/experiments}
data=${MRSV_SHARED_DATA:-$root/../shared/data}
mrsv=${MRSV:-$root/build/mrsv}

python=/usr/bin/python3
[ -x "$python" ] || python=$(command -v python3 || true)
[ -n "$python" ] || die "python3 not found"
"$python" -c 'import numpy, matplotlib' 2>/dev/null ||
  die "$python lacks numpy or matplotlib (Debian: apt-get install python3-numpy python3-matplotlib)"
command -v zstd >/dev/null || die "zstd not found (Debian: apt-get install zstd)"
[ -d "$data/terrain" ] && [ -d "$data/volume" ] || die "no data at $data (set MRSV_SHARED_DATA)"

start=$(date +%s)
if [ -z "${MRSV:-}" ]; then
  echo "section7: building mrsv (Release) in build/"
  if [ ! -f "$root/build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null || die "cmake configure failed"
  fi
  log=$(mktemp)
  if ! cmake --build "$root/build" -j 2 --target mrsv >"$log" 2>&1; then
    grep -m 5 -E "error" "$log" >&2 || true
    rm -f "$log"
    die "building mrsv failed"
  fi
  rm -f "$log"
fi
[ -x "$mrsv" ] || die "no mrsv at $mrsv"

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [ -n "$(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null)" ]; then commit="$commit+changes"; fi
echo "section7: running into $out"
"$python" "$root/tools/experiments/section7.py" --mrsv "$mrsv" --data "$data" --out "$out" \
  --commit "$commit" "${quick[@]}" "${keep[@]}" || exit 1
echo "section7: done in $(( $(date +%s) - start )) s: $out/report.md and $(ls "$out"/*.png | wc -l) PNGs"
