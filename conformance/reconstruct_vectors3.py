#!/usr/bin/env python3
"""Writes the reconstruction vectors of spec 10 (3-D Delaunay insertion) and spec 9
(quadtree), and their manifest entries.

As in reconstruct_vectors.py (chapter 8): each vector is a small grid stream made by
the reference encoder from a crop of real data (the description names it), with a
"reconstruct" list of `mrsv mesh` options ("args") and the SHA-256 of the canonical
output of 8.2, or "refused".

  - Chapter 10 (vectors/reconstruct3/): crops of the Stanford CT head. The expected
    hashes come from reconstruct_reference3.py, the suite's own reconstructor written
    from the text of chapter 10 alone, and each is checked equal to the reference
    reconstructor's (`mrsv mesh ... --canonical`); a disagreement stops the script with
    the first differing vertex or tet.
  - Chapter 9 (vectors/quadtree/): crops of the terrains, meshed with --method quadtree.
    The max-error cases (9.3 to 9.6) get their hashes from quadtree_reference.py, the
    suite's own quadtree written from chapter 9 alone, checked equal to the reference's.
    The wavelet-criterion cases (--epsilon, 9.2) carry the reference reconstructor's hash
    ("expected_by": "reference reconstructor" on the case): the suite has no detail
    signals of its own, so these pin the reference's behaviour down but do not check it
    against the text.

  python3 conformance/reconstruct_vectors3.py --data DIR --mrsv build/mrsv
      DIR holds terrain/*.raw.zst and volume/*.raw.zst (the project's shared real data)
"""
import argparse
import hashlib
import json
import os
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import reconstruct_reference as rr  # noqa: E402
import reconstruct_vectors as rv  # noqa: E402

PREFIX3 = "vectors/reconstruct3/"
PREFIXQ = "vectors/quadtree/"
HEAD = ("ct_head_stanford_cthead_256x256x99_uint8.raw.zst", 256, 256, 99)
HEADSQ = ("ct_head_vtk_headsq_64x64x93_uint16le.raw.zst", 64, 64, 93)


def crop3(data_dir, volume, z, y, x, dx, dy, dz, cache={}):
    name, sx, sy, sz = volume
    if name not in cache:
        cache[name] = subprocess.run(["zstd", "-d", "-c", os.path.join(data_dir, "volume", name)],
                                     check=True, capture_output=True).stdout
    raw, size = cache[name], 1 if name.endswith("uint8.raw.zst") else 2
    out = bytearray()
    for k in range(z, z + dz):
        for j in range(y, y + dy):
            p = ((k * sy + j) * sx + x) * size
            out += raw[p:p + dx * size]
    return bytes(out)


def run_python3(mrsv, stream, args):
    """reconstruct_reference3.py's canonical output, or None when it refuses."""
    with tempfile.TemporaryDirectory(prefix="mrsv-rvec3-") as tmp:
        src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            f.write(stream)
        r = subprocess.run([sys.executable, os.path.join(HERE, "reconstruct_reference3.py"), src, dst,
                            "--mrsv", mrsv, "--quiet"] + args, capture_output=True)
        if r.returncode != 0:
            return None
        return open(dst, "rb").read()


def run_quadtree(mrsv, stream, args):
    """quadtree_reference.py's canonical output, or None when it refuses."""
    with tempfile.TemporaryDirectory(prefix="mrsv-rvecq-") as tmp:
        src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            f.write(stream)
        r = subprocess.run([sys.executable, os.path.join(HERE, "quadtree_reference.py"), src, dst,
                            "--mrsv", mrsv, "--quiet"] + args, capture_output=True)
        if r.returncode != 0:
            return None
        return open(dst, "rb").read()


def build3(data_dir, mrsv):
    """Chapter 10: (name, stream, description, cases); refusals marked with '!'."""
    enc = rv.encode
    out = []
    h5 = crop3(data_dir, HEAD, 76, 72, 72, 5, 5, 5)
    where5 = "the Stanford CT head (ct_head_stanford_cthead_256x256x99), slices 76-80, rows 72-76, cols 72-76"
    out.append(("head5_stored", enc(mrsv, h5, (5, 5, 5), ["--coding", "stored"], "uint8"),
                f"stored 5x5x5 uint8 of {where5} (skull and soft tissue: samples 0 to 255)",
                [["--max-error", "50"], ["--max-error", "10"], ["--max-error", "0"], ["--max-error", "2.5"],
                 ["--tets", "60"], ["--max-error", "10", "--tets", "100"],
                 ["--max-error", "10", "--distance", "trilinear"], ["--max-error", "0", "--distance", "trilinear"],
                 ["--max-error", "10", "--progressive"], ["--max-error", "2147483648"], ["--max-error", ".5"],
                 ["!"], ["!", "--max-error", "2.5000000001"], ["!", "--max-error", "1", "--levels", "1"]]))
    h9 = crop3(data_dir, HEAD, 76, 72, 72, 9, 9, 9)
    where9 = "the Stanford CT head (ct_head_stanford_cthead_256x256x99), slices 76-84, rows 72-80, cols 72-80"
    ll = enc(mrsv, h9, (9, 9, 9), ["--progressive", "--lossless", "--wavelet", "bspline"], "uint8")
    bands = rv.chunk_ends(ll, b"GBND")
    st = rr.Stream(ll)
    out.append(("head9_bspline_lossless_progressive", ll,
                f"lossless progressive 9x9x9 uint8 (linear B-splines, levels {st.levels[0]}/{st.levels[1]}/"
                f"{st.levels[2]}, bands and residual) of {where9}",
                [["--max-error", "20"], ["--max-error", "5", "--progressive"], ["--tets", "200", "--progressive"],
                 ["--max-error", "10", "--distance", "trilinear", "--progressive"],
                 ["--max-error", "10", "--levels", "1"], ["--max-error", "10", "--levels", "1", "--progressive"],
                 ["--max-error", "8", "--tets", "150", "--progressive"],
                 ["--max-error", "10", "--distance", "trilinear", "--tets", "150", "--progressive"],
                 ["--max-error", "6", "--bytes", str(bands[0]), "--progressive"],
                 ["--max-error", "6", "--bytes", str(bands[-1]), "--progressive"],
                 ["!", "--max-error", "1", "--levels", "2"]]))
    h976 = crop3(data_dir, HEAD, 76, 72, 72, 9, 7, 6)
    where976 = "the Stanford CT head (ct_head_stanford_cthead_256x256x99), slices 76-81, rows 72-78, cols 72-80"
    out.append(("head9x7x6_psnr35", enc(mrsv, h976, (9, 7, 6), ["--progressive", "--psnr", "35"], "uint8"),
                f"lossy (--psnr 35, CDF 9/7, no level on these short axes) 9x7x6 uint8 of {where976}",
                [["--max-error", "10"], ["--max-error", "3", "--distance", "trilinear"], ["--tets", "100"],
                 ["--max-error", "0"]]))
    h17 = crop3(data_dir, HEAD, 40, 100, 100, 17, 17, 9)
    where17 = "the Stanford CT head (ct_head_stanford_cthead_256x256x99), slices 40-48, rows 100-116, cols 100-116"
    lossy = enc(mrsv, h17, (17, 17, 9), ["--progressive", "--psnr", "35", "--wavelet", "bspline"], "uint8")
    st = rr.Stream(lossy)
    out.append(("head17x17x9_bspline_psnr35_progressive", lossy,
                f"lossy progressive (--psnr 35, linear B-splines, levels {st.levels[0]}/{st.levels[1]}/"
                f"{st.levels[2]}) 17x17x9 uint8 of {where17}",
                [["--max-error", "10", "--progressive"], ["--max-error", "4"],
                 ["--max-error", "5", "--levels", "1", "--progressive"],
                 ["--max-error", "8", "--distance", "trilinear", "--progressive"],
                 ["--tets", "150", "--progressive"]]))
    hs = crop3(data_dir, HEADSQ, 40, 30, 30, 6, 5, 4)
    wheres = "the VTK headsq CT (ct_head_vtk_headsq_64x64x93), slices 40-43, rows 30-34, cols 30-35"
    out.append(("headsq6x5x4_uint16_stored", enc(mrsv, hs, (6, 5, 4), ["--coding", "stored"], "uint16"),
                f"stored 6x5x4 uint16 of {wheres}",
                [["--max-error", "0"], ["--max-error", "100"], ["--tets", "20"]]))
    g2 = crop3(data_dir, HEAD, 76, 72, 72, 2, 2, 2)
    out.append(("head2x2x2_stored", enc(mrsv, g2, (2, 2, 2), ["--coding", "stored"], "uint8"),
                "stored 2x2x2 uint8, the smallest grid 10.1 accepts (the eight corners): the Stanford CT head, "
                "slices 76-77, rows 72-73, cols 72-73",
                [["--max-error", "0"], ["--tets", "1"]]))
    # Refusals (10.1).
    floats = struct.pack("<125f", *h5)
    out.append(("head5_float32_stored", enc(mrsv, floats, (5, 5, 5), ["--coding", "stored"], "float32"),
                f"stored 5x5x5 float32 (the uint8 values of {where5}): float samples are refused",
                [["!", "--max-error", "1"]]))
    out.append(("head1x5x5_stored", enc(mrsv, h5[:25], (1, 5, 5), ["--coding", "stored"], "uint8"),
                "stored 1x5x5 uint8 (25 samples of the Stanford CT head): a side of 1 sample, refused",
                [["!", "--max-error", "1"]]))
    out.append(("head5x5x1_stored", enc(mrsv, h5[:25], (5, 5, 1), ["--coding", "stored"], "uint8"),
                "stored 5x5x1 uint8 (slice 76, rows 72-76, cols 72-76 of the Stanford CT head): Z = 1, refused",
                [["!", "--max-error", "1"]]))
    return out


def build9(data_dir, mrsv):
    """Chapter 9: (name, stream, description, cases); every case runs with --method quadtree."""
    enc = rv.encode
    out = []
    sh33 = rv.crop(data_dir, "st_helens", 100, 150, 33, 33)
    where = "Mt St Helens (mt_st_helens_317x460) rows 100-132, cols 150-182"
    out.append(("qt_sh33_stored", enc(mrsv, sh33, (33, 33), ["--coding", "stored"]),
                f"stored 33x33 int16 of {where}",
                [["--max-error", "5"], ["--max-error", "5", "--no-border-rule"], ["--max-error", "0"],
                 ["--max-error", "20"], ["--max-error", "2.5", "--no-border-rule"], ["--triangles", "100"],
                 ["--triangles", "1"], ["!", "--epsilon", "10"],
                 ["--max-error", "5", "--remove-vertices"], ["--max-error", "0", "--remove-vertices"],
                 ["--max-error", "2.5", "--no-border-rule", "--remove-vertices"],
                 ["--triangles", "100", "--remove-vertices"], ["!", "--epsilon", "10", "--remove-vertices"],
                 ["--max-error", "5", "--region", "16,0,33,33"],
                 ["--max-error", "5", "--region", "0,0,17,33", "--remove-vertices"],
                 ["!", "--epsilon", "10", "--region", "0,0,17,33"]]))
    out.append(("qt_sh33_bspline_lossless_progressive",
                enc(mrsv, sh33, (33, 33), ["--progressive", "--lossless", "--wavelet", "bspline"]),
                f"lossless progressive 33x33 int16 (linear B-splines, bands and residual) of {where}",
                [["--epsilon", "10"], ["--epsilon", "1000"], ["--epsilon", "0"], ["--epsilon", "10", "--levels", "1"],
                 ["--max-error", "5"], ["--max-error", "5", "--levels", "1"], ["--triangles", "200", "--epsilon", "0"],
                 ["--triangles", "150"]]))
    out.append(("qt_sh33_cdf97_lossless_progressive", enc(mrsv, sh33, (33, 33), ["--progressive", "--lossless"]),
                f"lossless progressive 33x33 int16 (CDF 9/7, bands and residual) of {where}",
                [["--epsilon", "100"], ["--epsilon", "2.5"], ["--triangles", "100", "--epsilon", "0"],
                 ["--max-error", "3"], ["--max-error", "3", "--no-border-rule"]]))
    bt = rv.crop(data_dir, "big_tujunga", 200, 500, 65, 49)
    where_bt = "Big Tujunga (big_tujunga_1197x643) rows 200-248, cols 500-564"
    lossy = enc(mrsv, bt, (65, 49), ["--progressive", "--psnr", "40", "--wavelet", "bspline"])
    bands = rv.chunk_ends(lossy, b"GBND")
    out.append(("qt_bt65x49_bspline_psnr40", lossy,
                f"lossy progressive (--psnr 40, linear B-splines) 65x49 int16 of {where_bt}: not square, "
                "so part of the tree lies outside the grid",
                [["--max-error", "10"], ["--max-error", "10", "--no-border-rule"], ["--epsilon", "50"],
                 ["--epsilon", "50", "--bytes", str(bands[len(bands) // 2])], ["--triangles", "300"],
                 ["--max-error", "10", "--remove-vertices"], ["--max-error", "10", "--no-border-rule", "--remove-vertices"],
                 ["--max-error", "4", "--levels", "1", "--remove-vertices"]]))
    sh17 = rv.crop(data_dir, "st_helens", 300, 40, 17, 65)
    out.append(("qt_sh17x65_stored", enc(mrsv, sh17, (17, 65), ["--coding", "stored"]),
                "stored 17x65 int16 of Mt St Helens (mt_st_helens_317x460) rows 300-364, cols 40-56",
                [["--max-error", "4"], ["--max-error", "4", "--no-border-rule"], ["--triangles", "64"],
                 ["--max-error", "4", "--remove-vertices"], ["--max-error", "1", "--no-border-rule", "--remove-vertices"]]))
    g3 = rv.crop(data_dir, "st_helens", 100, 150, 3, 3)
    out.append(("qt_grid_3x3_stored", enc(mrsv, g3, (3, 3), ["--coding", "stored"]),
                "stored 3x3 int16 (Mt St Helens rows 100-102, cols 150-152): under 4 x 4, so mrsv mesh meshes it "
                "without the tile border rule whether or not --no-border-rule is given",
                [["--max-error", "0"], ["--max-error", "0", "--no-border-rule"], ["--max-error", "100"],
                 ["--max-error", "100", "--remove-vertices"]]))
    g2 = rv.crop(data_dir, "st_helens", 100, 150, 2, 2)
    out.append(("qt_grid_2x2_stored", enc(mrsv, g2, (2, 2), ["--coding", "stored"]),
                "stored 2x2 int16, the smallest grid 9.1 accepts: Mt St Helens rows 100-101, cols 150-151",
                [["--max-error", "0"]]))
    g54 = rv.crop(data_dir, "st_helens", 100, 150, 5, 4)
    out.append(("qt_grid_5x4_stored", enc(mrsv, g54, (5, 4), ["--coding", "stored"]),
                "stored 5x4 int16, the smallest shapes with the tile border rule: Mt St Helens rows 100-103, "
                "cols 150-154",
                [["--max-error", "0"], ["--max-error", "3"]]))
    # 9.7's bound on a link: a flat field with a rough left column; at E = 1 the
    # border rule puts most of the column's points in the mesh, and after the
    # first removals a vertex next to it has a link of more than 6 points (of
    # more than 64 with 8.8's bound, D83's cut of this vector).
    edge = [0] * (100 * 100)
    for y in range(100):
        edge[100 * y] = (31 * y * y + 17 * y) % 13 - 6
    out.append(("qt_flat100_rough_edge_lossless",
                enc(mrsv, struct.pack("<%dh" % len(edge), *edge), (100, 100), ["--lossless"]),
                "lossless 100x100 int16, synthetic: 0 everywhere but x = 0, where v(0, y) = (31 y^2 + 17 y) mod 13 "
                "- 6; with --remove-vertices at E = 1 links reach more than the quadtree's 6 points (9.7), which "
                "changes the mesh (199 vertices, 273 triangles; with 8.8's bound of 64 points and bent points "
                "tried: 127 and 129; without a bound: 124 and 123)",
                [["--max-error", "1"], ["--max-error", "1", "--remove-vertices"],
                 ["--max-error", "1", "--no-border-rule", "--remove-vertices"]]))
    floats = struct.pack("<%df" % (33 * 33), *struct.unpack("<%dh" % (33 * 33), sh33))
    out.append(("qt_float32_33x33_stored", enc(mrsv, floats, (33, 33), ["--coding", "stored"], "float32"),
                f"stored 33x33 float32 (the int16 values of {where}): float samples are refused",
                [["!", "--max-error", "1"]]))
    out.append(("qt_col_1x33_stored", enc(mrsv, sh33[:66], (1, 33), ["--coding", "stored"]),
                "stored 1 x 33 int16 (Mt St Helens row 100, cols 150-182): under 2 x 2, refused",
                [["!", "--max-error", "1"]]))
    h5 = crop3(data_dir, HEAD, 76, 72, 72, 5, 5, 5)
    out.append(("qt_head5_stored", enc(mrsv, h5, (5, 5, 5), ["--coding", "stored"], "uint8"),
                "stored 5x5x5 uint8 of the Stanford CT head (slices 76-80, rows 72-76, cols 72-76): "
                "size_z > 1, refused by the quadtree",
                [["!", "--max-error", "1"]]))
    return out


def rules3(args, stream, refused):
    s = rr.Stream(stream)
    if refused:
        if s.sample_type not in rr.INTEGER_TYPES or min(s.sx, s.sy, s.sz) < 2:
            return ["R10.1-1"]
        if "--levels" in args:
            return ["R8.7-1"]
        if "--max-error" not in args and "--tets" not in args:
            return ["R10.1-2"]
        return ["R8.5-2"]
    tags = ["R10-1", "R8.2-1", "R8.2-2", "R8.2-3", "R10.1-2", "R10.2-1", "R10.2-2", "R10.2-3", "R10.3-1",
            "R10.4-1", "R10.4-2", "R10.5-1", "R10.7-1", "R10.7-2"]
    if "--max-error" in args:
        tags.append("R10.4-3")
        if "trilinear" in args:
            tags.append("R10.6-1")
    return tags


def rules9(args, stream, refused):
    s = rr.Stream(stream)
    if refused:
        return ["R9.1-1"]
    tags = ["R9.0-1", "R9.0-2", "R8.2-1", "R8.2-2", "R8.2-3", "R9.3-1", "R9.3-2", "R9.3-3", "R9.3-4", "R9.3-6"]
    if "--epsilon" in args:
        tags += ["R9.2-1", "R9.2-2", "R9.2-3"]
    else:
        tags += ["R9.3-5", "R9.4-1", "R9.4-2", "R9.4-3"]
        if "--max-error" in args and "--no-border-rule" not in args and s.sx >= 4 and s.sy >= 4:
            tags += ["R9.5-1", "R9.5-2"]
    if "--triangles" in args:
        tags.append("R9.6-1")
    if "--remove-vertices" in args:
        tags += ["R9.7-1", "R9.7-2", "R9.7-3", "R9.7-4", "R9.7-5"]
    if "--region" in args:
        tags.append("R8.1-3")
    return tags


def tag_key(t):
    return [int(x) for x in t[1:].replace("-", ".").split(".")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", required=True, help="the shared data directory (terrain/, volume/)")
    parser.add_argument("--mrsv", required=True, help="the reference mrsv binary")
    args = parser.parse_args()
    from make_vectors import write_manifest, with_rules  # noqa: E402
    from vector_rules import RULES  # noqa: E402
    entries, mismatches, counts = [], [], {"10": [0, 0], "9": [0, 0]}
    for prefix in (PREFIX3, PREFIXQ):
        os.makedirs(os.path.join(HERE, prefix), exist_ok=True)
        for n in os.listdir(os.path.join(HERE, prefix)):
            os.remove(os.path.join(HERE, prefix, n))
    for clause, prefix, vectors in (("10", PREFIX3, build3(args.data, args.mrsv)),
                                    ("9", PREFIXQ, build9(args.data, args.mrsv))):
        for name, stream, description, cases in vectors:
            path = prefix + name + ".mrsv"
            with open(os.path.join(HERE, path), "wb") as f:
                f.write(stream)
            grid = rv.grid_canonical(args.mrsv, stream)
            recs, tags = [], set()
            for case in cases:
                refused = bool(case) and case[0] == "!"
                a = case[1:] if refused else list(case)
                if clause == "9":
                    a = ["--method", "quadtree"] + a
                t0 = time.time()
                ref = rv.run_reference(args.mrsv, stream, a)
                by_reference = clause == "9" and "--epsilon" in a
                if clause == "10":
                    mine = run_python3(args.mrsv, stream, a)
                else:
                    mine = ref if by_reference else run_quadtree(args.mrsv, stream, a)
                took = time.time() - t0
                counts[clause][0] += 1
                rec = {"args": a}
                if by_reference:
                    rec["expected_by"] = "reference reconstructor"
                if refused:
                    counts[clause][1] += 1
                    rec["refused"] = True
                    if ref is not None or mine is not None:
                        mismatches.append(f"{name} {' '.join(a)}: a refusal, but the reference "
                                          f"{'refuses' if ref is None else 'does not refuse'} and the suite's "
                                          f"reconstructor {'refuses' if mine is None else 'does not refuse'}")
                else:
                    if mine is None:
                        sys.exit(f"{name} {a}: the expected reconstructor refused")
                    head = mine[:mine.index(b"\n")].split()
                    rec.update({"sha256": hashlib.sha256(mine).hexdigest(), "output_bytes": len(mine),
                                "vertices": int(head[3]), ("tets" if clause == "10" else "triangles"): int(head[4])})
                    if ref != mine:
                        mismatches.append(f"{name} {' '.join(a)}: " +
                                          ("the reference refuses" if ref is None else rv.first_difference(ref, mine)))
                recs.append(rec)
                tags |= set((rules3 if clause == "10" else rules9)(a, stream, refused))
                print(f"  {name} {' '.join(a)}: "
                      f"{'refused' if refused else '%d vertices, %d cells' % (rec['vertices'], int(head[4]))}"
                      f" ({took:.1f} s)")
            want = sorted(tags, key=tag_key)
            if RULES.get(name) != want:
                print(f'reconstruct_vectors3: vector_rules.py should say "{name}": {json.dumps(want)}')
            entry = {"file": path, "valid": True, "sha256": hashlib.sha256(grid).hexdigest(),
                     "output_bytes": len(grid), "expected_by": "reference decoder", "clause": clause,
                     "description": description, "reconstruct": recs}
            if clause == "9":
                entry["reconstruct_expected_by"] = ("quadtree_reference.py, checked equal to the reference; the "
                                                    "--epsilon cases (9.2): the reference reconstructor alone")
            else:
                entry["reconstruct_expected_by"] = "reconstruct_reference3.py, checked equal to the reference"
            entries.append(with_rules(entry, stream))
    manifest_path = os.path.join(HERE, "manifest.json")
    with open(manifest_path, encoding="utf-8") as f:
        kept = [e for e in json.load(f)["vectors"] if not e["file"].startswith((PREFIX3, PREFIXQ))]
    with open(manifest_path, "wb") as f:
        f.write(write_manifest(kept + entries))
    for m in mismatches:
        print("MISMATCH " + m)
    print(f"reconstruct_vectors3: {len(entries)} streams; chapter 10: {counts['10'][0]} reconstructions "
          f"({counts['10'][1]} refusals); chapter 9: {counts['9'][0]} ({counts['9'][1]} refusals); "
          f"{len(mismatches)} disagreements")
    return 1 if mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
