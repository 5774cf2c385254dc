#!/usr/bin/env bash
# Behaviour of the mrsv command line: help, exit statuses, one-line errors,
# no half-written outputs, inputs never overwritten.
# Usage: cli_test.sh PATH/TO/mrsv
set -u
mrsv=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
vectors=$root/conformance/vectors
crop=$root/demo/data/mt_st_helens_128x128_int16le.raw
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0

ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
# expect STATUS CMD... : runs CMD, compares the exit status
expect() {
  local want=$1; shift
  "$@" >"$work/stdout" 2>"$work/stderr"
  local got=$?
  if [ "$got" -eq "$want" ]; then ok; else bad "exit $got (want $want): $*: $(head -c 300 "$work/stderr")"; fi
}
stderr_has() { if grep -q -- "$1" "$work/stderr"; then ok; else bad "stderr lacks '$1': $(head -c 300 "$work/stderr")"; fi; }
stdout_has() { if grep -q -- "$1" "$work/stdout"; then ok; else bad "stdout lacks '$1'"; fi; }
one_line_stderr() { if [ "$(wc -l <"$work/stderr")" -eq 1 ]; then ok; else bad "stderr is not one line: $(cat "$work/stderr")"; fi; }

# Help everywhere.
expect 0 "$mrsv" --help; stdout_has "Commands:"
expect 0 "$mrsv" --version; stdout_has "format 0.1"
for cmd in encode decode info check; do
  expect 0 "$mrsv" "$cmd" --help; stdout_has "Usage: mrsv $cmd"
  expect 0 "$mrsv" help "$cmd"; stdout_has "Usage: mrsv $cmd"
done
expect 2 "$mrsv"
expect 2 "$mrsv" frobnicate; stderr_has "unknown command"
expect 2 "$mrsv" encode --no-such-option a b; stderr_has "unknown option"; one_line_stderr

# Encode, decode, compare: the stored coding is lossless.
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --meta spacing=30,30 --meta value_units=m "$crop" "$work/a.mrsv"
expect 0 "$mrsv" decode --quiet "$work/a.mrsv" "$work/a.raw"
if cmp -s "$crop" "$work/a.raw"; then ok; else bad "decoded samples differ from the input"; fi
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --meta spacing=30,30 --meta value_units=m "$crop" "$work/b.mrsv"
if cmp -s "$work/a.mrsv" "$work/b.mrsv"; then ok; else bad "encoder is not deterministic"; fi
expect 0 "$mrsv" decode --quiet --endian big "$work/a.mrsv" "$work/a_be.raw"
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --endian big "$work/a_be.raw" "$work/c.mrsv"
expect 0 "$mrsv" decode --quiet "$work/c.mrsv" "$work/c.raw"
if cmp -s "$crop" "$work/c.raw"; then ok; else bad "big-endian round trip differs"; fi

# Info and check.
expect 0 "$mrsv" info "$work/a.mrsv"; stdout_has "GHDR"; stdout_has "spacing=30,30"; stdout_has "complete"
stdout_has "band (coarse to fine) #0, step "; stdout_has "prediction"
expect 0 "$mrsv" info --json "$work/a.mrsv"
if python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["grid"]["size"]==[128,128,1]' "$work/stdout"; then ok; else bad "info --json is not the expected JSON"; fi
expect 0 "$mrsv" check "$work/a.mrsv" "$vectors/valid/smallest.mrsv"; stdout_has "ok: grid"
expect 1 "$mrsv" check "$vectors/invalid/bad_checksum.mrsv"
stderr_has "bad_checksum.mrsv: offset 568: E113 checksum_mismatch"; one_line_stderr
expect 1 "$mrsv" check "$work/a.mrsv" "$vectors/invalid/trailing_bytes.mrsv"; stderr_has "E118"
expect 1 "$mrsv" info "$vectors/invalid/unknown_critical_chunk.mrsv"; stdout_has "GHDR"; stderr_has "E115"

# Progressive prefix: --bytes cuts inside GRAW, leaving the header only.
expect 1 "$mrsv" decode --quiet --bytes 100 "$work/a.mrsv" "$work/p.raw"; stderr_has "ends before its sample data"
expect 0 "$mrsv" decode --quiet --canonical --bytes 100 "$work/a.mrsv" "$work/p.can"
if head -1 "$work/p.can" | grep -q "mrsv-canonical-grid 1 int16 2 128 128 1 0"; then ok; else bad "prefix canonical output"; fi

# A rate target: levels unless --progressive is dropped and the predictive
# route is better (at 6 bits/sample the lossless stream of the crop fits).
expect 0 "$mrsv" encode --dims 128,128 --type int16 --progressive --bits-per-sample 6 "$crop" "$work/r.mrsv"
stderr_has "levels [1-9]"
expect 0 "$mrsv" encode --dims 128,128 --type int16 --bits-per-sample 6 "$crop" "$work/r.mrsv"
stderr_has "PSNR inf dB, max error 0, levels 0 (predictive route"
expect 2 "$mrsv" encode --dims 128,128 --type int16 --lossless --bound-route predictive --progressive "$crop" "$work/x.mrsv"
stderr_has "not progressive"; one_line_stderr

# Bad input: one line naming the file and the rule; no output left behind.
expect 1 "$mrsv" decode --quiet "$vectors/invalid/truncated_payload.mrsv" "$work/t.raw"
stderr_has "truncated_payload.mrsv: offset 52: E111"; one_line_stderr
if [ ! -e "$work/t.raw" ]; then ok; else bad "decode left an output for an invalid stream"; fi
expect 1 "$mrsv" encode --quiet --dims 100,100 --type int16 "$crop" "$work/x.mrsv"
stderr_has "needs 20000"; one_line_stderr
if [ ! -e "$work/x.mrsv" ]; then ok; else bad "encode left an output for bad input"; fi
expect 2 "$mrsv" encode --dims 128,0 --type int16 "$crop" "$work/x.mrsv"; stderr_has "at least 1"
expect 2 "$mrsv" encode --dims 128,128 --type int12 "$crop" "$work/x.mrsv"; stderr_has "int12"
expect 2 "$mrsv" encode --dims 128,128 --type int16 --nodata 40000 "$crop" "$work/x.mrsv"; stderr_has "out of range"
expect 2 "$mrsv" encode --dims 128,128 --type int16 --meta Bad=1 "$crop" "$work/x.mrsv"; stderr_has "must match"
expect 3 "$mrsv" encode --dims 128,128 --type int16 "$work/missing.raw" "$work/x.mrsv"; stderr_has "missing.raw"
expect 3 "$mrsv" encode --dims 128,128 --type int16 "$crop" "$work/no/dir/x.mrsv"; one_line_stderr
: >"$work/empty.raw"
expect 1 "$mrsv" encode --dims 1 --type uint8 "$work/empty.raw" "$work/x.mrsv"; stderr_has "has 0 bytes"

# Grid files with a header: a small .hgt, .pgm and .nrrd are read; malformed
# ones give one line naming the file, the line, offset or field, and the rule.
printf '\001\007\200\000\021\021\001\002\000\000\377\377\000\001\000\002\000\003' >"$work/N46W122.hgt"
expect 0 "$mrsv" encode --quiet "$work/N46W122.hgt" "$work/h.mrsv"
expect 0 "$mrsv" info "$work/h.mrsv"; stdout_has "nodata -32768"; stdout_has "crs=EPSG:4326"
printf 'P2\n# plain\n3 2\n4095\n0 1 2\n4095 77 3\n' >"$work/p2.pgm"
expect 0 "$mrsv" encode --quiet "$work/p2.pgm" "$work/p2.mrsv"
expect 0 "$mrsv" decode --quiet "$work/p2.mrsv" "$work/p2.nrrd"
expect 0 "$mrsv" encode --quiet "$work/p2.nrrd" "$work/p2b.mrsv"
if cmp -s "$work/p2.mrsv" "$work/p2b.mrsv"; then ok; else bad "PGM and its NRRD copy encode differently"; fi
head -c 17 "$work/N46W122.hgt" >"$work/odd.hgt"
expect 1 "$mrsv" encode --quiet "$work/odd.hgt" "$work/x.mrsv"; stderr_has "odd.hgt: file size 17 bytes is not a square"; one_line_stderr
printf 'P5 2 1 100\n\005\310' >"$work/bad.pgm"
expect 1 "$mrsv" encode --quiet "$work/bad.pgm" "$work/x.mrsv"; stderr_has "bad.pgm: offset 12: sample 200 is above maxval 100"; one_line_stderr
printf 'NRRD0004\ntype: short\ndimension: 2\nsizes: 2 2\nendian: big\nencoding: gzip\n\n12345678' >"$work/gz.nrrd"
expect 1 "$mrsv" encode --quiet "$work/gz.nrrd" "$work/x.mrsv"; stderr_has "gz.nrrd: line 6: field 'encoding' 'gzip' is not supported"; one_line_stderr
printf 'NRRD0004\ntype: short\ndimension: 2\nsizes: 2 2\n\n12345678' >"$work/noend.nrrd"
expect 1 "$mrsv" encode --quiet "$work/noend.nrrd" "$work/x.mrsv"; stderr_has "noend.nrrd: line 5: the header has no 'endian' field"; one_line_stderr
printf 'NRRD0004\ntype: uchar\ndimension: 2\nsizes: 2 2\nspacings: 1 x\n\n1234' >"$work/sp.nrrd"
expect 1 "$mrsv" encode --quiet "$work/sp.nrrd" "$work/x.mrsv"; stderr_has "sp.nrrd: line 5: field 'spacings'"; one_line_stderr
expect 1 "$mrsv" tetrahedralize "$work/sp.nrrd" "$work/x.vtu"; stderr_has "sp.nrrd: line 5"; one_line_stderr
if [ ! -e "$work/x.mrsv" ] && [ ! -e "$work/x.vtu" ]; then ok; else bad "a malformed grid file left an output"; fi

# The input is never overwritten.
cp "$work/a.mrsv" "$work/keep.mrsv"
expect 2 "$mrsv" decode "$work/keep.mrsv" "$work/keep.mrsv"; stderr_has "refusing"
if cmp -s "$work/a.mrsv" "$work/keep.mrsv"; then ok; else bad "decode changed its input"; fi
cp "$crop" "$work/in.raw"
expect 2 "$mrsv" encode --dims 128,128 --type int16 "$work/in.raw" "$work/./in.raw"
if cmp -s "$crop" "$work/in.raw"; then ok; else bad "encode changed its input"; fi

# Progressive meshes (spec 6): encode, check, decode at levels, compare.
cow="$(dirname "$0")/../../../shared/data/surface/cow_viewpoint_2903v_5804tri.obj"
expect 0 "$mrsv" encode --quiet --bits 14 "$cow" "$work/cow.mrsv"
expect 0 "$mrsv" check "$work/cow.mrsv"; stdout_has "progressive mesh, 2904 vertices"
expect 0 "$mrsv" info "$work/cow.mrsv"; stdout_has "PBAS"; stdout_has "2900 splits"; stdout_has "vertex-split batch"
expect 0 "$mrsv" info --json "$work/cow.mrsv"; cp "$work/stdout" "$work/stdout.json"
if python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["mesh"]["vertex_count"]==2904' "$work/stdout"; then ok; else bad "info --json of a mesh is not the expected JSON"; fi
expect 0 "$mrsv" decode --quiet --faces 580 "$work/cow.mrsv" "$work/cow580.off"
if [ "$(sed -n 2p "$work/cow580.off" | cut -d' ' -f2)" -le 580 ]; then ok; else bad "--faces 580 gave more faces"; fi
expect 0 "$mrsv" decode --quiet --fraction 1 "$work/cow.mrsv" "$work/cow.ply"
expect 0 "$mrsv" compare --json "$cow" "$work/cow.ply"; stdout_has "hausdorff"
expect 2 "$mrsv" decode --faces 5 --vertices 5 "$work/cow.mrsv" "$work/x.obj"; one_line_stderr
# A coarse level decodes only the batches it needs, and is the same level as a
# whole decode then stepped back gives (--fraction decodes everything).
expect 0 "$mrsv" decode --canonical --faces 580 "$work/cow.mrsv" "$work/cow580a.canon"; stderr_has "the level needs no more"
expect 0 "$mrsv" decode --quiet --canonical --fraction "$(python3 -c 'print(580.5 / 5804)')" "$work/cow.mrsv" "$work/cow580b.canon"
if cmp -s "$work/cow580a.canon" "$work/cow580b.canon"; then ok; else bad "--faces 580 and the same level by --fraction differ"; fi
expect 0 "$mrsv" decode --quiet --canonical --vertices 1000 "$work/cow.mrsv" "$work/cow1000.canon"
expect 0 "$mrsv" decode --quiet --vertices 1000 "$work/cow.mrsv" "$work/cow1000.off"
if [ "$(sed -n 2p "$work/cow1000.off" | cut -d' ' -f1)" -eq 1000 ]; then ok; else bad "--vertices 1000 did not give 1000 vertices"; fi
# Cut inside a chunk (the 6th), not between two: a stream cut between chunks
# is a valid prefix.
cut=$(python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["chunks"][5]; print(c["offset"] + c["length"] // 2)' "$work/stdout.json" 2>/dev/null)
head -c "$cut" "$work/cow.mrsv" >"$work/cow_cut.mrsv"
expect 1 "$mrsv" check "$work/cow_cut.mrsv"; one_line_stderr
expect 0 "$mrsv" encode --help "$work/x.obj"; stdout_has "progressive mesh"; stdout_has "--free-from"
# Moves from the first collapse (D36) cost bytes.
expect 0 "$mrsv" encode --quiet --bits 14 --free-from 1 "$cow" "$work/cow_all.mrsv"
if [ "$(stat -c %s "$work/cow_all.mrsv")" -gt "$(stat -c %s "$work/cow.mrsv")" ]; then ok; else bad "--free-from 1 did not give a larger stream"; fi
expect 2 "$mrsv" encode --free-from 1.5 "$cow" "$work/x.mrsv"; stderr_has "from 0 to 1"; one_line_stderr
expect 2 "$mrsv" encode --placement endpoint --free-from 0.5 "$cow" "$work/x.mrsv"; stderr_has "needs free placement"
# Wider batches near full resolution (D37) code fewer split flags.
expect 0 "$mrsv" encode --quiet --bits 14 --wide-batches 0.3 "$cow" "$work/cow_wide.mrsv"
if [ "$(stat -c %s "$work/cow_wide.mrsv")" -lt "$(stat -c %s "$work/cow.mrsv")" ]; then ok; else bad "--wide-batches 0.3 did not give a smaller stream"; fi
expect 0 "$mrsv" decode --quiet --fraction 0.1 "$work/cow_wide.mrsv" "$work/cow_wide10.ply"
expect 2 "$mrsv" encode --wide-batches -0.1 "$cow" "$work/x.mrsv"; stderr_has "from 0 to 1"; one_line_stderr

# Tet meshes: help, a grid and an .mrsv grid made into tets, conversion, one-line errors.
tet=$root/../shared/data/tet
expect 0 "$mrsv" tetrahedralize --help; stdout_has "Usage: mrsv tetrahedralize"
expect 0 "$mrsv" help tetrahedralize; stdout_has "6 tets per cube"
expect 1 "$mrsv" tetrahedralize --dims 128,128 --type int16 "$crop" "$work/t.vtu"; stderr_has "3-D only"; one_line_stderr
head -c 4096 "$crop" >"$work/g.raw"
expect 0 "$mrsv" encode --quiet --dims 16,16,16 --type uint8 "$work/g.raw" "$work/g.mrsv"
expect 0 "$mrsv" tetrahedralize --quiet "$work/g.mrsv" "$work/g.vtk"; stdout_has "4096 vertices, 20250 tets, 1 fields (value)"
expect 0 "$mrsv" tetrahedralize --quiet --crop 1,2,3,4,5,6 "$work/g.mrsv" "$work/g.node"; stdout_has "120 vertices, 360 tets"
if [ -s "$work/g.node" ] && [ -s "$work/g.ele" ]; then ok; else bad "OUT.node did not write .node and .ele"; fi
# Two crops of one grid keep their places in it: compared, they barely overlap, and
# compare says so rather than report a PSNR that reads like a poor approximation.
expect 0 "$mrsv" tetrahedralize --quiet --crop 0,0,0,6,6,6 "$work/g.mrsv" "$work/c0.vtu"
expect 0 "$mrsv" tetrahedralize --quiet --crop 4,4,4,6,6,6 "$work/g.mrsv" "$work/c4.vtu"
expect 0 "$mrsv" compare --samples 20000 "$work/c0.vtu" "$work/c4.vtu"; stderr_has "lie outside B: do A and B share"
expect 0 "$mrsv" compare --samples 20000 "$work/c0.vtu" "$work/c0.vtu"
if [ ! -s "$work/stderr" ]; then ok; else bad "compare of a mesh with itself warned: $(cat "$work/stderr")"; fi
expect 0 "$mrsv" tetrahedralize "$work/g.ele" "$work/g2.vtu"; stdout_has "120 vertices, 360 tets, 1 fields"
expect 2 "$mrsv" tetrahedralize "$work/g.vtk" "$work/g.obj"; stderr_has "must end in"; one_line_stderr
expect 2 "$mrsv" tetrahedralize "$work/g.vtk" "$work/g.vtk"; stderr_has "refusing to overwrite"
expect 3 "$mrsv" tetrahedralize "$work/missing.vtu" "$work/x.vtu"; one_line_stderr
expect 0 "$mrsv" tetrahedralize --quiet "$tet/bunny_5433v_34055tet.mesh" "$work/bunny.vtu"; stdout_has "5433 vertices, 34055 tets"
# A PT stream: a coarse level decodes only the batches it needs, and is the level a
# whole decode then stepped back gives (--fraction decodes everything).
expect 0 "$mrsv" encode --quiet "$tet/hand_7234v_29998tet.mesh" "$work/hand.mrsv"
expect 0 "$mrsv" decode --canonical --tets 3000 "$work/hand.mrsv" "$work/hand3000a.canon"; stderr_has "the level needs no more"
expect 0 "$mrsv" decode --quiet --canonical --fraction "$(python3 -c 'print(3000.5 / 29998)')" "$work/hand.mrsv" "$work/hand3000b.canon"
if cmp -s "$work/hand3000a.canon" "$work/hand3000b.canon"; then ok; else bad "PT --tets 3000 and the same level by --fraction differ"; fi
expect 0 "$mrsv" decode --quiet --tets 0 "$work/hand.mrsv" "$work/hand0.vtu"
expect 0 "$mrsv" decode --vertices 2000 "$work/hand.mrsv" "$work/hand2000.vtu"; stderr_has "2000 vertices"
# Streaming decode (spec 2.7): standard input, decoded as it arrives, each level
# written as soon as it is complete; the same samples and errors as from a file.
# (Input through a pipe: < <(cat ...) keeps the counters in this shell.)
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --progressive --psnr 60 "$crop" "$work/sp.mrsv"
expect 0 "$mrsv" decode --quiet "$work/sp.mrsv" "$work/sp_file.nrrd"
expect 0 "$mrsv" decode - "$work/sp_pipe.nrrd" --levels-out "$work/sp_{level}.nrrd" < <(cat "$work/sp.mrsv")
stderr_has "sp_4.nrrd: level 4, 8x8x1"; stderr_has "sp_0.nrrd: level 0, 128x128x1"
if cmp -s "$work/sp_file.nrrd" "$work/sp_pipe.nrrd" && cmp -s "$work/sp_file.nrrd" "$work/sp_0.nrrd"; then ok; else bad "decode - differs from the file's decode"; fi
expect 0 "$mrsv" decode --quiet --levels 2 "$work/sp.mrsv" "$work/sp_file2.nrrd"
if cmp -s "$work/sp_file2.nrrd" "$work/sp_2.nrrd"; then ok; else bad "--levels-out level 2 differs from --levels 2"; fi
expect 0 "$mrsv" decode --quiet --levels 1 --levels-out "$work/spx.raw" "$work/sp.mrsv" "$work/sp1.raw"
if [ -e "$work/spx-L4.raw" ] && cmp -s "$work/sp1.raw" "$work/spx-L1.raw" && [ ! -e "$work/spx-L0.raw" ]; then ok; else bad "--levels-out without {level} or with --levels"; fi
if ls "$work" | grep -q '\.tmp'; then bad "a temporary file was left"; else ok; fi
head -c 700 "$work/sp.mrsv" >"$work/sp_cut.mrsv"
expect 1 "$mrsv" decode "$work/sp_cut.mrsv" "$work/x.raw"; sed 's/^.*: offset/offset/' "$work/stderr" >"$work/err_file"
expect 1 "$mrsv" decode - "$work/x.raw" < <(head -c 700 "$work/sp.mrsv"); stderr_has "standard input: offset"; one_line_stderr
if sed 's/^.*: offset/offset/' "$work/stderr" | cmp -s - "$work/err_file"; then ok; else bad "decode - of a truncated stream gave another error"; fi
if [ ! -e "$work/x.raw" ]; then ok; else bad "decode - left an output for a truncated stream"; fi
expect 0 "$mrsv" decode --quiet --bytes 700 "$work/sp.mrsv" "$work/sp700a.raw"
expect 0 "$mrsv" decode --quiet --bytes 700 - "$work/sp700b.raw" < <(cat "$work/sp.mrsv")
if cmp -s "$work/sp700a.raw" "$work/sp700b.raw"; then ok; else bad "--bytes on standard input differs"; fi
expect 1 "$mrsv" decode - "$work/x.raw" < <(cat "$vectors/invalid/bad_checksum.mrsv"); stderr_has "offset 568: E113"
expect 0 "$mrsv" decode --quiet - "$work/cow_pipe.ply" --levels-out "$work/cow_{level}.off" < <(cat "$work/cow.mrsv")
expect 0 "$mrsv" decode --quiet "$work/cow.mrsv" "$work/cow_file.ply"
if cmp -s "$work/cow_pipe.ply" "$work/cow_file.ply" && [ -e "$work/cow_0.off" ]; then ok; else bad "PM decode - or its levels"; fi
last=$(ls "$work"/cow_[0-9]*.off | sed 's/.*cow_\([0-9]*\)\.off/\1/' | sort -n | tail -1)
if [ "$(sed -n 2p "$work/cow_$last.off" | cut -d' ' -f1)" = 2904 ]; then ok; else bad "the last PM level lacks vertices"; fi
tiled="$vectors/tiled_valid/terrain_one_tile.mrsv"
expect 0 "$mrsv" decode --quiet "$tiled" "$work/tl_file.raw"
expect 0 "$mrsv" decode --quiet - "$work/tl_pipe.raw" < <(cat "$tiled")
expect 0 "$mrsv" decode --quiet --region 0,0,4,4 - "$work/tl_region.raw" < <(cat "$tiled")
expect 0 "$mrsv" decode --quiet --region 0,0,4,4 "$tiled" "$work/tl_region_file.raw"
if cmp -s "$work/tl_file.raw" "$work/tl_pipe.raw" && cmp -s "$work/tl_region.raw" "$work/tl_region_file.raw"; then ok; else bad "a tiled grid from standard input differs"; fi
expect 0 "$mrsv" decode --quiet - "$work/hand_pipe.vtu" --levels-out "$work/hand_{level}.vtu" < <(cat "$work/hand.mrsv")
expect 0 "$mrsv" decode --quiet "$work/hand.mrsv" "$work/hand_file.vtu"
if cmp -s "$work/hand_pipe.vtu" "$work/hand_file.vtu" && [ -e "$work/hand_0.vtu" ] && [ -e "$work/hand_1.vtu" ]; then ok; else bad "PT decode - or its levels"; fi
printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\nTetrahedra\n1\n1 1 1 2 0\n' >"$work/bad.mesh"
expect 1 "$mrsv" tetrahedralize "$work/bad.mesh" "$work/x.vtu"; stderr_has "bad.mesh:8: tet 1: vertex index 2 is out of range"; one_line_stderr
if [ ! -e "$work/x.vtu" ]; then ok; else bad "a failed tetrahedralize left an output"; fi

# Mesh reconstruction (spec 8, 9): help, TINs by insertion and quadtree, the
# canonical output, one-line errors, no output on failure.
expect 0 "$mrsv" mesh --help; stdout_has "Usage: mrsv mesh"
expect 0 "$mrsv" help mesh; stdout_has "border"
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --progressive --meta spacing=30,-30 --meta origin=557970,5121870 "$crop" "$work/p.mrsv"
expect 0 "$mrsv" mesh --quiet --max-error 5 "$work/p.mrsv" "$work/p.obj"
if python3 -c '
import sys
v = [l.split() for l in open(sys.argv[1]) if l.startswith("v ")]
f = [l for l in open(sys.argv[1]) if l.startswith("f ")]
xs = [float(p[1]) for p in v]; ys = [float(p[2]) for p in v]
assert 4 < len(v) < 128 * 128 and len(f) > 2
assert min(xs) == 557970 and max(xs) == 557970 + 127 * 30 and max(ys) == 5121870 and min(ys) == 5121870 - 127 * 30
' "$work/p.obj"; then ok; else bad "mesh OBJ lacks the stream's geometry"; fi
expect 0 "$mrsv" mesh --quiet --max-error 5 --canonical "$work/p.mrsv" "$work/p1.bin"
expect 0 "$mrsv" mesh --quiet --max-error 5 --canonical "$work/p.mrsv" "$work/p2.bin"
if cmp -s "$work/p1.bin" "$work/p2.bin" && head -c 26 "$work/p1.bin" | grep -q "mrsv-canonical-grid-mesh 1"; then ok; else bad "canonical mesh output not repeatable"; fi
expect 0 "$mrsv" mesh --max-error 5 --progressive "$work/p.mrsv" "$work/pp.ply"; stderr_has "stage 1 of"
expect 0 "$mrsv" mesh --quiet --method quadtree --max-error 5 "$work/p.mrsv" "$work/q.off"
expect 0 "$mrsv" mesh --method quadtree --max-error 5 --remove-vertices "$work/p.mrsv" "$work/qr.off"
stderr_has "vertices removed after the quadtree"
if [ "$(sed -n 2p "$work/qr.off" | cut -d' ' -f2)" -lt "$(sed -n 2p "$work/q.off" | cut -d' ' -f2)" ]; then ok
else bad "the removal pass left no fewer triangles"; fi
expect 0 "$mrsv" mesh --max-error 5 --remove-vertices "$work/p.mrsv" "$work/ir.obj"; stderr_has "vertices removed after insertion"
# spec 8.1 regions: two boxes of a tiled stream sharing the column x = 70 meet
# without cracks, in the whole grid's frame, and a box's mesh is the mesh of
# its samples coded alone.
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --tile 64 --max-error 2 --meta spacing=30,-30 \
  "$crop" "$work/pt.mrsv"
expect 0 "$mrsv" mesh --quiet --max-error 5 --region 0,0,71,128 "$work/pt.mrsv" "$work/ra.obj"
expect 0 "$mrsv" mesh --quiet --max-error 5 --region 70,0,128,128 "$work/pt.mrsv" "$work/rb.obj"
if python3 - "$work/ra.obj" "$work/rb.obj" <<'PY'
import sys
def side(path):
    return {tuple(round(float(t)) for t in l.split()[1:4]) for l in open(path)
            if l.startswith("v ") and round(float(l.split()[1])) == 70 * 30}
a, b = side(sys.argv[1]), side(sys.argv[2])
sys.exit(0 if a == b and len(a) > 2 else 1)
PY
then ok; else bad "two regions sharing a column do not share its vertices"; fi
expect 0 "$mrsv" decode --quiet --region 70,0,128,128 "$work/pt.mrsv" "$work/rb.raw"
expect 0 "$mrsv" encode --quiet --dims 58,128 --type int16 --lossless "$work/rb.raw" "$work/rb.mrsv"
expect 0 "$mrsv" mesh --quiet --max-error 5 --canonical "$work/rb.mrsv" "$work/rb1.can"
expect 0 "$mrsv" mesh --quiet --max-error 5 --region 70,0,128,128 --canonical "$work/pt.mrsv" "$work/rb2.can"
if cmp -s "$work/rb1.can" "$work/rb2.can"; then ok; else bad "a region's mesh differs from the mesh of its samples"; fi
expect 2 "$mrsv" mesh --max-error 5 --region 0,0,129,128 "$work/pt.mrsv" "$work/x.obj"; stderr_has "beyond"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 5 --region 0,0,64,64 --progressive "$work/pt.mrsv" "$work/x.obj"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 5 --progressive --remove-vertices "$work/p.mrsv" "$work/x.obj"; stderr_has "--remove-vertices"; one_line_stderr
expect 2 "$mrsv" mesh --triangles 500 --remove-vertices "$work/p.mrsv" "$work/x.obj"; stderr_has "needs --max-error"; one_line_stderr
expect 0 "$mrsv" mesh --quiet --triangles 500 "$work/p.mrsv" "$work/t.obj"
expect 0 "$mrsv" mesh --quiet --levels 2 --max-error 5 "$work/p.mrsv" "$work/l.obj"
expect 2 "$mrsv" mesh "$work/p.mrsv" "$work/x.obj"; stderr_has "give --max-error"; one_line_stderr
expect 2 "$mrsv" mesh --max-error -1 "$work/p.mrsv" "$work/x.obj"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 5 "$work/p.mrsv" "$work/x.vtu"; stderr_has "2-D grid"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 5 --method quadtree --progressive "$work/p.mrsv" "$work/x.obj"; one_line_stderr
expect 1 "$mrsv" mesh --max-error 5 --levels 12 "$work/p.mrsv" "$work/x.obj"; one_line_stderr
expect 1 "$mrsv" mesh --max-error 5 "$vectors/invalid/bad_checksum.mrsv" "$work/x.obj"; stderr_has "E113"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 5 "$work/p.mrsv" "$work/p.mrsv"; stderr_has "refusing to overwrite"
if [ ! -e "$work/x.obj" ] && [ ! -e "$work/x.vtu" ]; then ok; else bad "a failed mesh left an output"; fi
# 3-D: tets by insertion, opened back by our reader; 2-D options refused.
expect 0 "$mrsv" mesh --quiet --max-error 8 --progressive "$work/g.mrsv" "$work/g_ins.vtu"
expect 0 "$mrsv" tetrahedralize "$work/g_ins.vtu" "$work/g_ins.mesh"; stdout_has "1 fields (value)"
expect 0 "$mrsv" mesh --quiet --tets 300 --max-error 20 --distance trilinear "$work/g.mrsv" "$work/g_t.node"
expect 2 "$mrsv" mesh --tets 300 --distance trilinear "$work/g.mrsv" "$work/g_t2.node"; stderr_has "needs --max-error"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 8 --method quadtree "$work/g.mrsv" "$work/x.vtu"; stderr_has "2-D grids"; one_line_stderr
expect 2 "$mrsv" mesh --triangles 50 "$work/g.mrsv" "$work/x.vtu"; stderr_has "use --tets"; one_line_stderr
expect 2 "$mrsv" mesh --max-error 8 "$work/g.mrsv" "$work/x.obj"; stderr_has "tet mesh"; one_line_stderr

# Tiled grids (spec 11): tiles, regions, threads, out of core, one-line errors.
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --tile 48,40 --max-error 2 --meta spacing=30,-30 \
  --meta origin=1000,2000 "$crop" "$work/t.mrsv"
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --tile 48,40 --max-error 2 --meta spacing=30,-30 \
  --meta origin=1000,2000 --out-of-core --threads 1 "$crop" "$work/t2.mrsv"
if cmp -s "$work/t.mrsv" "$work/t2.mrsv"; then ok; else bad "out-of-core and threads change the stream"; fi
expect 0 "$mrsv" info "$work/t.mrsv"; stdout_has "tiled 48x40 (12 tiles"; stdout_has "TIDX"
expect 0 "$mrsv" check "$work/t.mrsv"; stdout_has "ok: grid"
expect 0 "$mrsv" decode "$work/t.mrsv" "$work/t.raw"
expect 0 "$mrsv" decode --region 10,20,60,90 "$work/t.mrsv" "$work/tr.nrrd"; stderr_has "region 50x70x1"; stderr_has "bytes read"
expect 0 "$mrsv" decode --quiet --region 10,20,60,90 --levels 1 "$work/t.mrsv" "$work/tr1.nrrd"
grep -q "sizes: 25 35" "$work/tr1.nrrd" && ok || bad "a region at --levels 1 is not every second sample"
expect 2 "$mrsv" decode --region 10,20,600,90 "$work/t.mrsv" "$work/x.raw"; stderr_has "beyond the grid"; one_line_stderr
expect 2 "$mrsv" decode --region 10,20,5 "$work/t.mrsv" "$work/x.raw"; stderr_has "give X0,X1"; one_line_stderr
expect 2 "$mrsv" decode --region 10,20,10,30 "$work/t.mrsv" "$work/x.raw"; stderr_has "empty"; one_line_stderr
expect 2 "$mrsv" decode --threads 0 "$work/t.mrsv" "$work/x.raw"; one_line_stderr
expect 2 "$mrsv" encode --dims 128,128 --type int16 --tile 0 "$crop" "$work/x.mrsv"; stderr_has "--tile"; one_line_stderr
expect 2 "$mrsv" encode --dims 128,128 --type int16 --tile 8,8,8 "$crop" "$work/x.mrsv"; stderr_has "3 sizes"; one_line_stderr
expect 2 "$mrsv" encode --dims 128,128 --type int16 --tile 64 --coding stored "$crop" "$work/x.mrsv"; one_line_stderr
expect 2 "$mrsv" encode --dims 128,128 --type int16 --out-of-core "$crop" "$work/x.mrsv"; stderr_has "needs --tile"; one_line_stderr
expect 2 "$mrsv" encode --dims 128,128 --type int16 --tile 64 --out-of-core --roi box:1,1,9,9 "$crop" "$work/x.mrsv"; stderr_has "--roi"; one_line_stderr
# A rate or PSNR target out of core: a pass over IN per step tried, the same stream.
for target in "--bits-per-sample 1.5" "--psnr 55"; do
  expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --tile 48,40 $target "$crop" "$work/tq.mrsv"
  expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --tile 48,40 $target --out-of-core "$crop" "$work/tq2.mrsv"
  if cmp -s "$work/tq.mrsv" "$work/tq2.mrsv"; then ok; else bad "out of core, $target: another stream"; fi
done
expect 1 "$mrsv" encode --dims 128,128 --type int16 --tile 64 --step 4 --roi box:1,1,9,9 "$crop" "$work/x.mrsv"; stderr_has "region of interest"; one_line_stderr
expect 3 "$mrsv" encode --dims 129,128 --type int16 --tile 64 --out-of-core "$crop" "$work/x.mrsv"; stderr_has "bytes"; one_line_stderr
expect 1 "$mrsv" decode --region 1,1,9,9 "$vectors/tiled_invalid/index_length_disagrees.mrsv" "$work/x.raw"; stderr_has "E208"; one_line_stderr
if [ ! -e "$work/x.mrsv" ] && [ ! -e "$work/x.raw" ]; then ok; else bad "a failed tiled command left an output"; fi

expect 1 "$mrsv" encode --dims 128,128 --type int16 --precinct 16 --max-error 2 --bound-route predictive --out-of-core \
  "$crop" "$work/x.mrsv"; stderr_has "residual route only"; one_line_stderr
# A grid in precincts decoded whole to raw or NRRD goes by rows of precincts
# on the threads: the samples of the whole decoder (the canonical output's),
# for any thread count; a damaged stream gives the whole decoder's error.
expect 0 "$mrsv" encode --quiet --dims 128,128 --type int16 --precinct 16 --step 3 "$crop" "$work/p.mrsv"
expect 0 "$mrsv" decode --quiet --canonical "$work/p.mrsv" "$work/p.canon"
for t in 1 3; do
  expect 0 "$mrsv" decode --quiet --threads $t "$work/p.mrsv" "$work/p$t.raw"
  if tail -c 32768 "$work/p.canon" | cmp -s - "$work/p$t.raw"; then ok; else bad "precinct rows on $t threads differ"; fi
done
expect 0 "$mrsv" decode --quiet "$work/p.mrsv" "$work/p.nrrd"
if tail -c 32768 "$work/p.nrrd" | cmp -s - "$work/p1.raw"; then ok; else bad "precinct rows to NRRD differ"; fi
cp "$work/p.mrsv" "$work/pd.mrsv"
printf '\x55' | dd of="$work/pd.mrsv" bs=1 seek=$(( $(stat -c %s "$work/p.mrsv") / 2 )) conv=notrunc 2>/dev/null
expect 1 "$mrsv" decode --canonical "$work/pd.mrsv" "$work/x.canon"; cp "$work/stderr" "$work/stderr.whole"
expect 1 "$mrsv" decode "$work/pd.mrsv" "$work/x.raw"; one_line_stderr
if [ "$(sed 's/x\.raw/X/' "$work/stderr")" = "$(sed 's/x\.canon/X/' "$work/stderr.whole")" ]; then ok
else bad "a damaged precinct stream: $(cat "$work/stderr") against $(cat "$work/stderr.whole")"; fi
if [ ! -e "$work/x.raw" ]; then ok; else bad "a failed precinct decode left an output"; fi

echo "cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
