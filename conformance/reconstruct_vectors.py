#!/usr/bin/env python3
"""Writes the reconstruction vectors (spec 8) and their manifest entries.

Each vector is a small grid stream, made by the reference encoder (`mrsv encode`)
from a crop of a real terrain (the manifest's description names the crop), with a
list of reconstructions in "reconstruct": the options of `mrsv mesh` ("args") and
either the SHA-256 of the canonical output of 8.2 or "refused" (the reconstructor
must exit non-zero and write nothing). The expected hashes are computed by
reconstruct_reference.py, the suite's own reconstructor written from the text of
chapter 8 alone, and each is checked equal to the reference reconstructor's
(`mrsv mesh ... --canonical`) before it is written; a disagreement stops the script
with the first differing vertex or triangle. A case the reference reconstructor is
known to get wrong carries "known_failure" (why); run_conformance.py reports it
and only fails if it starts to pass, so that the mark is removed with the fix.

The entry's own "sha256" is the stream's decoded grid (3.4) as the reference
decoder writes it, so the grid runs of the suite decode these streams too.

  python3 conformance/reconstruct_vectors.py --data DIR --mrsv build/mrsv
      DIR holds terrain/*.raw.zst (the project's shared real data); writes
      vectors/reconstruct/ and the reconstruction entries of manifest.json
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

PREFIX = "vectors/reconstruct/"

TERRAINS = {
    "st_helens": ("mt_st_helens_317x460_int16le.raw.zst", 317, 460),
    "big_tujunga": ("big_tujunga_1197x643_int16le.raw.zst", 1197, 643),
    "fuji": ("srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", 1201, 1201),
}


def crop(data_dir, terrain, row, col, w, h, cache={}):
    name, width, height = TERRAINS[terrain]
    if name not in cache:
        raw = subprocess.run(["zstd", "-d", "-c", os.path.join(data_dir, "terrain", name)],
                             check=True, capture_output=True).stdout
        cache[name] = struct.unpack("<%dh" % (width * height), raw)
    full = cache[name]
    out = []
    for y in range(row, row + h):
        out.extend(full[y * width + col:y * width + col + w])
    return struct.pack("<%dh" % len(out), *out)


def encode(mrsv, raw, dims, options, sample_type="int16"):
    with tempfile.TemporaryDirectory(prefix="mrsv-rvec-") as tmp:
        src, dst = os.path.join(tmp, "in.raw"), os.path.join(tmp, "out.mrsv")
        with open(src, "wb") as f:
            f.write(raw)
        subprocess.run([mrsv, "encode", "--quiet", "--dims", ",".join(map(str, dims)), "--type", sample_type]
                       + options + [src, dst], check=True)
        return open(dst, "rb").read()


def run_reference(mrsv, stream, args):
    """The reference reconstructor's canonical output, or None when it refuses."""
    with tempfile.TemporaryDirectory(prefix="mrsv-rvec-") as tmp:
        src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            f.write(stream)
        r = subprocess.run([mrsv, "mesh", "--quiet", "--canonical", src, dst] + args, capture_output=True)
        if r.returncode != 0:
            return None
        return open(dst, "rb").read()


def run_python(mrsv, stream, args):
    """reconstruct_reference.py's canonical output, or None when it refuses."""
    with tempfile.TemporaryDirectory(prefix="mrsv-rvec-") as tmp:
        src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            f.write(stream)
        r = subprocess.run([sys.executable, os.path.join(HERE, "reconstruct_reference.py"), src, dst,
                            "--mrsv", mrsv, "--quiet"] + args, capture_output=True)
        if r.returncode != 0:
            return None
        return open(dst, "rb").read()


def first_difference(a, b):
    """Where two canonical outputs (8.2) first differ: the header, a vertex or a triangle."""
    la, lb = a.index(b"\n"), b.index(b"\n")
    if a[:la] != b[:lb]:
        return f"header {a[:la].decode()} against {b[:lb].decode()}"
    v = int(a[:la].split()[3])
    for i in range(v):
        x, y = a[la + 1 + 16 * i:la + 17 + 16 * i], b[la + 1 + 16 * i:la + 17 + 16 * i]
        if x != y:
            return f"vertex {i}: {struct.unpack('<IIIi', x)} against {struct.unpack('<IIIi', y)}"
    base = la + 1 + 16 * v
    for i in range((len(a) - base) // 12):
        x, y = a[base + 12 * i:base + 12 * i + 12], b[base + 12 * i:base + 12 * i + 12]
        if x != y:
            return f"triangle {i}: {struct.unpack('<III', x)} against {struct.unpack('<III', y)}"
    return "none"


def grid_canonical(mrsv, stream):
    with tempfile.TemporaryDirectory(prefix="mrsv-rvec-") as tmp:
        src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            f.write(stream)
        subprocess.run([mrsv, "decode", "--quiet", "--canonical", src, dst], check=True)
        return open(dst, "rb").read()


def chunk_ends(stream, kind):
    return [e for t, _, e in rr.chunks(stream) if t == kind]


# Known disagreements of the reference reconstructor with the text, by (vector, args).
KNOWN_FAILURES = {}


def build(data_dir, mrsv):
    """(name, stream, description, cases): cases are lists of args; refusals marked with '!'."""
    out = []
    sh33 = crop(data_dir, "st_helens", 100, 150, 33, 33)
    where_sh33 = "Mt St Helens (mt_st_helens_317x460) rows 100-132, cols 150-182"
    out.append(("sh33_stored", encode(mrsv, sh33, (33, 33), ["--coding", "stored"]),
                f"stored 33x33 int16 crop of {where_sh33}",
                [["--max-error", "20"], ["--max-error", "2.5"], ["--max-error", "0"],
                 ["--max-error", "1", "--no-border-rule"], ["--max-error", "2.5", "--no-border-cleanup"],
                 ["--triangles", "50"],
                 ["--max-error", "20", "--triangles", "40"], ["--max-error", "1", "--progressive"],
                 ["--max-error", "2147483648"], ["--max-error", ".5"],
                 ["!", "--max-error", "2.5000000001"], ["!", "--max-error", "2147483648.5"],
                 ["!", "--triangles", "0"], ["!", "--max-error", "1", "--levels", "1"],
                 ["--max-error", "5", "--remove-vertices"], ["--max-error", "0", "--remove-vertices"],
                 ["--max-error", "1", "--no-border-rule", "--remove-vertices"],
                 ["--max-error", "5", "--triangles", "100", "--remove-vertices"],
                 ["!", "--max-error", "1", "--progressive", "--remove-vertices"],
                 ["!", "--triangles", "50", "--remove-vertices"],
                 ["--max-error", "5", "--region", "0,0,17,33"], ["--max-error", "5", "--region", "16,0,33,33"],
                 ["--max-error", "2", "--region", "16,0,33,33", "--remove-vertices"],
                 ["--triangles", "40", "--region", "3,5,20,31", "--no-border-rule"],
                 ["!", "--max-error", "5", "--region", "0,0,34,33"],
                 ["!", "--max-error", "5", "--region", "0,0,17,33", "--progressive"]]))
    ll = encode(mrsv, sh33, (33, 33), ["--progressive", "--lossless"])
    bands = chunk_ends(ll, b"GBND")
    stream = rr.Stream(ll)
    lv = stream.band_levels()
    first_of_level1 = bands[lv.index(1)]
    last_of_level2 = bands[lv.index(1) - 1]
    no_band = [e for t, _, e in rr.chunks(ll) if t == b"WHDR"][0]
    out.append(("sh33_lossless_progressive", ll,
                f"lossless progressive 33x33 int16 (CDF 9/7, levels {stream.levels[0]}/{stream.levels[1]}, "
                f"bands and residual) of {where_sh33}",
                [["--max-error", "1", "--progressive"], ["--max-error", "0", "--progressive"],
                 ["--max-error", "2.5"], ["--max-error", "5", "--progressive", "--no-border-rule"],
                 ["--triangles", "100", "--progressive"], ["--max-error", "2", "--triangles", "80", "--progressive"],
                 ["--max-error", "3", "--levels", "1"], ["--max-error", "3", "--levels", "1", "--progressive"],
                 ["--max-error", "3", "--levels", "2", "--progressive"],
                 ["--max-error", "4", "--bytes", str(bands[-1]), "--progressive"],
                 ["--max-error", "4", "--bytes", str(first_of_level1), "--progressive"],
                 ["--max-error", "4", "--bytes", str(first_of_level1), "--levels", "1", "--progressive"],
                 ["--max-error", "4", "--bytes", str(last_of_level2)],
                 ["--max-error", "1", "--bytes", str(bands[0])],
                 ["!", "--max-error", "3", "--levels", "3"],
                 ["!", "--max-error", "1", "--bytes", str(no_band)]]))
    bt = crop(data_dir, "big_tujunga", 200, 500, 65, 49)
    where_bt = "Big Tujunga (big_tujunga_1197x643) rows 200-248, cols 500-564"
    out.append(("bt65x49_psnr40_progressive", encode(mrsv, bt, (65, 49), ["--progressive", "--psnr", "40"]),
                f"lossy progressive (--psnr 40) 65x49 int16 of {where_bt}",
                [["--max-error", "2.5", "--progressive"], ["--max-error", "20"],
                 ["--max-error", "1", "--progressive", "--no-border-rule"],
                 ["--triangles", "300", "--progressive"], ["--max-error", "5", "--levels", "1", "--progressive"]]))
    ne = encode(mrsv, bt, (65, 49), ["--progressive", "--max-error", "2"])
    bands, lv = chunk_ends(ne, b"GBND"), rr.Stream(ne).band_levels()
    # Level 1's first band has a nonzero step here: a prefix ending with it differs from level 2's end.
    first_of_level1 = str(bands[lv.index(1)])
    out.append(("bt65x49_maxerr2_progressive", ne,
                f"near-lossless progressive (--max-error 2; levels 3/2, so level 3 splits x alone) 65x49 int16 "
                f"of {where_bt}",
                [["--max-error", "0", "--progressive"], ["--max-error", "2.5"], ["--max-error", "20", "--progressive"],
                 ["--max-error", "2", "--bytes", first_of_level1, "--progressive"],
                 ["--max-error", "2", "--bytes", first_of_level1, "--levels", "1", "--progressive"],
                 ["--max-error", "2", "--bytes", str(bands[-1]), "--progressive"],
                 ["--max-error", "2", "--levels", "2"], ["--max-error", "1", "--levels", "3", "--progressive"],
                 ["!", "--max-error", "1", "--levels", "4"]]))
    sh17 = crop(data_dir, "st_helens", 300, 40, 17, 65)
    where_sh17 = "Mt St Helens (mt_st_helens_317x460) rows 300-364, cols 40-56"
    out.append(("sh17x65_lossless", encode(mrsv, sh17, (17, 65), ["--lossless"]),
                f"lossless 17x65 int16 (the encoder's choice of route) of {where_sh17}",
                [["--max-error", "1"], ["--max-error", "1", "--no-border-cleanup"], ["--max-error", "0", "--progressive"],
                 ["--max-error", "2.5", "--no-border-rule"],
                 ["--max-error", "2.5", "--remove-vertices"]]))
    fuji = crop(data_dir, "fuji", 750, 850, 33, 33)
    where_fuji = "Mt Fuji's summit (srtm3_N35E138_mt_fuji_1201x1201) rows 750-782, cols 850-882, 45 voids"
    out.append(("fuji33_mask_lossless_progressive",
                encode(mrsv, fuji, (33, 33), ["--nodata", "-32768", "--progressive", "--lossless"]),
                f"lossless progressive 33x33 int16 with a no-data mask of {where_fuji}",
                [["--max-error", "5"], ["--max-error", "2", "--progressive"], ["--max-error", "0"],
                 ["--max-error", "5", "--remove-vertices"]]))
    out.append(("fuji33_mask_psnr45_progressive",
                encode(mrsv, fuji, (33, 33), ["--nodata", "-32768", "--progressive", "--psnr", "45"]),
                f"lossy progressive (--psnr 45) 33x33 int16 with a no-data mask of {where_fuji}",
                [["--max-error", "2.5", "--progressive"], ["--max-error", "20"]]))
    coast = crop(data_dir, "fuji", 1024, 800, 33, 33)
    where_coast = "the coast of Suruga Bay (srtm3_N35E138_mt_fuji_1201x1201) rows 1024-1056, cols 800-832, 42 % sea at 0"
    out.append(("coast33_stored", encode(mrsv, coast, (33, 33), ["--coding", "stored"]),
                f"stored 33x33 int16 of {where_coast}: flat sea, many equal errors and cocircular points",
                [["--max-error", "0"], ["--max-error", "1", "--no-border-rule"], ["--triangles", "64"],
                 ["--max-error", "0.5"]]))
    g2 = crop(data_dir, "st_helens", 100, 150, 2, 2)
    out.append(("grid_2x2_stored", encode(mrsv, g2, (2, 2), ["--coding", "stored"]),
                "stored 2x2 int16, the smallest grid 8.1 accepts: Mt St Helens rows 100-101, cols 150-151",
                [["--max-error", "0"], ["--triangles", "1"]]))
    g53 = crop(data_dir, "st_helens", 100, 150, 5, 3)
    out.append(("grid_5x3_lossless", encode(mrsv, g53, (5, 3), ["--progressive", "--lossless"]),
                "lossless 5x3 int16 (no wavelet level): Mt St Helens rows 100-102, cols 150-154",
                [["--max-error", "0", "--progressive"], ["--max-error", "0", "--no-border-rule"]]))
    # Refusals (8.1).
    floats = struct.pack("<%df" % (33 * 33), *struct.unpack("<%dh" % (33 * 33), sh33))
    out.append(("float32_33x33_stored", encode(mrsv, floats, (33, 33), ["--coding", "stored"], "float32"),
                f"stored 33x33 float32 (the int16 values of {where_sh33}): float samples are refused",
                [["!", "--max-error", "1"]]))
    line = sh33[:66]
    out.append(("line_33_int16", encode(mrsv, line, (33,), ["--coding", "stored"]),
                "stored 1-D int16 grid of 33 samples (Mt St Helens row 100, cols 150-182): refused",
                [["!", "--max-error", "1"]]))
    out.append(("col_1x33_int16", encode(mrsv, line, (1, 33), ["--coding", "stored"]),
                "stored 2-D int16 grid of 1 x 33 samples (Mt St Helens row 100, cols 150-182): X < 2, refused",
                [["!", "--max-error", "1"]]))
    out.append(("row_33x1_int16", encode(mrsv, line, (33, 1), ["--coding", "stored"]),
                "stored 2-D int16 grid of 33 x 1 samples (Mt St Helens row 100, cols 150-182): Y < 2, refused",
                [["!", "--max-error", "1"]]))
    return out


def rules_of_case(args, stream, refused):
    """The R8 tags one reconstruction exercises."""
    s = rr.Stream(stream)
    if refused:
        if s.sample_type not in rr.INTEGER_TYPES or s.num_dims != 2 or s.sx < 2 or s.sy < 2:
            return ["R8.1-2"]
        if "--remove-vertices" in args:
            return ["R8.8-1"]
        if "--region" in args:
            return ["R8.1-3"]
        if "--levels" in args or "--bytes" in args:
            return ["R8.7-1"]
        return ["R8.5-2"]
    tags = ["R8-1", "R8.2-1", "R8.2-2", "R8.2-3", "R8.3-1", "R8.3-2", "R8.4-1", "R8.5-1", "R8.5-3",
            "R8.5-4", "R8.5-5"]
    if "--max-error" in args:
        tags.append("R8.5-2")
        if "--no-border-rule" not in args:
            tags += ["R8.6-1", "R8.6-2"]
    if s.has_mask:
        tags.append("R8.1-1")
    if s.coding == 1:
        tags += ["R8.7-1", "R8.7-2"]
    if "--remove-vertices" in args:
        tags += ["R8.8-1"] + ["R9.4-1", "R9.7-1", "R9.7-2", "R9.7-3", "R9.7-4", "R9.7-5"]
    elif ("--max-error" in args and "--no-border-rule" not in args and "--progressive" not in args
          and "--no-border-cleanup" not in args):
        tags += ["R8.8-2"] + ["R9.4-1", "R9.7-1", "R9.7-2", "R9.7-3", "R9.7-4", "R9.7-5"]
    if "--region" in args:
        tags.append("R8.1-3")
    return tags


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", required=True, help="the shared data directory (terrain/*.raw.zst)")
    parser.add_argument("--mrsv", required=True, help="the reference mrsv binary")
    args = parser.parse_args()
    from make_vectors import write_manifest, with_rules  # noqa: E402
    from vector_rules import RULES  # noqa: E402
    entries, mismatches, cases_total, refusals = [], [], 0, 0
    os.makedirs(os.path.join(HERE, PREFIX), exist_ok=True)
    for n in os.listdir(os.path.join(HERE, PREFIX)):
        os.remove(os.path.join(HERE, PREFIX, n))
    for name, stream, description, cases in build(args.data, args.mrsv):
        path = PREFIX + name + ".mrsv"
        with open(os.path.join(HERE, path), "wb") as f:
            f.write(stream)
        grid = grid_canonical(args.mrsv, stream)
        recs, tags = [], set()
        for case in cases:
            refused = case[0] == "!"
            a = case[1:] if refused else case
            t0 = time.time()
            mine = run_python(args.mrsv, stream, a)
            took = time.time() - t0
            ref = run_reference(args.mrsv, stream, a)
            known = KNOWN_FAILURES.get((name, tuple(a)))
            rec = {"args": a}
            cases_total += 1
            if refused:
                refusals += 1
                if mine is not None:
                    sys.exit(f"{name} {a}: the text refuses this, reconstruct_reference.py did not")
                rec["refused"] = True
                if (ref is None) == bool(known):
                    mismatches.append(f"{name} {' '.join(a)}: the reference "
                                      f"{'refuses' if ref is None else 'does not refuse'}")
            else:
                if mine is None:
                    sys.exit(f"{name} {a}: reconstruct_reference.py refused")
                head = mine[:mine.index(b"\n")].split()
                rec.update({"sha256": hashlib.sha256(mine).hexdigest(), "output_bytes": len(mine),
                            "vertices": int(head[3]), "triangles": int(head[4])})
                if ref != mine and not known:
                    mismatches.append(f"{name} {' '.join(a)}: " +
                                      ("the reference refuses" if ref is None else first_difference(ref, mine)))
            if known:
                rec["known_failure"] = known
            recs.append(rec)
            tags |= set(rules_of_case(a, stream, refused))
            print(f"  {name} {' '.join(case)}: "
                  f"{'refused' if refused else '%d vertices, %d triangles' % (rec['vertices'], rec['triangles'])}"
                  f" ({took:.1f} s)")
        want = sorted(tags, key=lambda t: [int(x) for x in t[1:].replace("-", ".").split(".")])
        if RULES.get(name) != want:
            print(f'reconstruct_vectors: vector_rules.py should say "{name}": {json.dumps(want)}')
        entry = {"file": path, "valid": True, "sha256": hashlib.sha256(grid).hexdigest(), "output_bytes": len(grid),
                 "expected_by": "reference decoder", "clause": "8", "description": description,
                 "reconstruct": recs}
        entries.append(with_rules(entry, stream))
    manifest_path = os.path.join(HERE, "manifest.json")
    with open(manifest_path, encoding="utf-8") as f:
        kept = [e for e in json.load(f)["vectors"] if not e["file"].startswith(PREFIX)]
    with open(manifest_path, "wb") as f:
        f.write(write_manifest(kept + entries))
    for m in mismatches:
        print("MISMATCH " + m)
    print(f"reconstruct_vectors: {len(entries)} streams, {cases_total} reconstructions ({refusals} refusals), "
          f"{len(mismatches)} disagreements with the reference reconstructor")
    return 1 if mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
