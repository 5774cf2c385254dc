#!/usr/bin/env python3
"""Conformance vectors of tiled grids (spec 11).

Valid vectors are written by the reference encoder (`mrsv encode --tile`) from
the crops in demo/data. Their expected outputs are made here without the
reference's tile code: the tiled stream is cut into one chapter-5 stream per
tile (GHDR with the tile's sizes, the tile's chunks in its own order, MEND),
each is decoded by `mrsv decode --canonical` (chapter 5 only), and the samples
are put together by spec 11.4; lossless vectors are checked against the input
samples too. Region outputs (11.5) are crops of the whole. Invalid vectors are
valid ones edited chunk by chunk, checksums recomputed, each breaking one rule.

  python3 conformance/tiled_vectors.py --mrsv build/mrsv           write vectors/tiled_*/ and their manifest entries
  python3 conformance/tiled_vectors.py --mrsv build/mrsv --verify  recompute every tiled valid vector's expected
                                                                    outputs from its tiles and compare with the manifest
"""
import argparse
import hashlib
import json
import os
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from make_coded_vectors import Generator, crop, frame, offset_of, parse_chunks  # noqa: E402
from make_vectors import TILED_PREFIX, canonical, file_header, chunk, write_manifest, profile_of  # noqa: E402

SAMPLE = {1: ("uint8", 1), 2: ("int16", 2), 3: ("uint16", 2), 4: ("int32", 4), 5: ("float32", 4), 6: ("float64", 8)}


def round_order(counts):
    """spec 11.3: (tile, j) pairs in file order."""
    order, r = [], 0
    while True:
        row = [(t, r) for t, c in enumerate(counts) if c > r]
        if not row:
            return order
        order += row
        r += 1


def tiles_of(data):
    """The grid header fields, tiling, index and each tile's chunks (type, payload) of a tiled stream
    or prefix; `complete`: MEND follows every tile chunk."""
    chunks = parse_chunks(data)
    complete = bool(chunks) and chunks[-1][0] == "MEND"
    ghdr = chunks[0][1]
    num_dims, stype, coding, flags = ghdr[0], ghdr[1], ghdr[2], ghdr[3]
    size = struct.unpack_from("<3I", ghdr, 4)
    (nodata,) = struct.unpack_from("<Q", ghdr, 16)
    assert coding == 2
    i = next(k for k, (t, _) in enumerate(chunks) if t == "TINF")
    tile = struct.unpack_from("<3I", chunks[i][1], 0)
    count = [(size[a] + tile[a] - 1) // tile[a] for a in range(3)]
    n = count[0] * count[1] * count[2]
    counts = list(chunks[i + 1][1][:n])
    per_tile = [[] for _ in range(n)]
    rest = chunks[i + 2:]
    order = round_order(counts)
    for k, (t, _) in enumerate(order):
        if k >= len(rest) or rest[k][0] == "MEND":
            complete = False
            break
        per_tile[t].append(rest[k])
    return dict(num_dims=num_dims, stype=stype, flags=flags, size=size, nodata=nodata, tile=tile,
                count=count, per_tile=per_tile, complete=complete)


def tile_box(g, t):
    i = [t % g["count"][0], (t // g["count"][0]) % g["count"][1], t // (g["count"][0] * g["count"][1])]
    origin = [i[a] * g["tile"][a] for a in range(3)]
    return origin, [min(g["tile"][a], g["size"][a] - origin[a]) for a in range(3)]


def decode_tiles(mrsv, data, tmp):
    """spec 11.4 by way of chapter 5: the grid's samples, or None while some tile has none."""
    g = tiles_of(data)
    name, nbytes = SAMPLE[g["stype"]]
    out = bytearray(g["size"][0] * g["size"][1] * g["size"][2] * nbytes)
    for t, tile_chunks in enumerate(g["per_tile"]):
        origin, size = tile_box(g, t)
        header = bytes([g["num_dims"], g["stype"], 1, g["flags"]]) + struct.pack("<3IQ", *size, g["nodata"])
        stream = file_header() + chunk("GHDR", header) + b"".join(chunk(c, p) for c, p in tile_chunks)
        if g["complete"]:
            stream += chunk("MEND", b"")
        src, dst = os.path.join(tmp, "tile.mrsv"), os.path.join(tmp, "tile.canonical")
        open(src, "wb").write(stream)
        subprocess.run([mrsv, "decode", "--quiet", "--canonical", src, dst], check=True)
        canon = open(dst, "rb").read()
        line, samples = canon.split(b"\n", 1)
        if line.split()[7] == b"0":
            return g, None
        row = size[0] * nbytes
        for z in range(size[2]):
            for y in range(size[1]):
                at = (((origin[2] + z) * g["size"][1] + origin[1] + y) * g["size"][0] + origin[0]) * nbytes
                src_at = (z * size[1] + y) * row
                out[at:at + row] = samples[src_at:src_at + row]
    return g, bytes(out)


def canonical_of(g, samples, box=None):
    """spec 3.4 (11.4), or the canonical region output of 11.5 for `box` = (lo, hi)."""
    name, nbytes = SAMPLE[g["stype"]]
    dims = list(g["size"][:g["num_dims"]])
    nodata = g["nodata"] if g["flags"] & 1 else None
    if box is None:
        return canonical(name, dims, samples, nodata)
    lo, hi = box
    sub = None
    if samples is not None:
        sub = bytearray()
        for z in range(lo[2], hi[2]):
            for y in range(lo[1], hi[1]):
                at = ((z * g["size"][1] + y) * g["size"][0] + lo[0]) * nbytes
                sub += samples[at:at + (hi[0] - lo[0]) * nbytes]
        sub = bytes(sub)
    return canonical(name, [hi[a] - lo[a] for a in range(g["num_dims"])], sub, nodata)


def region_arg(lo, hi, dims):
    return ",".join(str(v) for v in list(lo[:dims]) + list(hi[:dims]))


def parse_region(text, dims):
    v = [int(x) for x in text.split(",")]
    lo, hi = v[:dims] + [0] * (3 - dims), v[dims:] + [1] * (3 - dims)
    return lo, hi


class TiledGenerator(Generator):
    def valid(self, name, data, description, rules, regions=(), samples=None):
        path = f"{TILED_PREFIX}valid/{name}.mrsv"
        self.files[path] = data
        g, decoded = decode_tiles(self.mrsv, data, self.tmp)
        if samples is not None:
            assert decoded == samples, f"{name}: the tiles do not decode to the input"
        output = canonical_of(g, decoded)
        assert output == self.reference_output(data), f"{name}: the reference decoder disagrees"
        entry = {"file": path, "valid": True, "sha256": hashlib.sha256(output).hexdigest(),
                 "output_bytes": len(output), "expected_by": "tiles decoded by chapter 5", "clause": "11",
                 "description": description, "profile": "grid", "rules": ["R1.6-1", "R1.6-3"] + rules}
        if regions:
            entry["regions"] = []
            for text in regions:
                out = canonical_of(g, decoded, parse_region(text, g["num_dims"]))
                entry["regions"].append({"region": text, "sha256": hashlib.sha256(out).hexdigest(),
                                         "output_bytes": len(out)})
        self.entries.append(entry)

    def invalid(self, name, chunks, error, error_name, offset, description, rules):
        path = f"{TILED_PREFIX}invalid/{name}.mrsv"
        self.files[path] = frame(chunks) if isinstance(chunks, list) else chunks
        self.entries.append({"file": path, "valid": False, "error": error, "error_name": error_name,
                             "offset": offset, "clause": "11", "description": description,
                             "profile": "grid", "rules": ["R1.6-2", "R1.6-3"] + rules})


def build(g):
    helens = open(os.path.join(HERE, "..", "demo", "data", "mt_st_helens_128x128_int16le.raw"), "rb").read()
    head = crop("ct_head_64x64x32_uint8.raw", (64, 64, 32), (0, 0, 0), (45, 38, 21), 1)
    h2, h3 = [128, 128], [45, 38, 21]
    lossless = ["--lossless"]
    regions2 = ["0,0,1,1", "17,40,90,41", "30,30,100,127", "0,0,128,128"]
    regions3 = ["3,4,5,40,30,19", "0,0,0,45,38,21"]

    # Valid streams: lossless with partial tiles, lossy by rate and by step,
    # error bounded, progressive, a volume, one tile, voids.
    t = g.encode(helens, "int16", h2, lossless + ["--tile", "48,40"])
    g.valid("terrain_tiles48x40_lossless", t, "a 128x128 terrain in 48x40 tiles (partial tiles on both axes), "
            "lossless", ["R3.1-3", "R11.1-1", "R11.1-2", "R11.1-3", "R11.1-4", "R11.1-5", "R11.2-1", "R11.2-2",
                         "R11.2-3", "R11.2-4", "R11.3-1", "R11.3-2", "R11.3-3", "R11.3-4", "R11.5-1"],
            regions=regions2, samples=helens)
    g.valid("terrain_tiles64_rate2", g.encode(helens, "int16", h2, ["--tile", "64", "--bits-per-sample", "2"]),
            "64x64 tiles at 2 bits per sample (one step for all tiles)", ["R11.5-1"], regions=regions2)
    g.valid("terrain_tiles32_step_progressive",
            g.encode(helens, "int16", h2, ["--tile", "32", "--step", "6", "--progressive", "--order", "2"]),
            "32x32 tiles, linear B-spline, step 6, full pyramid", ["R11.5-1"], regions=regions2)
    g.valid("terrain_tiles64_bound3", g.encode(helens, "int16", h2, ["--tile", "64", "--max-error", "3",
                                                                      "--bound-route", "residual"]),
            "64x64 tiles, every sample within 3 (bands and residual)", ["R11.5-1"], regions=regions2)
    g.valid("terrain_one_tile", g.encode(helens, "int16", h2, lossless + ["--tile", "1000"]),
            "a tile size beyond the grid: one tile", [], samples=helens)
    voids = bytearray(helens)
    for i in range(0, len(voids), 2 * 37):
        voids[i:i + 2] = struct.pack("<h", -32768)
    g.valid("terrain_tiles64_voids", g.encode(bytes(voids), "int16", h2, ["--tile", "64", "--max-error", "2"],
                                              nodata=-32768),
            "64x64 tiles with voids (a mask per tile), within 2", [], regions=regions2)
    g.valid("volume_bricks16_lossless", g.encode(head, "uint8", h3, lossless + ["--tile", "16,16,8"]),
            "a 45x38x21 CT crop in 16x16x8 bricks, lossless", ["R11.5-1"], regions=regions3, samples=head)
    g.valid("volume_bricks32_rate1", g.encode(head, "uint8", h3, ["--tile", "32,32,16", "--bits-per-sample", "1"]),
            "32x32x16 bricks at 1 bit per sample", ["R11.5-1"], regions=regions3)

    # Prefixes: after the index (no samples), after the first rounds.
    c = parse_chunks(t)
    g.valid("terrain_tiles_prefix_index", frame(c[:4]), "a prefix that ends after TIDX: a shape, no samples",
            ["R11.1-8"])
    n_tiles = 3 * 4
    g.valid("terrain_tiles_prefix_round1", frame(c[:4 + n_tiles + 5]),
            "a prefix ending inside round 1: some tiles have a band, so no samples yet", [])
    progressive = parse_chunks(g.encode(helens, "int16", h2, ["--tile", "64", "--bits-per-sample", "1",
                                                                "--progressive"]))
    g.valid("terrain_tiles_prefix_round2", frame(progressive[:4 + 4 * 2]),
            "a prefix of whole rounds: every tile's WHDR and scaling block", ["R11.1-8"], regions=regions2)

    # Invalid streams, one rule each.
    ghdr, meta, tinf, tidx = c[0], c[1], c[2], c[3]
    tiles = c[4:-1]
    p_tinf = offset_of(c, 2)
    p_tidx = offset_of(c, 3)
    q_tinf, q_tidx = p_tinf + 8, p_tidx + 8
    p_first = offset_of(c, 4)
    mend = ("MEND", b"")

    def tinf_with(**kw):
        v = list(struct.unpack("<4I", tinf[1]))
        for k, val in kw.items():
            v["xyzr".index(k)] = val
        return ("TINF", struct.pack("<4I", *v))

    g.invalid("coding3", [(ghdr[0], ghdr[1][:2] + b"\x03" + ghdr[1][3:]), mend], 202, "unsupported_coding",
              12 + 8 + 2, "coding 3 is not defined", ["R3.1-3"])
    g.invalid("band_before_tinf", [ghdr, meta, ("GBND", tiles[-1][1]), tinf, tidx] + tiles + [mend], 116,
              "chunk_order", p_tinf, "a GBND where TINF must come", ["R11.1-1"])
    g.invalid("meta_after_tinf", [ghdr, tinf, meta, tidx] + tiles + [mend], 116, "chunk_order",
              offset_of([ghdr, tinf], 2), "meta between TINF and TIDX", ["R11.1-2"])
    g.invalid("ancillary_among_tiles", [ghdr, meta, tinf, tidx] + tiles[:5] + [("zzzz", b"x")] + tiles[5:] + [mend],
              116, "chunk_order", offset_of(c, 9), "an ancillary chunk among the tile chunks", ["R11.1-3"])
    lengths = bytearray(tidx[1])
    struct.pack_into("<I", lengths, n_tiles + 4 * 0, struct.unpack_from("<I", tidx[1], n_tiles)[0] + 1)
    g.invalid("index_length_disagrees", [ghdr, meta, tinf, ("TIDX", bytes(lengths))] + tiles + [mend], 208,
              "bad_tile_index", p_first + 4, "TIDX gives tile 0's WHDR one byte more than it has", ["R11.1-4"])
    g.invalid("critical_after_tiles", [ghdr, meta, tinf, tidx] + tiles + [tiles[0], mend], 116, "chunk_order",
              offset_of(c, len(c) - 1), "a WHDR after the last tile chunk", ["R11.1-5"])
    g.invalid("no_tinf", [ghdr, meta, mend], 116, "chunk_order", offset_of(c, 2), "MEND with no TINF", ["R11.1-6"])
    g.invalid("no_tidx", [ghdr, meta, tinf, mend], 116, "chunk_order", offset_of(c, 3), "MEND right after TINF",
              ["R11.1-7"])
    g.invalid("tiles_missing", [ghdr, meta, tinf, tidx] + tiles[:-3] + [mend], 116, "chunk_order",
              offset_of(c, len(c) - 4), "MEND before the last three tile chunks", ["R11.1-8"])
    # Tile 11 (the last) loses its last chunk from the index and the stream:
    # its bands are short at MEND (5.1 rule 12).
    counts = bytearray(tidx[1][:n_tiles])
    per = [[] for _ in range(n_tiles)]
    pos = n_tiles
    for t_ in range(n_tiles):
        per[t_] = list(struct.unpack_from(f"<{counts[t_]}I", tidx[1], pos))
        pos += 4 * counts[t_]
    order = round_order(list(counts))
    last_k = max(k for k, (t_, j) in enumerate(order) if t_ == n_tiles - 1)
    counts[n_tiles - 1] -= 1
    per[n_tiles - 1].pop()
    short_index = bytes(counts) + b"".join(struct.pack(f"<{len(v)}I", *v) for v in per)
    short_tiles = tiles[:last_k] + tiles[last_k + 1:]
    short = [ghdr, meta, tinf, ("TIDX", short_index)] + short_tiles + [mend]
    g.invalid("tile_bands_short", short, 116, "chunk_order", offset_of(short, len(short) - 1),
              "the last tile's last band left out of TIDX and the stream: its bands are short at MEND", ["R11.1-9"])
    # Two failures: tile 0's first GBND (round 1) has a bad band_index, and a
    # later tile chunk disagrees with TIDX; the earlier one is reported.
    k_band = n_tiles  # round 1 starts with tile 0
    bad_band = bytearray(tiles[k_band][1])
    bad_band[0] ^= 1
    lengths = bytearray(tidx[1])
    last_entry = len(lengths) - 4
    struct.pack_into("<I", lengths, last_entry, struct.unpack_from("<I", tidx[1], last_entry)[0] + 1)
    two = [ghdr, meta, tinf, ("TIDX", bytes(lengths))] + tiles[:k_band] + [(tiles[k_band][0], bytes(bad_band))] + \
        tiles[k_band + 1:] + [mend]
    g.invalid("first_failure_in_file_order", two, 205, "bad_band_header", offset_of(two, 4 + k_band) + 8,
              "a bad band_index in round 1 and a TIDX length mismatch later: the earlier is reported",
              ["R11.1-10", "R11.1-12"])

    g.invalid("tinf_length", [ghdr, meta, ("TINF", tinf[1] + b"\0"), tidx] + tiles + [mend], 117,
              "bad_chunk_length", p_tinf + 4, "TINF of 17 bytes", ["R11.2-1", "R11.1-11"])
    g.invalid("tile_size_zero", [ghdr, meta, tinf_with(y=0), tidx] + tiles + [mend], 207, "bad_tiling",
              q_tinf + 4, "tile_size_y 0", ["R11.2-2"])
    g.invalid("tile_size_z_in_2d", [ghdr, meta, tinf_with(z=2), tidx] + tiles + [mend], 207, "bad_tiling",
              q_tinf + 8, "tile_size_z 2 in a 2-D grid", ["R11.2-2"])
    g.invalid("tinf_reserved", [ghdr, meta, tinf_with(r=1), tidx] + tiles + [mend], 105, "reserved_nonzero",
              q_tinf + 12, "TINF.reserved 1", ["R11.2-3"])
    big = bytes([2, 1, 2, 0]) + struct.pack("<3IQ", 1100, 1000, 1, 0)
    g.invalid("too_many_tiles", [("GHDR", big), ("TINF", struct.pack("<4I", 1, 1, 1, 0)), mend], 207, "bad_tiling",
              offset_of([("GHDR", big)], 1) + 8, "1,100,000 tiles of one sample", ["R11.2-4"])
    g.invalid("tidx_too_short", [ghdr, meta, tinf, ("TIDX", tidx[1][:n_tiles - 1])] + tiles + [mend], 208,
              "bad_tile_index", p_tidx + 4, "TIDX shorter than one byte per tile", ["R11.3-1"])
    zero = bytearray(tidx[1])
    zero[5] = 0
    g.invalid("tile_without_chunks", [ghdr, meta, tinf, ("TIDX", bytes(zero))] + tiles + [mend], 208,
              "bad_tile_index", q_tidx + 5, "tile 5 with a chunk count of 0", ["R11.3-2"])
    g.invalid("tidx_length", [ghdr, meta, tinf, ("TIDX", tidx[1] + b"\0\0\0\0")] + tiles + [mend], 208,
              "bad_tile_index", p_tidx + 4, "TIDX with four bytes too many", ["R11.3-3", "R11.1-11"])
    huge = bytearray(tidx[1])
    struct.pack_into("<I", huge, n_tiles + 4, (1 << 30) + 1)
    g.invalid("tile_chunk_too_long", [ghdr, meta, tinf, ("TIDX", bytes(huge))] + tiles + [mend], 208,
              "bad_tile_index", q_tidx + n_tiles + 4, "a listed length of 2^30 + 1", ["R11.3-4"])
    # Truncated: the file ends inside a tile chunk (2.3).
    g.invalid("truncated_in_tile_chunk", t[:offset_of(c, 20) + 30], 111, "chunk_past_end",
              offset_of(c, 20) + 4, "the file ends inside a tile chunk", [])


def verify(mrsv):
    """Recomputes the expected outputs of every tiled valid vector from its tiles."""
    manifest = json.load(open(os.path.join(HERE, "manifest.json"), encoding="utf-8"))
    bad, n = 0, 0
    with tempfile.TemporaryDirectory(prefix="mrsv-tiled-") as tmp:
        for e in manifest["vectors"]:
            if not (e["file"].startswith(TILED_PREFIX) and e["valid"]):
                continue
            n += 1
            data = open(os.path.join(HERE, e["file"]), "rb").read()
            g, samples = decode_tiles(mrsv, data, tmp)
            outputs = [(canonical_of(g, samples), e["sha256"], "whole")]
            for r in e.get("regions", []):
                outputs.append((canonical_of(g, samples, parse_region(r["region"], g["num_dims"])), r["sha256"],
                                "region " + r["region"]))
            for out, expected, what in outputs:
                if hashlib.sha256(out).hexdigest() != expected:
                    print(f"FAIL {e['file']} {what}: the tiles decode to another output")
                    bad += 1
    print(f"tiled_vectors: {n} valid tiled vectors, {bad} disagreements")
    return 1 if bad or n == 0 else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mrsv", default=os.path.join(HERE, "..", "build", "mrsv"))
    parser.add_argument("--verify", action="store_true")
    args = parser.parse_args()
    mrsv = os.path.abspath(args.mrsv)
    if args.verify:
        return verify(mrsv)
    with tempfile.TemporaryDirectory(prefix="mrsv-tiled-") as tmp:
        g = TiledGenerator(mrsv, tmp)
        build(g)
    names = [e["file"] for e in g.entries]
    assert len(names) == len(set(names)), "duplicate vector names"
    for sub in ("valid", "invalid"):
        d = os.path.join(HERE, "vectors", "tiled_" + sub)
        os.makedirs(d, exist_ok=True)
        for n in os.listdir(d):
            os.remove(os.path.join(d, n))
    for path, data in g.files.items():
        open(os.path.join(HERE, path), "wb").write(data)
    manifest = os.path.join(HERE, "manifest.json")
    kept = [e for e in json.load(open(manifest, encoding="utf-8"))["vectors"] if not e["file"].startswith(TILED_PREFIX)]
    for e in g.entries:
        assert profile_of(g.files[e["file"]]) == "grid"
    open(manifest, "wb").write(write_manifest(kept + g.entries))
    print(f"tiled_vectors: wrote {len(g.entries)} tiled vectors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
