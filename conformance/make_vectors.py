#!/usr/bin/env python3
"""Generates the MRSV conformance vectors and conformance/manifest.json.

This is a second, independent writer of the format: it is built from spec/
alone and shares no code with the reference encoder, so a vector that the
reference decoder accepts and hashes as expected checks both against the text.
Expected outputs are computed here from the samples put in, never by running
a decoder.

  python3 conformance/make_vectors.py           write vectors/ and manifest.json
  python3 conformance/make_vectors.py --check   fail if the committed files differ
"""
import argparse
import array
import hashlib
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from hand_vectors import build_hand  # noqa: E402
from vector_rules import rules_of  # noqa: E402

CROPS = os.path.join(HERE, "..", "demo", "data")

# spec 2.2
SIGNATURE = bytes([0x8E, 0x4D, 0x52, 0x53, 0x56, 0x0D, 0x0A, 0x1A, 0x0A])
VERSION = (0, 1)

# spec 3.1 sample_type: code, struct format, size
SAMPLE_TYPES = {
    "uint8": (1, "B", 1),
    "int16": (2, "h", 2),
    "uint16": (3, "H", 2),
    "int32": (4, "i", 4),
    "float32": (5, "f", 4),
    "float64": (6, "d", 8),
}


def _crc_table():
    table = []
    for i in range(256):
        c = i
        for _ in range(8):
            c = (c >> 1) ^ (0x82F63B78 if c & 1 else 0)
        table.append(c)
    return table


_CRC_TABLE = _crc_table()


def crc32c(data):
    """spec 2.3: CRC-32C, reflected, initial and final value all ones."""
    crc = 0xFFFFFFFF
    for b in data:
        crc = (crc >> 8) ^ _CRC_TABLE[(crc ^ b) & 0xFF]
    return crc ^ 0xFFFFFFFF


assert crc32c(b"123456789") == 0xE3069283


def file_header(major=VERSION[0], minor=VERSION[1], flags=0):
    return SIGNATURE + bytes([major, minor, flags])


def chunk(ctype, payload, length=None, crc=None):
    """spec 2.3 chunk(); `length` and `crc` override the true values for invalid vectors."""
    head = ctype.encode("ascii") + struct.pack("<I", len(payload) if length is None else length)
    if crc is None:
        crc = crc32c(head + payload)
    return head + payload + struct.pack("<I", crc)


MEND = chunk("MEND", b"")


def ghdr(stype, dims, nodata_bits=None, num_dims=None, coding=0, flags=None, raw_type=None):
    """spec 3.1 grid_header()."""
    sizes = list(dims) + [1] * (3 - len(dims))
    if flags is None:
        flags = 1 if nodata_bits is not None else 0
    return struct.pack("<BBBBIIIQ", len(dims) if num_dims is None else num_dims,
                       SAMPLE_TYPES[stype][0] if raw_type is None else raw_type,
                       coding, flags, sizes[0], sizes[1], sizes[2], nodata_bits or 0)


def meta(entries):
    """spec 2.6: key=value lines."""
    return "".join(f"{k}={v}\n" for k, v in entries).encode("utf-8")


def canonical(stype, dims, samples, nodata_bits=None):
    """spec 3.4 canonical output; `samples` is None for a prefix before GRAW."""
    sizes = list(dims) + [1] * (3 - len(dims))
    count = 0 if samples is None else sizes[0] * sizes[1] * sizes[2]
    nodata = "-" if nodata_bits is None else "%016x" % nodata_bits
    line = f"mrsv-canonical-grid 1 {stype} {len(dims)} {sizes[0]} {sizes[1]} {sizes[2]} {count} {nodata}\n"
    return line.encode("ascii") + (samples or b"")


CANONICAL_EMPTY = b"mrsv-canonical-empty 1\n"


def pack(stype, values):
    return struct.pack("<%d%s" % (len(values), SAMPLE_TYPES[stype][1]), *values)


def crop(name, src_dims, origin, size, sample_bytes):
    with open(os.path.join(CROPS, name), "rb") as f:
        data = f.read()
    out = bytearray()
    for z in range(origin[2], origin[2] + size[2]):
        for y in range(origin[1], origin[1] + size[1]):
            start = ((z * src_dims[1] + y) * src_dims[0] + origin[0]) * sample_bytes
            out += data[start:start + size[0] * sample_bytes]
    return bytes(out)


class Vectors:
    def __init__(self):
        self.files = {}     # relative path -> bytes
        self.entries = []   # manifest entries

    def valid(self, name, data, output, clause, description, levels=None):
        """`levels`: [(vertex count, canonical output)] of a mesh's levels (spec 6.8)."""
        path = f"vectors/valid/{name}.mrsv"
        self.files[path] = data
        entry = {"file": path, "valid": True, "sha256": hashlib.sha256(output).hexdigest(),
                 "output_bytes": len(output), "clause": clause, "description": description}
        if levels:
            entry["levels"] = [{"vertices": n, "sha256": hashlib.sha256(out).hexdigest(), "output_bytes": len(out)}
                               for n, out in levels]
        self.entries.append(entry)

    def invalid(self, name, data, error, error_name, offset, clause, description):
        path = f"vectors/invalid/{name}.mrsv"
        self.files[path] = data
        self.entries.append({"file": path, "valid": False, "error": error,
                             "error_name": error_name, "offset": offset, "clause": clause,
                             "description": description})


def build():
    v = Vectors()
    H = file_header()

    # --- valid -----------------------------------------------------------
    smallest = H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GRAW", b"\x2a") + MEND
    v.valid("smallest", smallest, canonical("uint8", [1], b"\x2a"), "2.2, 2.3, 3.1, 3.3",
            "the smallest complete file: a one-sample uint8 grid")

    v.valid("unknown_ancillary_skipped",
            H + chunk("GHDR", ghdr("uint8", [1])) + chunk("xtra", b"future data, skipped")
            + chunk("GRAW", b"\x2a") + chunk("zzzz", b"") + MEND,
            canonical("uint8", [1], b"\x2a"), "2.4",
            "two unknown ancillary chunks that a decoder must skip")

    helens_dims = [16, 12]
    helens = crop("mt_st_helens_128x128_int16le.raw", (128, 128, 1), (40, 60, 0), (16, 12, 1), 2)
    helens_meta = meta([
        ("value_units", "m"), ("spatial_units", "m"), ("spacing", "30,30"),
        ("origin", "560790,5115990"), ("crs", "EPSG:26910"),
        ("provenance", "USGS 7.5' DEM MSH-M80 (Mount St. Helens after 1980), crop of demo/data"),
        ("description", "Mount St. Helens \u2014 16\u00d712 window, elevation in metres"),
    ])
    helens_ghdr = chunk("GHDR", ghdr("int16", helens_dims))
    helens_file = H + helens_ghdr + chunk("meta", helens_meta) + chunk("GRAW", helens) + MEND
    v.valid("terrain_int16_metadata", helens_file, canonical("int16", helens_dims, helens),
            "2.6, 3.1, 3.3", "a real terrain window (int16) with a meta chunk of every registered key")

    fuji_dims = [24, 20]
    fuji = crop("mt_fuji_summit_128x128_int16le.raw", (128, 128, 1), (50, 54, 0), (24, 20, 1), 2)
    assert -32768 in array.array("h", fuji), "the Fuji window must hold voids"
    v.valid("terrain_int16_nodata",
            H + chunk("GHDR", ghdr("int16", fuji_dims, nodata_bits=0x8000)) + chunk("GRAW", fuji) + MEND,
            canonical("int16", fuji_dims, fuji, nodata_bits=0x8000), "3.1",
            "SRTM window at Mt. Fuji's summit with voids; nodata -32768 comes back exactly")

    head_dims = [8, 8, 8]
    head = crop("ct_head_64x64x32_uint8.raw", (64, 64, 32), (28, 28, 12), (8, 8, 8), 1)
    v.valid("volume_uint8",
            H + chunk("GHDR", ghdr("uint8", head_dims)) + chunk("GRAW", head) + MEND,
            canonical("uint8", head_dims, head), "3.1, 3.3", "a CT head block (uint8, 3-D)")

    sq_dims = [16, 16, 8]
    sq = crop("ct_headsq_16x16x8_uint16le.raw", (16, 16, 8), (0, 0, 0), (16, 16, 8), 2)
    v.valid("volume_uint16",
            H + chunk("GHDR", ghdr("uint16", sq_dims)) + chunk("meta", meta([("spacing", "3.2,3.2,1.5"), ("value_units", "HU+1024")]))
            + chunk("GRAW", sq) + MEND,
            canonical("uint16", sq_dims, sq), "3.1, 3.3", "a 12-bit CT block (uint16, 3-D)")

    ints = [-2147483648, -1, 0, 1, 2147483647, 123456789, -98765]
    v.valid("line_int32",
            H + chunk("GHDR", ghdr("int32", [len(ints)])) + chunk("GRAW", pack("int32", ints)) + MEND,
            canonical("int32", [len(ints)], pack("int32", ints)), "3.1",
            "a 1-D int32 grid with the extreme values")

    # Float samples are carried bit for bit: NaN payloads, -0 and infinities.
    nan_bits = struct.pack("<I", 0x7FC00001)
    floats = pack("float32", [0.0, -0.0, 1.5, -3.25e-38]) + nan_bits + pack("float32", [float("inf"), -float("inf"), 8848.86, 1e-45])
    v.valid("grid_float32_special",
            H + chunk("GHDR", ghdr("float32", [3, 3], nodata_bits=0x7FC00001)) + chunk("GRAW", floats) + MEND,
            canonical("float32", [3, 3], floats, nodata_bits=0x7FC00001), "3.1, 3.3",
            "float32 samples with -0, a NaN payload (also the nodata value), infinities and a subnormal")

    doubles = pack("float64", [0.1 * i - 0.35 for i in range(12)])
    v.valid("volume_float64",
            H + chunk("GHDR", ghdr("float64", [3, 2, 2])) + chunk("GRAW", doubles) + MEND,
            canonical("float64", [3, 2, 2], doubles), "3.1", "a 3-D float64 grid")

    v.valid("prefix_file_header_only", H, CANONICAL_EMPTY, "2.5",
            "a stream prefix cut right after the file header")
    v.valid("prefix_after_header", H + helens_ghdr, canonical("int16", helens_dims, None), "2.5",
            "a stream prefix cut after GHDR: the grid's shape, no samples")
    v.valid("prefix_after_meta", H + helens_ghdr + chunk("meta", helens_meta),
            canonical("int16", helens_dims, None), "2.5", "a stream prefix cut after the meta chunk")
    v.valid("prefix_before_mend", helens_file[:-len(MEND)], canonical("int16", helens_dims, helens),
            "2.5", "a stream prefix cut just before MEND: all samples")

    # --- invalid: file header (2.2) ------------------------------------------
    v.invalid("bad_signature", b"\x89PNG\r\n\x1a\n" + smallest[8:], 102, "bad_signature", 0, "2.2",
              "a PNG signature")
    v.invalid("signature_crlf_to_lf", smallest.replace(b"\r\n", b"\n", 1), 103,
              "signature_transfer_damage", 0, "2.2", "the signature's CR LF became LF (text-mode transfer)")
    v.invalid("signature_lf_to_crlf", SIGNATURE[:5] + b"\r\r\n\x1a\r\n" + smallest[9:], 103,
              "signature_transfer_damage", 0, "2.2", "every LF of the signature became CR LF")
    v.invalid("signature_high_bit_cleared", b"\x0e" + smallest[1:], 103, "signature_transfer_damage",
              0, "2.2", "the first byte lost its high bit (7-bit transfer)")
    v.invalid("truncated_file_header", smallest[:10], 101, "truncated_file_header", 10, "2.2",
              "the file ends inside the 12-byte file header")
    v.invalid("empty_file", b"", 101, "truncated_file_header", 0, "2.2", "a file of zero bytes")
    v.invalid("unsupported_version", file_header(major=1, minor=0) + smallest[12:], 104,
              "unsupported_version", 9, "2.2.1", "format version 1.0, not known to a 0.1 decoder")
    v.invalid("reserved_header_flags", file_header(flags=1) + smallest[12:], 105, "reserved_nonzero",
              11, "2.2", "header_flags is not 0")

    # --- invalid: chunk framing (2.3-2.5) -------------------------------------
    graw_at = 12 + 36
    v.invalid("truncated_chunk", smallest[:graw_at + 5], 110, "truncated_chunk_header", graw_at,
              "2.3", "the file ends five bytes into the GRAW chunk header")
    head_ghdr = chunk("GHDR", ghdr("uint8", head_dims))
    head_file = H + head_ghdr + chunk("GRAW", head) + MEND
    v.invalid("truncated_payload", head_file[:graw_at + 8 + 100], 111, "chunk_past_end", graw_at + 4,
              "2.3", "the file ends inside the GRAW payload")
    v.invalid("length_past_end", H + head_ghdr + chunk("GRAW", head, length=len(head) + 1000) + MEND,
              111, "chunk_past_end", graw_at + 4, "2.3", "chunk_length runs 1000 bytes past the end of the file")
    v.invalid("oversized_length", H + head_ghdr + chunk("GRAW", head, length=0xFFFFFFF0) + MEND,
              112, "oversized_chunk", graw_at + 4, "2.3, B.1", "chunk_length above the 2^30 limit")
    damaged = bytearray(head_file)
    damaged[graw_at + 8 + 77] ^= 0x10
    v.invalid("bad_checksum", bytes(damaged), 113, "checksum_mismatch", graw_at + 8 + len(head), "2.3",
              "one bit of a sample flipped: the CRC-32C does not match")
    v.invalid("bad_checksum_ancillary",
              H + chunk("GHDR", ghdr("uint8", [1])) + chunk("xtra", b"abc", crc=0) + chunk("GRAW", b"\x2a") + MEND,
              113, "checksum_mismatch", graw_at + 8 + 3, "2.3, 2.4",
              "a damaged unknown ancillary chunk is an error too (decision D3)")
    v.invalid("bad_chunk_type", H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GR4W", b"\x2a") + MEND,
              114, "bad_chunk_type", graw_at, "2.3", "chunk_type with a digit")
    v.invalid("unknown_critical_chunk",
              H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GZIP", b"") + chunk("GRAW", b"\x2a") + MEND,
              115, "unknown_critical_chunk", graw_at, "2.4", "a critical chunk type this version does not define")
    v.invalid("trailing_bytes", smallest + b"\n", 118, "trailing_bytes", len(smallest), "2.5",
              "one byte after MEND")
    v.invalid("mend_with_payload", H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GRAW", b"\x2a") + chunk("MEND", b"\0"),
              117, "bad_chunk_length", graw_at + 13 + 4, "2.5", "MEND with a one-byte payload")
    v.invalid("mend_only", H + MEND, 116, "chunk_order", 12, "2.5", "MEND with no content header")
    v.invalid("meta_before_header",
              H + chunk("meta", meta([("a", "1")])) + chunk("GHDR", ghdr("uint8", [1])) + chunk("GRAW", b"\x2a") + MEND,
              116, "chunk_order", 12, "2.5", "the first chunk is not the content header")
    v.invalid("two_headers",
              H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GHDR", ghdr("uint8", [1])) + chunk("GRAW", b"\x2a") + MEND,
              116, "chunk_order", graw_at, "2.5", "a second GHDR")
    two_meta = chunk("meta", meta([("a", "1")]))
    v.invalid("two_meta_chunks",
              H + chunk("GHDR", ghdr("uint8", [1])) + two_meta + two_meta + chunk("GRAW", b"\x2a") + MEND,
              116, "chunk_order", graw_at + len(two_meta), "2.5", "a second meta chunk")
    v.invalid("two_graw_chunks",
              H + chunk("GHDR", ghdr("uint8", [1])) + chunk("GRAW", b"\x2a") + chunk("GRAW", b"\x2a") + MEND,
              116, "chunk_order", graw_at + 13, "3.3", "a second GRAW chunk")
    v.invalid("missing_graw", H + chunk("GHDR", ghdr("uint8", [1])) + MEND, 116, "chunk_order",
              graw_at, "3.3", "a complete stored stream without its GRAW chunk")

    # --- invalid: grid header (3.1) and samples (3.3) -------------------------
    def header_case(name, payload, error, error_name, at, description, samples=b"\x2a"):
        v.invalid(name, H + chunk("GHDR", payload) + chunk("GRAW", samples) + MEND, error, error_name,
                  at, "3.1", description)

    header_case("ghdr_wrong_length", ghdr("uint8", [1])[:23], 117, "bad_chunk_length", 16,
                "GHDR payload of 23 bytes")
    header_case("num_dims_zero", ghdr("uint8", [1], num_dims=0), 201, "bad_grid_header", 20, "num_dims 0")
    header_case("num_dims_four", ghdr("uint8", [1], num_dims=4), 201, "bad_grid_header", 20, "num_dims 4")
    header_case("size_zero", ghdr("uint8", [4, 0]), 201, "bad_grid_header", 20, "size_y 0", samples=b"")
    header_case("size_beyond_num_dims", ghdr("uint8", [1, 1, 2], num_dims=2), 201, "bad_grid_header", 20,
                "a 2-D grid with size_z 2", samples=b"\0\0")
    header_case("axis_above_limit", ghdr("uint8", [(1 << 24) + 1]), 201, "bad_grid_header", 20,
                "size_x above 2^24")
    header_case("too_many_samples", ghdr("uint8", [1 << 24, 1 << 24]), 201, "bad_grid_header", 20,
                "2^48 samples, above the 2^32 limit")
    header_case("too_many_samples_3d", ghdr("uint8", [1 << 24, 1 << 24, 1 << 24]), 201, "bad_grid_header",
                20, "2^72 samples: the product must not wrap at 2^64")
    header_case("bad_sample_type", ghdr("uint8", [1], raw_type=9), 201, "bad_grid_header", 21,
                "sample_type 9")
    header_case("unsupported_coding", ghdr("uint8", [1], coding=7), 202, "unsupported_coding", 22,
                "coding 7")
    header_case("grid_flags_reserved", ghdr("uint8", [1], flags=0x80), 105, "reserved_nonzero", 23,
                "a reserved bit of grid_flags")
    header_case("nodata_without_flag", ghdr("uint8", [1], nodata_bits=5, flags=0), 201, "bad_grid_header",
                20, "nodata_bits set but has_nodata clear")
    header_case("nodata_above_sample_size", ghdr("uint8", [1], nodata_bits=0x1FF), 201, "bad_grid_header",
                20, "a uint8 nodata value with bits above bit 7")
    v.invalid("graw_size_mismatch", H + chunk("GHDR", ghdr("uint8", [4, 4])) + chunk("GRAW", bytes(15)) + MEND,
              203, "sample_data_mismatch", graw_at + 4, "3.3", "15 sample bytes for a 4x4 uint8 grid")

    # --- invalid: metadata (2.6) ----------------------------------------------
    meta_payload_at = graw_at + 8

    def meta_case(name, payload, at, description):
        v.invalid(name, H + chunk("GHDR", ghdr("uint8", [1])) + chunk("meta", payload) + chunk("GRAW", b"\x2a") + MEND,
                  130, "bad_metadata", meta_payload_at + at, "2.6", description)

    meta_case("meta_no_equals", b"units=m\nspacing\n", 8, "an entry without '='")
    meta_case("meta_duplicate_key", b"crs=EPSG:4326\ncrs=EPSG:32610\n", 14, "a key given twice")
    meta_case("meta_bad_utf8", b"description=caf\xe9\n", 0, "Latin-1 text, not UTF-8")
    meta_case("meta_unterminated", b"units=m", 0, "the last entry has no LF")
    meta_case("meta_bad_key", b"Units=m\n", 0, "a key with an upper-case letter")
    meta_case("meta_bad_spacing", b"spacing=30;30\n", 0, "spacing that is not a list of numbers")
    build_hand(v, H, chunk, ghdr, meta, canonical, MEND)
    return v


CODED_PREFIX = "vectors/coded_"
PT_PREFIX = "vectors/pt_"
RECONSTRUCT_PREFIX = "vectors/reconstruct/"
TILED_PREFIX = "vectors/tiled_"   # tiled_vectors.py
RECONSTRUCT3_PREFIXES = ("vectors/reconstruct3/", "vectors/quadtree/")   # reconstruct_vectors3.py


def coded_entries():
    """The manifest entries written by make_coded_vectors.py, pt_vectors.py and the
    reconstruct_vectors scripts, as committed."""
    path = os.path.join(HERE, "manifest.json")
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as f:
        return [e for e in json.load(f)["vectors"] if e["file"].startswith(
            (CODED_PREFIX, PT_PREFIX, RECONSTRUCT_PREFIX, TILED_PREFIX) + RECONSTRUCT3_PREFIXES)]


def profile_of(data):
    """spec 1.6: the profile named by the content header; "any" without one."""
    return {b"GHDR": "grid", b"PHDR": "mesh", b"THDR": "tet"}.get(data[12:16], "any")


def with_rules(entry, data):
    """The entry with its profile and the rule tags of vector_rules.py (spec README)."""
    name = os.path.splitext(os.path.basename(entry["file"]))[0]
    out = dict(entry)
    out["profile"] = profile_of(data)
    # tiled_vectors.py writes its vectors' tags itself.
    out["rules"] = entry["rules"] if entry["file"].startswith(TILED_PREFIX) else rules_of(name, entry["valid"])
    return out


def write_manifest(entries):
    lines = ["{",
             '  "format": "MRSV",',
             '  "version": "%d.%d",' % VERSION,
             '  "output_hash": "sha256 of the canonical output: spec 3.4 for grids, 6.8 for meshes (levels: '
             'each level of a mesh, by its vertex count)",',
             '  "vectors": [']
    for i, e in enumerate(entries):
        lines.append("    " + json.dumps(e, ensure_ascii=False) + ("," if i + 1 < len(entries) else ""))
    lines += ["  ]", "}"]
    return ("\n".join(lines) + "\n").encode("utf-8")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true",
                        help="compare with the committed files instead of writing")
    args = parser.parse_args()
    v = build()
    outputs = dict(v.files)
    # The coded and PT vectors (make_coded_vectors.py, pt_vectors.py) share the manifest: keep them.
    entries = [with_rules(e, v.files[e["file"]]) for e in v.entries] + \
        [with_rules(e, open(os.path.join(HERE, e["file"]), "rb").read()) for e in coded_entries()]
    outputs["manifest.json"] = write_manifest(entries)
    names = [e["file"] for e in v.entries]
    assert len(names) == len(set(names)), "duplicate vector names"
    if args.check:
        stale = []
        for path, data in outputs.items():
            full = os.path.join(HERE, path)
            if not os.path.exists(full) or open(full, "rb").read() != data:
                stale.append(path)
        on_disk = set()
        for sub in ("valid", "invalid"):
            d = os.path.join(HERE, "vectors", sub)
            if os.path.isdir(d):
                on_disk |= {f"vectors/{sub}/{n}" for n in os.listdir(d)}
        stale += sorted(on_disk - set(outputs))
        if stale:
            print("make_vectors: these differ from what the generator writes:", *stale, sep="\n  ")
            print("make_vectors: 0 passed, 1 failed")
            return 1
        print(f"make_vectors: {len(v.entries)} container vectors and the manifest match the generator")
        return 0
    for sub in ("valid", "invalid"):
        d = os.path.join(HERE, "vectors", sub)
        os.makedirs(d, exist_ok=True)
        for n in os.listdir(d):
            os.remove(os.path.join(d, n))
    for path, data in outputs.items():
        with open(os.path.join(HERE, path), "wb") as f:
            f.write(data)
    print(f"make_vectors: wrote {len(v.entries)} vectors and manifest.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
