#!/usr/bin/env bash
# README command 1: the MRSV pipeline on the bundled crops of real data
# (demo/data, cut from ../shared/data), ending with a short report.
# Everything it writes goes to demo/out/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/tools/setup.sh"
mrsv=$root/build/mrsv
data=$root/demo/data
out=$root/demo/out
rm -rf "$out"
mkdir -p "$out"

# PSNR (peak = max - min of the valid input) and max error of decoded vs input.
psnr() {  # psnr INPUT DECODED TYPE [NODATA]
  python3 - "$@" <<'PY'
import array, math, sys
src, dec, t = sys.argv[1:4]
nodata = int(sys.argv[4]) if len(sys.argv) > 4 else None
code = {"int16": "h", "uint8": "B", "uint16": "H"}[t]
a, b = array.array(code), array.array(code)
a.frombytes(open(src, "rb").read()); b.frombytes(open(dec, "rb").read())
pairs = [(x, y) for x, y in zip(a, b) if x != nodata]
lo, hi = min(x for x, _ in pairs), max(x for x, _ in pairs)
se = sum((x - y) ** 2 for x, y in pairs); worst = max(abs(x - y) for x, y in pairs)
voids = all(y == nodata for x, y in zip(a, b) if x == nodata) if nodata is not None else True
p = "inf" if se == 0 else "%.2f" % (10 * math.log10((hi - lo) ** 2 * len(pairs) / se))
print("PSNR %s dB, max error %d%s" % (p, worst, ", voids exact" if nodata is not None and voids else ""))
PY
}

# name | file | dims | type | options
inputs=(
  "mt_st_helens|mt_st_helens_128x128_int16le.raw|128,128|int16|--meta value_units=m --meta spacing=30,30 --meta crs=EPSG:26910"
  "mt_fuji_summit|mt_fuji_summit_128x128_int16le.raw|128,128|int16|--nodata -32768 --meta value_units=m --meta crs=EPSG:4326"
  "ct_head|ct_head_64x64x32_uint8.raw|64,64,32|uint8|--meta spacing=1,1,2"
  "ct_headsq|ct_headsq_16x16x8_uint16le.raw|16,16,8|uint16|--meta spacing=3.2,3.2,1.5"
)

echo
echo "== 1. lossless coding (the smaller of: wavelet bands + exact residual, predicted samples) =="
report=()
for entry in "${inputs[@]}"; do
  IFS='|' read -r name file dims type extra <<<"$entry"
  # shellcheck disable=SC2086  # extra holds several options
  "$mrsv" encode --quiet --lossless --dims "$dims" --type "$type" $extra \
    --meta "provenance=demo/data/$file (see demo/data/SOURCES.md)" "$data/$file" "$out/$name.mrsv"
  "$mrsv" decode --quiet "$out/$name.mrsv" "$out/$name.raw"
  if cmp -s "$data/$file" "$out/$name.raw"; then same=exact; else same=DIFFERENT; fi
  [ "$same" = exact ] || { echo "  $name: lossless round trip differs" >&2; exit 1; }
  in_bytes=$(stat -c %s "$data/$file")
  mrsv_bytes=$(stat -c %s "$out/$name.mrsv")
  zstd_bytes=$(zstd -19 -q -c "$data/$file" | wc -c)
  xz_bytes=$(xz -9 -c "$data/$file" | wc -c)
  if [ "$type" = uint8 ]; then sample_bytes=1; else sample_bytes=2; fi
  bits=$(awk -v b="$mrsv_bytes" -v n="$in_bytes" -v s="$sample_bytes" 'BEGIN { printf "%.2f", 8 * b * s / n }')
  report+=("$(printf '%-15s %-9s %-6s %8s %8s %6s %8s %8s  %s' "$name" "${dims//,/x}" "$type" \
    "$in_bytes" "$mrsv_bytes" "$bits" "$zstd_bytes" "$xz_bytes" "$same")")
  echo "  demo/data/$file -> demo/out/$name.mrsv: $same"
done

echo
echo "== 2. check every file (rules down to the coefficients; recorded error figures) =="
"$mrsv" check "$out"/*.mrsv | sed "s|$out/|  demo/out/|"

echo
echo "== 3. lossy: a rate, a PSNR, an error bound, the keep oracle, a region of interest =="
helens=$data/mt_st_helens_128x128_int16le.raw
fuji=$data/mt_fuji_summit_128x128_int16le.raw
for opts in "--bits-per-sample 1" "--psnr 55" "--keep 0.05"; do
  "$mrsv" encode --quiet --dims 128,128 --type int16 $opts "$helens" "$out/lossy.mrsv"
  "$mrsv" decode --quiet "$out/lossy.mrsv" "$out/lossy.raw"
  printf '  st helens %-22s %6d bytes: %s\n' "$opts" "$(stat -c %s "$out/lossy.mrsv")" \
    "$(psnr "$helens" "$out/lossy.raw" int16)"
done
"$mrsv" encode --quiet --dims 128,128 --type int16 --nodata -32768 --max-error 4 "$fuji" "$out/bound.mrsv"
"$mrsv" decode --quiet "$out/bound.mrsv" "$out/bound.raw"
printf '  fuji      %-22s %6d bytes: %s\n' "--max-error 4" "$(stat -c %s "$out/bound.mrsv")" \
  "$(psnr "$fuji" "$out/bound.raw" int16 -32768)"
"$mrsv" encode --quiet --dims 128,128 --type int16 --bits-per-sample 0.5 \
  --roi ellipsoid:64,64,20,20 --roi-falloff 6 "$helens" "$out/roi.mrsv"
"$mrsv" decode --quiet "$out/roi.mrsv" "$out/roi.raw"
python3 - "$helens" "$out/roi.raw" <<'PY'
import array, math, sys
a, b = array.array("h"), array.array("h")
a.frombytes(open(sys.argv[1], "rb").read()); b.frombytes(open(sys.argv[2], "rb").read())
r = max(a) - min(a)
def psnr(sel):
    se = [(a[i] - b[i]) ** 2 for i in range(len(a)) if sel(i % 128, i // 128)]
    m = sum(se) / len(se)
    return "inf" if m == 0 else "%.1f" % (10 * math.log10(r * r / m))
inside = lambda x, y: (x - 64) ** 2 + (y - 64) ** 2 <= 400
print("  st helens --bits-per-sample 0.5 --roi ellipsoid:64,64,20,20: PSNR %s dB inside the region, %s dB outside"
      % (psnr(inside), psnr(lambda x, y: not inside(x, y))))
PY

echo
echo "== 4. info: the chunk table of a wavelet-coded file =="
"$mrsv" info "$out/mt_st_helens.mrsv" | sed "s|$out/|demo/out/|; s/^/  /"

echo
echo "== 5. progressive: every prefix of complete chunks decodes, coarse to fine =="
"$mrsv" encode --quiet --dims 128,128 --type int16 --progressive --bits-per-sample 2 "$helens" "$out/prog.mrsv"
"$mrsv" info --json "$out/prog.mrsv" >"$out/prog.json"
python3 - "$out/prog.json" <<'PY' >"$out/cuts.txt"
import json, sys
chunks = json.load(open(sys.argv[1]))["chunks"]
bands = [c for c in chunks if c["type"] == "GBND"]
for i in (0, 3, 6, len(bands) - 1):
    c = bands[i]
    print(i + 1, len(bands), c["offset"] + 12 + c["length"])
PY
while read -r n total bytes; do
  "$mrsv" decode --quiet --bytes "$bytes" "$out/prog.mrsv" "$out/prefix.raw"
  printf '  first %6d bytes (%2d of %d bands): %s\n' "$bytes" "$n" "$total" "$(psnr "$helens" "$out/prefix.raw" int16)"
done <"$out/cuts.txt"
"$mrsv" decode --quiet --levels 2 "$out/prog.mrsv" "$out/quarter.nrrd"
echo "  --levels 2: a reduced-resolution grid: $(grep -a -m1 "^sizes" "$out/quarter.nrrd")"

echo
echo "== 6. damage is reported, never decoded =="
cp "$out/mt_fuji_summit.mrsv" "$out/damaged.mrsv"
printf '\x00' | dd of="$out/damaged.mrsv" bs=1 seek=3000 conv=notrunc status=none
if "$mrsv" check "$out/damaged.mrsv" 2>"$out/damaged.txt"; then
  echo "  a damaged file passed the check" >&2
  exit 1
fi
echo "  $(sed "s|$out/|demo/out/|" "$out/damaged.txt")"
if "$mrsv" decode --quiet "$out/damaged.mrsv" "$out/damaged.raw" 2>/dev/null; then exit 1; fi
[ ! -e "$out/damaged.raw" ] && echo "  decode refused it and wrote no output file"

echo
echo "== 7. progressive mesh: one stream, every level from the base mesh to the full cow =="
cow=$data/cow_viewpoint_2903v_5804tri.obj
"$mrsv" encode --bits 14 "$cow" "$out/cow.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s|$data/|demo/data/|; s/^/  /"
for faces in 58 580 5804; do
  "$mrsv" decode --quiet --faces "$faces" "$out/cow.mrsv" "$out/cow_$faces.ply"
  "$mrsv" compare --json "$cow" "$out/cow_$faces.ply" >"$out/cow_$faces.json"
  python3 - "$faces" "$out/cow_$faces.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[2]))
print("  --faces %-5s -> %5d faces: Hausdorff %.5f, RMS %.6f of the bounding-box diagonal"
      % (sys.argv[1], d["b"]["triangles"], d["hausdorff_relative"], d["rms_relative"]))
PY
done
"$mrsv" check "$out/cow.mrsv" | sed "s|$out/|  demo/out/|"

echo
echo "== 8. progressive tetrahedralization (paper 6, 7.2): a 32^3 CT crop as 178,746 tets, one stream =="
"$mrsv" tetrahedralize --quiet --dims 64,64,32 --type uint8 --crop 16,16,0,32,32,32 \
  "$data/ct_head_64x64x32_uint8.raw" "$out/ct_tets.vtu" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
"$mrsv" encode "$out/ct_tets.vtu" "$out/ct_tets.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
for fraction in 0.5 0.1 0.05; do
  "$mrsv" decode --quiet --fraction "$fraction" "$out/ct_tets.mrsv" "$out/ct_tets_$fraction.vtu"
  "$mrsv" compare --json --samples 200000 "$out/ct_tets.vtu" "$out/ct_tets_$fraction.vtu" >"$out/ct_tets_$fraction.json"
  python3 - "$fraction" "$out/ct_tets_$fraction.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[2]))
print("  --fraction %-4s -> %6d tets: field PSNR %.2f dB, boundary Hausdorff %.4f of the diagonal, %s"
      % (sys.argv[1], d["b"]["tets"], d["field"]["psnr_db"], d["boundary"]["hausdorff_relative"],
         "valid" if d["quality_b"]["valid"] else "INVALID"))
PY
done
"$mrsv" check "$out/ct_tets.mrsv" | sed "s|$out/|  demo/out/|"
echo "  (open demo/out/ct_tets_*.vtu in ParaView or with VTK/meshio: the field is 'value')"

echo
echo "== 9. mesh reconstruction (paper 4, 5): adaptive TINs of a terrain stream, the same in any implementation =="
"$mrsv" encode --quiet --dims 128,128 --type int16 --progressive --meta spacing=30,-30 "$helens" "$out/helens_prog.mrsv"
for e in 2 10; do
  for method in insertion quadtree; do
    "$mrsv" mesh --max-error "$e" --method "$method" "$out/helens_prog.mrsv" "$out/helens_${method}_$e.obj" 2>&1 |
      sed "s|$out/|demo/out/|; s/^mrsv mesh: /  --max-error $e m: /"
  done
done
echo "  with the vertex-removal pass (spec 8.8, 9.7): the same bound, fewer triangles:"
for method in insertion quadtree; do
  "$mrsv" mesh --max-error 10 --method "$method" --remove-vertices "$out/helens_prog.mrsv" \
    "$out/helens_${method}_10_removed.obj" 2>&1 | tail -1 | sed "s|$out/|demo/out/|; s/^mrsv mesh: /  --max-error 10 m: /"
done
"$mrsv" mesh --max-error 2 --progressive "$out/helens_prog.mrsv" "$out/helens_progressive_2.obj" 2>&1 |
  sed "s|$out/|demo/out/|; s/^mrsv mesh: /  /"
"$mrsv" mesh --quiet --max-error 2 --canonical "$out/helens_prog.mrsv" "$out/helens_insertion_2.canonical"
echo "  SHA-256 of the canonical mesh (spec 8.2), what any conforming reconstructor must give:"
echo "  $(sha256sum "$out/helens_insertion_2.canonical" | cut -c1-64)"
echo "  3-D: the 32^3 CT crop as a progressive stream, tets by Delaunay insertion (paper 5.2):"
python3 - "$data/ct_head_64x64x32_uint8.raw" "$out/ct32.raw" <<'PY'
import sys
src = open(sys.argv[1], "rb").read()
out = bytearray()
for z in range(32):
    for y in range(16, 48):
        row = (z * 64 + y) * 64
        out += src[row + 16:row + 48]
open(sys.argv[2], "wb").write(out)
PY
"$mrsv" encode --quiet --dims 32,32,32 --type uint8 --progressive "$out/ct32.raw" "$out/ct32.mrsv"
for e in 20 10 5; do
  "$mrsv" mesh --max-error "$e" --progressive "$out/ct32.mrsv" "$out/ct32_insertion_$e.vtu" 2>&1 | tail -1 |
    sed "s|$out/|demo/out/|; s/^mrsv mesh: /    --max-error $e: /"
done
echo "  (demo/out/ct32_insertion_*.vtu: open in ParaView or with VTK/meshio; the samples are 'value')"

echo
echo "== 10. where users work: a GeoTIFF in and out (GDAL), the GDAL driver, Python =="
tif=$root/../shared/data/terrain/big_tujunga_srtm1_30m_utm11.tif.zst
if [ -f "$tif" ] && [ -x "$(command -v gdalinfo)" ] && [ -d "$root/build/gdalplugins" ]; then
  zstd -dqf "$tif" -o "$out/tujunga.tif"
  "$mrsv" encode --max-error 1 --progressive "$out/tujunga.tif" "$out/tujunga.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
  "$mrsv" info "$out/tujunga.mrsv" | grep -E "crs|origin|spacing" | sed 's/^/  /'
  "$mrsv" decode --quiet --levels 2 "$out/tujunga.mrsv" "$out/tujunga_levels2.tif"
  echo "  demo/out/tujunga_levels2.tif (gdalinfo): $(gdalinfo "$out/tujunga_levels2.tif" | grep -E "^Size is|^Pixel Size" | tr '\n' ' ')"
  echo "  the driver plugin: $(GDAL_DRIVER_PATH="$root/build/gdalplugins" gdalinfo "$out/tujunga.mrsv" | grep -E "^Driver|Overviews" | sed 's/^ *//' | tr '\n' ' ')"
  GDAL_DRIVER_PATH="$root/build/gdalplugins" gdal_translate -q -of MRSV -co MAX_ERROR=1 -co PROGRESSIVE=YES "$out/tujunga.tif" "$out/tujunga_gdal.mrsv"
  echo "  gdal_translate -of MRSV -co MAX_ERROR=1 -co PROGRESSIVE=YES: $(cmp -s "$out/tujunga.mrsv" "$out/tujunga_gdal.mrsv" && echo "the same bytes as mrsv encode's" || echo "DIFFERENT bytes from mrsv encode's")"
  PYTHONPATH=$root/build/python /usr/bin/python3 - "$out/tujunga.mrsv" <<'PY' | sed 's/^/  /'
import sys, mrsv
a, info = mrsv.decode(sys.argv[1], levels=1)
print("python: mrsv.decode(levels=1) -> numpy %s %s, crs %s, error bound %g"
      % (a.dtype, a.shape, info["metadata"].get("crs"), info["error_bound"]))
PY
else
  echo "  (skipped: needs ../shared/data, gdal-bin and a build with GDAL; tools/setup.sh installs them)"
fi

echo
echo "== 11. tiles (spec 11) and precincts (5.7.6): a terrain cut in 256 x 256, a window decoded from what it meets =="
rainier=$root/../shared/data/terrain/srtm3_N46W122_mt_rainier_1201x1201_int16le.raw.zst
if [ -f "$rainier" ]; then
  zstd -dqf "$rainier" -o "$out/rainier.raw"
  "$mrsv" encode --dims 1201,1201 --type int16 --nodata -32768 --tile 256 --max-error 1 --bound-route residual \
    "$out/rainier.raw" "$out/rainier_tiled.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
  "$mrsv" info "$out/rainier_tiled.mrsv" | grep "^content" | sed 's/^/  /'
  "$mrsv" decode --region 400,300,656,556 "$out/rainier_tiled.mrsv" "$out/rainier_window.nrrd" 2>&1 |
    sed "s|$out/|demo/out/|; s/^/  /"
  "$mrsv" encode --dims 1201,1201 --type int16 --nodata -32768 --tile 256 --max-error 1 --bound-route residual \
    --out-of-core --quiet \
    "$out/rainier.raw" "$out/rainier_ooc.mrsv"
  cmp -s "$out/rainier_tiled.mrsv" "$out/rainier_ooc.mrsv" &&
    echo "  out of core (a row of tiles in memory at a time): the same bytes"
  echo "  precincts (spec 5.7.6): one transform, every band in blocks of 256 x 256 samples; at 1 bit/sample"
  for cut in "" "--tile 256" "--precinct 256"; do
    "$mrsv" encode --dims 1201,1201 --type int16 --nodata -32768 --bits-per-sample 1 $cut \
      "$out/rainier.raw" "$out/rainier_cut.mrsv" 2>&1 | sed -n 's/.*bits\/sample, \(PSNR [0-9.]* dB\).*/\1/p' |
      sed "s/^/    ${cut:-whole grid}: /"
  done
  "$mrsv" decode --region 400,300,656,556 "$out/rainier_cut.mrsv" "$out/rainier_pwindow.nrrd" 2>&1 |
    sed "s|$out/|demo/out/|; s/^/  /"
  echo "  precincts out of core (D91): a strip of precincts in memory at a time, the analysis level by level"
  "$mrsv" encode --dims 1201,1201 --type int16 --nodata -32768 --precinct 256 --max-error 1 --out-of-core \
    "$out/rainier.raw" "$out/rainier_pooc.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
  mpi=$(dirname "$mrsv")/mrsv-mpi
  if [ -x "$mpi" ] && command -v mpirun >/dev/null; then
    echo "  the same by 2 MPI ranks as a team (D92): pieces and boxes from a shared queue, blocks written by MPI-IO"
    mpirun --allow-run-as-root --oversubscribe -np 2 "$mpi" encode --dims 1201,1201 --type int16 --nodata -32768 \
      --precinct 256 --max-error 1 "$out/rainier.raw" "$out/rainier_pmpi.mrsv" 2>&1 | sed "s|$out/|demo/out/|; s/^/  /"
    cmp -s "$out/rainier_pooc.mrsv" "$out/rainier_pmpi.mrsv" && echo "  the same bytes as one process"
  fi
else
  echo "  (skipped: needs ../shared/data)"
fi

{
  echo
  echo "== report: lossless sizes (bytes) =="
  printf '%-15s %-9s %-6s %8s %8s %6s %8s %8s  %s\n' "data set" "size" "type" "raw" ".mrsv" "bits" "zstd-19" "xz -9" "round trip"
  printf '%s\n' "${report[@]}"
  echo
  echo "Format $("$mrsv" --version | sed 's/.*format //'); tools/bench/ compares with zfp, OpenJPEG and JPEG XL."
} | tee "$out/report.txt"
