#!/usr/bin/env python3
"""Generates the conformance vectors of wavelet-coded grids (spec 4 and 5).

Valid vectors are written by the reference encoder (`mrsv encode`) from the
real crops in demo/data and small synthetic grids. Their expected output is:
  - for lossless vectors, the canonical output of the input samples, computed
    here (independent of any decoder);
  - otherwise the canonical output of the reference decoder (`mrsv decode
    --canonical`), which pins the normative integer decoding process.
Invalid vectors are valid ones edited here, chunk by chunk, with their
checksums recomputed, so each breaks exactly one rule; the expected code and
offset are derived here from the layout.

  python3 conformance/make_coded_vectors.py --mrsv build/mrsv

It rewrites vectors/coded_valid/, vectors/coded_invalid/ and the coded entries
of manifest.json (make_vectors.py keeps them when it writes the container ones).
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
from make_vectors import CODED_PREFIX, canonical, chunk, file_header, with_rules, write_manifest  # noqa: E402
from mesh_vectors import build_mesh  # noqa: E402

CROPS = os.path.join(HERE, "..", "demo", "data")


def parse_chunks(data):
    """[(type, payload)] of a complete file; no validation (the inputs are ours)."""
    pos, out = 12, []
    while pos < len(data):
        ctype = data[pos:pos + 4].decode("ascii")
        (length,) = struct.unpack_from("<I", data, pos + 4)
        out.append((ctype, data[pos + 8:pos + 8 + length]))
        pos += 12 + length
    return out


def frame(chunks):
    return file_header() + b"".join(chunk(t, p) for t, p in chunks)


def offset_of(chunks, index):
    """Offset of chunk `index` in the framed file."""
    return 12 + sum(12 + len(p) for _, p in chunks[:index])


def find(chunks, ctype, nth=0):
    hits = [i for i, (t, _) in enumerate(chunks) if t == ctype]
    return hits[nth]


def crop(name, src, origin, size, nbytes):
    data = open(os.path.join(CROPS, name), "rb").read()
    out = bytearray()
    for z in range(origin[2], origin[2] + size[2]):
        for y in range(origin[1], origin[1] + size[1]):
            start = ((z * src[1] + y) * src[0] + origin[0]) * nbytes
            out += data[start:start + size[0] * nbytes]
    return bytes(out)


SAMPLE_BYTES = {"uint8": 1, "int16": 2, "uint16": 2, "int32": 4, "float32": 4, "float64": 8}


def region_of(output, text):
    """The canonical region output (spec 11.5) of box `text`, cut from a whole
    canonical grid output (3.4)."""
    line, _, samples = output.partition(b"\n")
    f = line.decode("ascii").split()
    stype, dims, size, count, nodata = f[2], int(f[3]), [int(v) for v in f[4:7]], int(f[7]), f[8]
    v = [int(x) for x in text.split(",")]
    lo, hi = v[:dims] + [0] * (3 - dims), v[dims:] + [1] * (3 - dims)
    sub = bytearray()
    nbytes = SAMPLE_BYTES[stype]
    if count:
        for z in range(lo[2], hi[2]):
            for y in range(lo[1], hi[1]):
                at = ((z * size[1] + y) * size[0] + lo[0]) * nbytes
                sub += samples[at:at + (hi[0] - lo[0]) * nbytes]
    sizes = [hi[a] - lo[a] for a in range(3)]
    n = sizes[0] * sizes[1] * sizes[2] if count else 0
    head = f"mrsv-canonical-grid 1 {stype} {dims} {sizes[0]} {sizes[1]} {sizes[2]} {n} {nodata}\n"
    return head.encode("ascii") + bytes(sub)


class Generator:
    def __init__(self, mrsv, tmp):
        self.mrsv, self.tmp = mrsv, tmp
        self.files, self.entries = {}, []

    def encode(self, samples, stype, dims, options, nodata=None):
        src = os.path.join(self.tmp, "in.raw")
        out = os.path.join(self.tmp, "out.mrsv")
        with open(src, "wb") as f:
            f.write(samples)
        cmd = [self.mrsv, "encode", "--quiet", "--dims", ",".join(map(str, dims)), "--type", stype]
        if nodata is not None:
            cmd += ["--nodata", str(nodata)]
        subprocess.run(cmd + options + [src, out], check=True)
        return open(out, "rb").read()

    def encode_file(self, path, options):
        out = os.path.join(self.tmp, "out.mrsv")
        subprocess.run([self.mrsv, "encode", "--quiet"] + options + [path, out], check=True)
        return open(out, "rb").read()

    def reference_output(self, data, options=()):
        src = os.path.join(self.tmp, "v.mrsv")
        out = os.path.join(self.tmp, "v.canonical")
        with open(src, "wb") as f:
            f.write(data)
        subprocess.run([self.mrsv, "decode", "--quiet", "--canonical", *options, src, out], check=True)
        return open(out, "rb").read()

    def valid(self, name, data, clause, description, expected=None, levels=(), regions=()):
        """`levels`: vertex counts of mesh levels whose outputs the manifest lists (spec 6.8);
        `regions`: boxes (X0,Y0[,Z0],X1,Y1[,Z1]) whose canonical region outputs (11.5) it
        lists, cut here from the whole output."""
        path = f"{CODED_PREFIX}valid/{name}.mrsv"
        self.files[path] = data
        by = "construction" if expected is not None else "reference decoder"
        output = expected if expected is not None else self.reference_output(data)
        entry = {"file": path, "valid": True, "sha256": hashlib.sha256(output).hexdigest(),
                 "output_bytes": len(output), "expected_by": by, "clause": clause, "description": description}
        if regions:
            entry["regions"] = []
            for text in regions:
                out = region_of(output, text)
                entry["regions"].append({"region": text, "sha256": hashlib.sha256(out).hexdigest(),
                                         "output_bytes": len(out)})
        if levels:
            entry["levels"] = []
            for n in levels:
                out = self.reference_output(data, ["--vertices", str(n)])
                entry["levels"].append({"vertices": n, "sha256": hashlib.sha256(out).hexdigest(),
                                        "output_bytes": len(out)})
        self.entries.append(entry)

    def invalid(self, name, chunks, error, error_name, offset, clause, description):
        path = f"{CODED_PREFIX}invalid/{name}.mrsv"
        self.files[path] = frame(chunks) if isinstance(chunks, list) else chunks
        self.entries.append({"file": path, "valid": False, "error": error, "error_name": error_name,
                             "offset": offset, "clause": clause, "description": description})


def build(g):
    helens = crop("mt_st_helens_128x128_int16le.raw", (128, 128, 1), (20, 30, 0), (61, 45, 1), 2)
    fuji = crop("mt_fuji_summit_128x128_int16le.raw", (128, 128, 1), (40, 40, 0), (53, 47, 1), 2)
    head = crop("ct_head_64x64x32_uint8.raw", (64, 64, 32), (10, 12, 4), (37, 29, 19), 1)
    headsq = crop("ct_headsq_16x16x8_uint16le.raw", (16, 16, 8), (0, 0, 0), (16, 16, 8), 2)
    h2 = [61, 45]
    h3 = [37, 29, 19]

    # Every order, lossless (expected output by construction) and lossy.
    for order in (1, 2, 3, 4):
        g.valid(f"terrain_order{order}_lossless",
                g.encode(helens, "int16", h2, ["--order", str(order), "--lossless", "--bound-route", "residual"]),
                "4, 5", f"a terrain window, order {order}, lossless (bands + residual)",
                expected=canonical("int16", h2, helens))
        g.valid(f"terrain_order{order}_step",
                g.encode(helens, "int16", h2, ["--order", str(order), "--step", "7"]),
                "4, 5", f"a terrain window, order {order}, lossy with step 7 (no residual)")
        g.valid(f"volume_order{order}_rate",
                g.encode(head, "uint8", h3, ["--order", str(order), "--progressive", "--bits-per-sample", "1.5"]),
                "4, 5", f"a CT block (3-D uint8), order {order}, about 1.5 bits per sample")
    # The CDF 9/7 wavelet (4.11), the default: lossless, a step, a rate, odd sizes.
    g.valid("terrain_cdf97_lossless",
            g.encode(helens, "int16", h2, ["--wavelet", "cdf97", "--lossless", "--bound-route", "residual"]),
            "4.11, 5", "a terrain window, CDF 9/7, lossless (bands + residual)",
            expected=canonical("int16", h2, helens))
    g.valid("terrain_cdf97_step", g.encode(helens, "int16", h2, ["--wavelet", "cdf97", "--step", "7"]),
            "4.11, 5", "a terrain window, CDF 9/7, lossy with step 7 (no residual)")
    g.valid("volume_cdf97_rate",
            g.encode(head, "uint8", h3, ["--wavelet", "cdf97", "--progressive", "--bits-per-sample", "1.5"]),
            "4.11, 5", "a CT block (3-D uint8), CDF 9/7, about 1.5 bits per sample")
    g.valid("terrain_cdf97_odd_sizes",
            g.encode(helens[:2 * 61 * 17], "int16", [61, 17], ["--wavelet", "cdf97", "--step", "3"]),
            "4.11", "a 61 x 17 window, CDF 9/7: levels 3 and 1, odd lengths at most levels")
    # The baseline entropy mode (5.10).
    g.valid("terrain_baseline_lossless",
            g.encode(helens, "int16", h2, ["--entropy", "baseline", "--lossless", "--bound-route", "residual"]),
            "5.10", "a terrain window, baseline entropy mode, lossless (bands + residual)",
            expected=canonical("int16", h2, helens))
    g.valid("volume_baseline_rate",
            g.encode(head, "uint8", h3, ["--entropy", "baseline", "--progressive", "--bits-per-sample", "1.5"]),
            "5.10", "a CT block, baseline entropy mode, about 1.5 bits per sample")
    g.valid("terrain_baseline_nodata_predictive",
            g.encode(fuji, "int16", [53, 47], ["--entropy", "baseline", "--max-error", "2",
                                                 "--bound-route", "predictive"], nodata=-32768),
            "5.10", "SRTM window with voids, baseline mode: mask, predicted samples with step 5")
    # Error bound and voids.
    g.valid("terrain_nodata_max_error4",
            g.encode(fuji, "int16", [53, 47], ["--max-error", "4", "--bound-route", "residual"], nodata=-32768),
            "5.5, 5.8.2", "SRTM window with voids: no-data mask, residual with step 9")
    # A void rectangle over whole 8 x 8 blocks of the residual and of the predicted
    # samples: blocks whose every position is skipped still code their flag (5.7.2).
    holed = bytearray(helens)
    for y in range(8, 32):
        for x in range(16, 40):
            struct.pack_into("<h", holed, 2 * (y * h2[0] + x), -32768)
    holed = bytes(holed)
    g.valid("terrain_void_blocks_max_error4",
            g.encode(holed, "int16", h2, ["--max-error", "4", "--bound-route", "residual"], nodata=-32768),
            "5.7.2, 5.8", "St Helens with a 24 x 24 void: whole blocks of the residual skipped")
    g.valid("terrain_void_blocks_predictive_lossless",
            g.encode(holed, "int16", h2, ["--lossless", "--bound-route", "predictive", "--prediction", "neighbour"],
                     nodata=-32768),
            "5.7.2, 5.7.4", "the same, lossless with neighbour prediction: whole predicted blocks skipped",
            expected=canonical("int16", h2, holed, nodata_bits=0x8000))
    g.valid("terrain_nodata_predictive_max_error4",
            g.encode(fuji, "int16", [53, 47], ["--max-error", "4", "--bound-route", "predictive"], nodata=-32768),
            "5.7.4, 5.8.2", "SRTM window with voids: levels 0, samples quantised with step 9, predicted")
    g.valid("terrain_nodata_lossless",
            g.encode(fuji, "int16", [53, 47], ["--lossless", "--bound-route", "predictive"], nodata=-32768),
            "5.5, 5.8.2", "SRTM window with voids, lossless",
            expected=canonical("int16", [53, 47], fuji, nodata_bits=0x8000))
    g.valid("volume_uint16_lossless", g.encode(headsq, "uint16", [16, 16, 8], ["--lossless"]),
            "5", "12-bit CT block (uint16), lossless",
            expected=canonical("uint16", [16, 16, 8], headsq))
    # Weighted prediction (5.7.5) in 1, 2 and 3 dimensions, and on a coarsest block.
    g.valid("terrain_weighted_lossless",
            g.encode(helens, "int16", h2, ["--lossless", "--bound-route", "predictive", "--prediction", "weighted"]),
            "5.7.5", "a terrain window, lossless, samples coded with weighted prediction",
            expected=canonical("int16", h2, helens))
    g.valid("terrain_nodata_weighted_max_error1",
            g.encode(fuji, "int16", [53, 47], ["--max-error", "1", "--bound-route", "predictive",
                                                 "--prediction", "weighted"], nodata=-32768),
            "5.7.5, 5.8.2", "SRTM window with voids: step 3, weighted prediction, voids at their prediction")
    g.valid("volume_weighted_lossless",
            g.encode(headsq, "uint16", [16, 16, 8], ["--lossless", "--bound-route", "predictive",
                                                      "--prediction", "weighted"]),
            "5.7.5", "12-bit CT block, lossless, each slice with weighted prediction",
            expected=canonical("uint16", [16, 16, 8], headsq))
    g.valid("terrain_weighted_step",
            g.encode(helens, "int16", h2, ["--order", "2", "--step", "3", "--prediction", "weighted"]),
            "5.7.5", "a terrain window, step 3, coarsest block with weighted prediction")
    # Sample types: 1-D int32, 2-D float32 and 3-D float64 (lossy: floats have no residual).
    line = [int(50000 * ((i / 40.0) ** 2) - 20000 + (i * 7919) % 300) for i in range(200)]
    ints = struct.pack("<200i", *line)
    g.valid("line_int32_lossless", g.encode(ints, "int32", [200], ["--lossless"]), "5",
            "a 1-D int32 line, lossless", expected=canonical("int32", [200], ints))
    g.valid("line_int32_weighted_lossless",
            g.encode(ints, "int32", [200], ["--lossless", "--bound-route", "predictive", "--prediction", "weighted"]),
            "5.7.5", "a 1-D int32 line, lossless, weighted prediction", expected=canonical("int32", [200], ints))
    g.valid("line_int32_step", g.encode(ints, "int32", [200], ["--order", "2", "--step", "100"]), "5",
            "a 1-D int32 line, linear wavelets, step 100")
    # Residuals up to 2^31 in magnitude: escapes whose unary prefix passes 11 (the last
    # magnitude model) and whose bits below the leading one need two decode_direct groups.
    wide, x = [], 12345
    for _ in range(300):
        x = (x * 1103515245 + 12345) % (1 << 31)
        wide.append(x - (1 << 30) if x % 3 else (x % 64) - 32)
    wide_bytes = struct.pack("<300i", *wide)
    g.valid("line_int32_wide_lossless",
            g.encode(wide_bytes, "int32", [300], ["--lossless", "--bound-route", "predictive", "--prediction",
                                                  "neighbour"]),
            "5.7.3", "a 1-D int32 line of values up to 2^30, lossless with neighbour prediction: escapes "
            "with more than 11 prefix bits and more than 24 bits below the leading one",
            expected=canonical("int32", [300], wide_bytes))
    # A 3-D int32 block of full-range noise, quantised with step 1: symbols of the last
    # level far beyond 16 bits (a decoder that keeps them narrower must widen them).
    noise, x = [], 2024
    for _ in range(23 * 19 * 17):
        x = (x * 1103515245 + 12345) % (1 << 31)
        noise.append(x * 2 - (1 << 31))
    g.valid("volume_int32_noise_step1",
            g.encode(struct.pack("<%di" % len(noise), *noise), "int32", [23, 19, 17],
                     ["--progressive", "--step", "1"]),
            "4.11, 5.4", "3-D int32 noise of full range, CDF 9/7 with step 1: symbols up to about 2^31 "
            "in the bands of level 1")
    # One level, its coarse block (the whole low-pass block of level 1) with weighted
    # prediction: what the encoder's defaults pick for large CT volumes at 1 bit per sample.
    g.valid("volume_cdf97_one_level_weighted",
            g.encode(head, "uint8", h3, ["--progressive", "--levels", "1", "--prediction", "weighted",
                                         "--bits-per-sample", "1.5"]),
            "4.11, 5.7.5", "a CT block (3-D uint8), CDF 9/7, one level whose coarse block uses weighted "
            "prediction, about 1.5 bits per sample")
    vals = struct.unpack("<%dh" % (len(helens) // 2), helens)
    floats = struct.pack("<%df" % len(vals), *[v * 0.3048 + 0.125 for v in vals])
    g.valid("terrain_float32_psnr", g.encode(floats, "float32", h2, ["--psnr", "70"]), "5.8.2",
            "a terrain in feet as float32, PSNR 70 dB")
    hv = struct.unpack("<%dB" % len(head), head)
    doubles = struct.pack("<%dd" % len(hv), *[v / 255.0 - 0.5 for v in hv])
    g.valid("volume_float64_rate", g.encode(doubles, "float64", h3, ["--bits-per-sample", "3"]), "5.8.2",
            "a CT block as float64 in [-0.5, 0.5], 3 bits per sample")
    # Prefixes: after the first band, after half the bands, before GRES, before MEND.
    full = g.encode(helens, "int16", h2, ["--max-error", "1", "--bound-route", "residual"])
    chunks = parse_chunks(full)
    bands = [i for i, (t, _) in enumerate(chunks) if t == "GBND"]
    for label, upto in (("first_band", bands[0]), ("half_bands", bands[len(bands) // 2]),
                        ("all_bands", bands[-1])):
        g.valid(f"prefix_{label}", frame(chunks[:upto + 1]), "2.5.1, 5.1",
                f"a stream prefix cut after band {bands.index(upto) + 1} of {len(bands)}")
    g.valid("prefix_before_mend", frame(chunks[:-1]), "2.5.1, 5.1", "all chunks but MEND: residual applied")
    g.valid("complete_max_error1", full, "5", "the stream the prefixes come from")
    linear = parse_chunks(g.encode(helens, "int16", h2, ["--order", "2", "--max-error", "1", "--bound-route", "residual"]))
    linear_bands = [i for i, (t, _) in enumerate(linear) if t == "GBND"]
    g.valid("prefix_linear_half_bands", frame(linear[:linear_bands[len(linear_bands) // 2] + 1]), "2.5.1, 4.5, 5.1",
            "a prefix of a linear B-spline stream, cut after half its bands")

    # Precincts (5.7.6): every array (bands, mask, residual) in blocks coded apart,
    # with region outputs (a region decoder reads the blocks a box reaches).
    R2 = ["0,0,1,1", "17,20,40,21", "5,3,61,45", "30,10,45,44"]
    R2F = ["0,0,1,1", "20,10,40,30", "0,0,53,47"]
    R3 = ["3,4,5,20,20,9", "0,0,0,37,29,19", "36,28,18,37,29,19"]
    g.valid("terrain_precinct16_lossless",
            g.encode(helens, "int16", h2, ["--precinct", "16", "--lossless", "--bound-route", "residual"]),
            "5.7.6", "a terrain window in precincts of 16: bands and residual in blocks, lossless",
            expected=canonical("int16", h2, helens), regions=R2)
    g.valid("terrain_precinct16_weighted_lossless",
            g.encode(helens, "int16", h2, ["--precinct", "16", "--lossless", "--bound-route", "predictive",
                                           "--prediction", "weighted"]),
            "5.7.5, 5.7.6", "the samples in blocks of 16 x 16, each with weighted prediction of its own",
            expected=canonical("int16", h2, helens), regions=R2)
    g.valid("terrain_precinct16_nodata_neighbour",
            g.encode(fuji, "int16", [53, 47], ["--precinct", "16", "--max-error", "2", "--bound-route",
                                               "predictive", "--prediction", "neighbour"], nodata=-32768),
            "5.7.4, 5.7.6", "SRTM window with voids: mask in blocks, samples with step 5 predicted block by block",
            regions=R2F)
    g.valid("terrain_precinct32_nodata_max_error4",
            g.encode(fuji, "int16", [53, 47], ["--precinct", "32", "--max-error", "4", "--bound-route", "residual"],
                     nodata=-32768),
            "5.5, 5.7.6", "SRTM window with voids, precincts of 32: mask, bands and residual in blocks; "
            "coarse levels in blocks of 16", regions=R2F)
    g.valid("volume_precinct16_rate",
            g.encode(head, "uint8", h3, ["--precinct", "16", "--progressive", "--bits-per-sample", "1.5"]),
            "5.7.6", "a CT block (3-D uint8) in precincts of 16^3, about 1.5 bits per sample", regions=R3)
    g.valid("volume_precinct16_baseline_rate",
            g.encode(head, "uint8", h3, ["--precinct", "16", "--entropy", "baseline", "--progressive",
                                         "--bits-per-sample", "1.5"]),
            "5.7.6, 5.10", "the same in the baseline entropy mode", regions=R3)
    g.valid("terrain_precinct16_step",
            g.encode(helens, "int16", h2, ["--precinct", "16", "--step", "40"]),
            "5.7.6", "a terrain window, precincts of 16, step 40: blocks of all zeros have length 0", regions=R2)
    pre = parse_chunks(g.encode(helens, "int16", h2, ["--precinct", "16", "--max-error", "1",
                                                      "--bound-route", "residual"]))
    pre_bands = [i for i, (t, _) in enumerate(pre) if t == "GBND"]
    g.valid("precinct_prefix_half_bands", frame(pre[:pre_bands[len(pre_bands) // 2] + 1]), "2.5.1, 5.7.6",
            "a prefix of a stream in precincts of 16, cut after half its bands", regions=R2)

    def block_table(payload):
        """(n, lengths) of a blocked array: the first n whose lengths add up to the rest."""
        for n in range(1, len(payload) // 4 + 1):
            lengths = struct.unpack_from("<%dI" % n, payload, 0)
            if sum(lengths) == len(payload) - 4 * n:
                return n, list(lengths)
        raise ValueError("not a blocked array")

    def blocked(name, chunks_in, index, header, edit, err_at, description, clause="5.7.6"):
        """Edits the blocked array after `header` bytes of chunk `index`'s payload;
        edit(n, lengths, data) returns the new array and the error's offset in it."""
        c = list(chunks_in)
        t, p = c[index]
        n, lengths = block_table(p[header:])
        array, at = edit(n, lengths, bytearray(p[header:]))
        c[index] = (t, p[:header] + bytes(array))
        g.invalid(name, c, 206, "bad_entropy_payload", offset_of(c, index) + 8 + header + at, clause, description)

    def first_block(n, lengths):
        k = next(i for i, v in enumerate(lengths) if v > 0)
        return k, 4 * n + sum(lengths[:k])

    def short_table(n, lengths, a):
        return a[:4 * n - 2], 0

    def sum_off(n, lengths, a):
        struct.pack_into("<I", a, 0, lengths[0] + 1)
        return a, 0

    def block_first_byte(n, lengths, a):
        _, at = first_block(n, lengths)
        a[at] = 1
        return a, at

    def block_truncated(n, lengths, a):
        k, at = first_block(n, lengths)
        struct.pack_into("<I", a, 4 * k, lengths[k] - 1)
        del a[at + lengths[k] - 1]
        return a, at

    def block_extra_byte(n, lengths, a):
        k, at = first_block(n, lengths)
        struct.pack_into("<I", a, 4 * k, lengths[k] + 1)
        a.insert(at + lengths[k], 0x55)
        return a, at

    pb = [i for i in pre_bands if len(pre[i][1]) > 12][-1]  # the finest band with coded data
    blocked("precinct_table_short", pre, pb, 12, short_table, 0,
            "a band's coded data ends inside its table of block lengths")
    blocked("precinct_lengths_sum", pre, pb, 12, sum_off, 0,
            "the first block length is one more than its bytes: the lengths do not add up")
    blocked("precinct_block_first_byte", pre, pb, 12, block_first_byte, 0,
            "the first coded block of a band does not start with 0")
    blocked("precinct_block_truncated", pre, pb, 12, block_truncated, 0,
            "the first coded block of a band one byte short (its length too)")
    pmask = parse_chunks(g.encode(fuji, "int16", [53, 47], ["--precinct", "16", "--max-error", "4",
                                                            "--bound-route", "residual"], nodata=-32768))
    blocked("precinct_mask_lengths_sum", pmask, find(pmask, "GMSK"), 0, sum_off, 0,
            "GMSK in blocks whose lengths do not add up", clause="5.5, 5.7.6")
    blocked("precinct_residual_block_extra_byte", pmask, find(pmask, "GRES"), 4, block_extra_byte, 0,
            "a block of GRES with one byte left over (its length too)", clause="5.5, 5.7.6")

    # --- invalid: wavelet header (5.2) -----------------------------------------
    w = find(chunks, "WHDR")
    wpos = offset_of(chunks, w) + 8

    def whdr(name, at, value_bytes, error, error_name, err_at, description):
        c = list(chunks)
        p = bytearray(c[w][1])
        p[at:at + len(value_bytes)] = value_bytes
        c[w] = ("WHDR", bytes(p))
        g.invalid(name, c, error, error_name, wpos + err_at, "5.2", description)

    whdr("whdr_order_6", 0, b"\x06", 204, "bad_wavelet_header", 0, "order 6 (1-4 B-splines, 5 CDF 9/7)")
    whdr("whdr_levels_17", 1, b"\x11", 204, "bad_wavelet_header", 1, "17 levels on x")
    whdr("whdr_levels_beyond_dims", 3, b"\x01", 204, "bad_wavelet_header", 3, "levels on z of a 2-D grid")
    whdr("whdr_no_plan", 1, b"\x09", 204, "bad_wavelet_header", 1,
         "9 levels on a 61-sample axis of a 9/7 stream: level 9 would split 1 value")
    whdr("whdr_entropy_mode_2", 4, b"\x02", 202, "unsupported_coding", 4, "entropy_mode 2 (reserved)")
    whdr("whdr_frac_bits_25", 5, b"\x19", 204, "bad_wavelet_header", 5, "frac_bits 25")
    whdr("whdr_flags_reserved", 6, b"\x82", 105, "reserved_nonzero", 6, "a reserved bit of wavelet_flags")
    whdr("whdr_mask_without_nodata", 6, b"\x03", 204, "bad_wavelet_header", 6,
         "has_mask in a grid without a no-data value")
    whdr("whdr_scale_for_integers", 16, b"\x00\x00\x00\x00\x00\x00\xf0\x3f", 204, "bad_wavelet_header", 16,
         "value_scale 1.0 for integer samples")
    whdr("whdr_offset_too_large", 8, struct.pack("<q", (1 << 40) + 1), 204, "bad_wavelet_header", 8,
         "|value_offset| above 2^40")
    c = list(chunks)
    c[w] = ("WHDR", chunks[w][1][:23])
    g.invalid("whdr_wrong_length", c, 117, "bad_chunk_length", offset_of(c, w) + 4, "5.2", "WHDR of 23 bytes")

    # --- invalid: bands (5.3) and entropy payloads (5.6, 5.7) ------------------
    b0, b1 = bands[0], bands[1]

    def band(name, index, edit, error, error_name, err_at, description, clause="5.3"):
        c = list(chunks)
        p = bytearray(c[index][1])
        edit(p)
        c[index] = ("GBND", bytes(p))
        g.invalid(name, c, error, error_name, offset_of(c, index) + 8 + err_at, clause, description)

    band("band_index_skipped", b1, lambda p: p.__setitem__(0, 2), 205, "bad_band_header", 0,
         "the second GBND says band 2")
    band("band_step_too_large", b0, lambda p: p.__setitem__(slice(4, 12), struct.pack("<Q", 1 << 35)),
         205, "bad_band_header", 4, "step 2^35")
    band("band_step_zero_with_data", b0, lambda p: p.__setitem__(slice(4, 12), bytes(8)), 205,
         "bad_band_header", 4, "step 0 but coded data follows")
    band("band_flags_reserved", b0, lambda p: p.__setitem__(2, p[2] | 0x80), 105, "reserved_nonzero", 2,
         "a reserved bit of band_flags")
    band("band_prediction_3", b0, lambda p: p.__setitem__(2, 3), 205, "bad_band_header", 2,
         "prediction 3 (reserved)")
    band("band_reserved", b0, lambda p: p.__setitem__(3, 1), 105, "reserved_nonzero", 3, "reserved byte 1")
    band("entropy_first_byte", b0, lambda p: p.__setitem__(12, 1), 206, "bad_entropy_payload", 12,
         "coded data that does not start with 0", clause="5.6")
    band("entropy_truncated", b0, lambda p: p.__delitem__(slice(len(p) - 1, len(p))), 206,
         "bad_entropy_payload", 12, "coded data one byte short", clause="5.6")
    band("entropy_extra_byte", b0, lambda p: p.append(0x55), 206, "bad_entropy_payload", 12,
         "one byte of coded data left over", clause="5.6")
    c = list(chunks)
    c[b0] = ("GBND", chunks[b0][1][:11])
    g.invalid("band_short_payload", c, 117, "bad_chunk_length", offset_of(c, b0) + 4, "5.3",
              "GBND payload of 11 bytes")

    base = parse_chunks(g.encode(helens, "int16", h2, ["--entropy", "baseline", "--lossless",
                                                        "--bound-route", "predictive"]))
    bb = find(base, "GBND")
    c = list(base)
    c[bb] = ("GBND", base[bb][1][:2] + b"\x02" + base[bb][1][3:])
    g.invalid("band_weighted_in_baseline", c, 205, "bad_band_header", offset_of(c, bb) + 10, "5.3",
              "prediction 2 (weighted) in the baseline entropy mode")

    # --- invalid: chunk order (5.1) ------------------------------------------
    r = find(chunks, "GRES")
    c = chunks[:w] + [chunks[b0], chunks[w]] + chunks[w + 1:b0] + chunks[b0 + 1:]
    g.invalid("band_before_whdr", c, 116, "chunk_order", offset_of(c, w), "5.1", "GBND before WHDR")
    c = chunks[:w + 1] + [chunks[w]] + chunks[w + 1:]
    g.invalid("two_whdr", c, 116, "chunk_order", offset_of(c, w + 1), "5.1", "a second WHDR")
    lossy = parse_chunks(g.encode(helens, "int16", h2, ["--step", "7"]))
    last = [i for i, (t, _) in enumerate(lossy) if t == "GBND"][-1]
    c = lossy[:last] + lossy[last + 1:]
    g.invalid("missing_band", c, 116, "chunk_order", offset_of(c, len(c) - 1), "5.1",
              "the last band is missing at MEND")
    c = chunks[:r] + chunks[r + 1:]
    g.invalid("missing_residual", c, 116, "chunk_order", offset_of(c, len(c) - 1), "5.1",
              "has_residual is set but there is no GRES")
    c = chunks[:b1] + [chunks[r]] + chunks[b1:r] + chunks[r + 1:]
    g.invalid("residual_before_last_band", c, 116, "chunk_order", offset_of(c, b1), "5.1",
              "GRES before the last band")
    c = chunks[:r] + [("GRAW", b"\0" * 4)] + chunks[r:]
    g.invalid("graw_in_wavelet_grid", c, 116, "chunk_order", offset_of(c, r), "5.1",
              "a GRAW chunk in a wavelet-coded grid")
    c = list(chunks)
    c[r] = ("GRES", struct.pack("<I", 0) + chunks[r][1][4:])
    g.invalid("residual_step_zero", c, 204, "bad_wavelet_header", offset_of(c, r) + 8, "5.5",
              "residual_step 0")
    c = list(chunks)
    c[r] = ("GRES", struct.pack("<I", (1 << 20) + 1) + chunks[r][1][4:])
    g.invalid("residual_step_too_large", c, 204, "bad_wavelet_header", offset_of(c, r) + 8, "5.5",
              "residual_step 2^20 + 1")

    masked = parse_chunks(g.encode(fuji, "int16", [53, 47], ["--max-error", "4", "--bound-route", "residual"],
                                   nodata=-32768))
    m, mb = find(masked, "GMSK"), find(masked, "GBND")
    c = masked[:m] + masked[m + 1:mb + 1] + [masked[m]] + masked[mb + 1:]
    g.invalid("mask_after_band", c, 116, "chunk_order", offset_of(c, m), "5.1",
              "GBND before GMSK when has_mask is set")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mrsv", default=os.path.join(HERE, "..", "build", "mrsv"),
                        help="the reference tool (default build/mrsv)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="mrsv-coded-") as tmp:
        g = Generator(os.path.abspath(args.mrsv), tmp)
        build(g)
        build_mesh(g, parse_chunks, frame, offset_of, find)
    names = [e["file"] for e in g.entries]
    assert len(names) == len(set(names)), "duplicate vector names"
    for sub in ("valid", "invalid"):
        d = os.path.join(HERE, "vectors", "coded_" + sub)
        os.makedirs(d, exist_ok=True)
        for n in os.listdir(d):
            os.remove(os.path.join(d, n))
    for path, data in g.files.items():
        with open(os.path.join(HERE, path), "wb") as f:
            f.write(data)
    manifest = os.path.join(HERE, "manifest.json")
    with open(manifest, encoding="utf-8") as f:
        kept = [e for e in json.load(f)["vectors"] if not e["file"].startswith(CODED_PREFIX)]
    with open(manifest, "wb") as f:
        f.write(write_manifest(kept + [with_rules(e, g.files[e["file"]]) for e in g.entries]))
    print(f"make_coded_vectors: wrote {len(g.entries)} coded vectors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
