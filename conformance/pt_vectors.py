#!/usr/bin/env python3
"""Generates the conformance vectors of PT streams (spec 7) and their manifest entries.

Sources. The PT streams with splits in vectors/pt_valid/pt_grid_*.mrsv,
pt_two_fields.mrsv and pt_no_fields.mrsv were written once by the reference encoder
(`mrsv tetrahedralize --ascii` of small random uint8 grids, 4x3x3, 6x5x4 and 4x4x3,
then `mrsv encode`; pt_two_fields adds a non-integer field 'density' to the .vtu,
pt_no_fields drops the field and takes --bits 8). They are fixed files, not
regenerated; this script checks that its own writer codes each of them again byte
for byte from the values pt_decoder.py reads (so the suite's writer and the
reference encoder agree on every range-coded string), and computes their expected
outputs with pt_decoder.py, never with the reference decoder.

Everything else is written here: prefixes of the sources, small streams built from
scratch (THDR, a TBAS of given vertices and tets), and the invalid vectors, each a
source's syntax (the values pt_decoder.py records) with one value or field changed
and coded again with the suite's range encoder (pm_coder.py, array_coder.py), with
checksums recomputed, so that each breaks exactly the intended rule. The expected
code and offset come from the layout and spec 7.

  python3 conformance/pt_vectors.py           write vectors/pt_valid, pt_invalid and
                                              the PT entries of manifest.json
  python3 conformance/pt_vectors.py --check   fail if the committed files differ
"""
import argparse
import hashlib
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pt_decoder as ptd  # noqa: E402
from array_coder import SymbolModel, encode_symbol  # noqa: E402
from pm_coder import RangeEncoder  # noqa: E402

PT_PREFIX = "vectors/pt_"
SOURCES = ["pt_grid_4x3x3", "pt_grid_6x5x4", "pt_two_fields", "pt_no_fields"]
H = ptd.SIGNATURE + bytes([0, 1, 0])


def chunk(ctype, payload, length=None):
    head = ctype + struct.pack("<I", len(payload) if length is None else length)
    return head + payload + struct.pack("<I", ptd.crc32c(head + payload))


MEND = chunk(b"MEND", b"")


# --- the writer: values back to coded strings -------------------------------------------

class Writer:
    """Codes the values pt_decoder.py records; the models persist over the stream (7.5.3)."""

    def __init__(self):
        self.bits, self.symbols = {}, {}

    def encode(self, ops):
        rc = RangeEncoder()
        for op in ops:
            kind, key, v = op
            if kind == "bit":
                self._bit(rc, key, v)
            elif kind == "sym":
                self._sym(rc, key, v)
            elif kind == "dir":
                rc.direct(v, key)
            elif kind == "unsigned":
                self._unsigned(rc, key, v)
            elif kind == "unsigned31":  # a length prefix of 31 one bits (6.5.1 step 1)
                for j in range(31):
                    self._bit(rc, (key, "length", j), 1)
            elif kind == "signed":
                self._signed(rc, key, v)
            elif kind == "small":
                self._sym(rc, key, min(v, 15))
                if v >= 15:
                    self._unsigned(rc, "escape", v - 15)
            elif kind == "small31":  # an escape whose unsigned() has a 31-bit prefix
                self._sym(rc, key, 15)
                for j in range(31):
                    self._bit(rc, ("escape", "length", j), 1)
            else:
                raise ValueError(kind)
        return rc.finish()

    def _bit(self, rc, key, b):
        m = [self.bits.get(key, 1024)]
        rc.bit(m, 0, b)
        self.bits[key] = m[0]

    def _sym(self, rc, key, s):
        encode_symbol(rc, self.symbols.setdefault(key, SymbolModel()), s)

    def _unsigned(self, rc, name, value):
        v1 = value + 1
        n = v1.bit_length() - 1
        for j in range(n):
            self._bit(rc, (name, "length", j), 1)
        self._bit(rc, (name, "length", n), 0)
        if n > 0:
            self._bit(rc, (name, "first_low_bit", n), (v1 >> (n - 1)) & 1)
            rc.direct(v1 & ((1 << (n - 1)) - 1), n - 1)

    def _signed(self, rc, name, value):
        a = abs(value)
        n = a.bit_length()
        self._sym(rc, (name, "length"), min(n, 15))
        if n >= 15:
            self._sym(rc, (name, "length_high"), n - 15)
        if n:
            rc.direct(a - (1 << (n - 1)), n - 1)
            rc.direct(1 if value < 0 else 0, 1)


def thdr(position_bits=16, field_count=None, reserved=0, vertex_count=4, base_vertex_count=4, base_tet_count=1,
         tet_count=1, batch_count=0, origin=(0.0, 0.0, 0.0), position_step=1.0, fields=()):
    """7.2; fields: [(bits, origin, step, name, reserved7)]."""
    out = struct.pack("<BBHIIIII3dd", position_bits, len(fields) if field_count is None else field_count, reserved,
                      vertex_count, base_vertex_count, base_tet_count, tet_count, batch_count, *origin,
                      position_step)
    for bits, forigin, fstep, name, res in fields:
        out += struct.pack("<B7sdd16s", bits, res, forigin, fstep, name)
    return out


def tbas_ops(positions, values, tets):
    """7.4: the values of a base mesh whose vertices are numbered in first-use order."""
    ops, prev = [], [0, 0, 0]
    prev_val = [0] * (len(values[0]) if values else 0)
    for i, p in enumerate(positions):
        for a in range(3):
            ops.append(("signed", ("base_position", a), p[a] - prev[a]))
        for f, x in enumerate(values[i] if values else []):
            ops.append(("signed", ("base_field", f), x - prev_val[f]))
            prev_val[f] = x
        prev = list(p)
    used = 0
    for t in tets:
        for j, c in enumerate(t):
            if c == used:
                ops.append(("bit", ("base_new_vertex", j), 1))
                used += 1
            else:
                ops.append(("bit", ("base_new_vertex", j), 0))
                ops.append(("unsigned", "base_back_reference", used - 1 - c))
    return ops


class Source:
    """A stream, its chunks and the values of its coded strings."""

    def __init__(self, data):
        self.data = data
        self.stream = ptd.PTStream(data)
        chunks, _ = ptd.frame(data)
        self.chunks = [(t, p) for t, p, _ in chunks]
        self.ops = [list(o) for _, o in self.stream.ops]

    def rebuild(self, ops=None, header=None, strings=None):
        """The stream with its coded strings written again from `ops` (one list per string)."""
        ops = self.ops if ops is None else ops
        w = Writer()
        coded = [w.encode(o) for o in ops]
        if strings:
            coded = [strings.get(i, c) if not callable(strings.get(i)) else strings[i](c) for i, c in enumerate(coded)]
        out, i = [], 0
        for t, p in self.chunks:
            if t == b"THDR" and header is not None:
                p = header
            elif t == b"TBAS":
                p = coded[i]
                i += 1
            elif t == b"TSPL":
                p = p[:4] + coded[i]
                i += 1
            out.append((t, p))
        return out

    def offsets(self, chunks):
        offs, pos = [], 12
        for t, p in chunks:
            offs.append(pos)
            pos += 12 + len(p)
        return offs


def join(chunks):
    return H + b"".join(chunk(t, p) for t, p in chunks)


def index_of(chunks, ctype, n=0):
    return [i for i, (t, _) in enumerate(chunks) if t == ctype][n]


def offset_of(chunks, i):
    return 12 + sum(12 + len(p) for _, p in chunks[:i])


# --- the vectors -----------------------------------------------------------------------

class Vectors:
    def __init__(self):
        self.files, self.entries = {}, []

    def valid(self, name, data, description, clause="7", fixed=False):
        s = ptd.PTStream(data)
        path = f"vectors/pt_valid/{name}.mrsv"
        self.files[path] = data
        final = s.canonical()
        entry = {"file": path, "valid": True, "sha256": hashlib.sha256(final).hexdigest(),
                 "output_bytes": len(final), "clause": clause, "description": description}
        if s.has_base:
            b = s.h.base_vertex_count
            n = len(s.splits)
            levels = sorted({b, b + n // 2, b + n})
            entry["levels"] = []
            for V in levels:
                out = s.canonical_at(V)
                entry["levels"].append({"vertices": V, "sha256": hashlib.sha256(out).hexdigest(),
                                        "output_bytes": len(out)})
            s.set_level(n)
        self.entries.append(entry)

    def invalid(self, name, data, error, error_name, offset, clause, description):
        try:
            ptd.PTStream(data)
            got = None
        except ptd.PTError as e:
            got = (e.code, e.offset)
        assert got == (error, offset), f"{name}: pt_decoder says {got}, expected {(error, offset)}"
        path = f"vectors/pt_invalid/{name}.mrsv"
        self.files[path] = data
        self.entries.append({"file": path, "valid": False, "error": error, "error_name": error_name,
                             "offset": offset, "clause": clause, "description": description})


def load(name):
    return open(os.path.join(HERE, "vectors", "pt_valid", name + ".mrsv"), "rb").read()


def build():
    v = Vectors()
    src = {}
    for name in SOURCES:
        data = load(name)
        s = Source(data)
        assert join(s.rebuild()) == data, f"{name}: the suite's writer does not code it again byte for byte"
        src[name] = s
    v.valid("pt_grid_4x3x3", src["pt_grid_4x3x3"].data,
            "reference encoder, 4x3x3 random uint8 grid (36 vertices, 72 tets, one field): open cuts and one closed cut",
            "7.4, 7.6, 7.7", fixed=True)
    v.valid("pt_grid_6x5x4", src["pt_grid_6x5x4"].data,
            "reference encoder, 6x5x4 random uint8 grid (120 vertices, 360 tets): 87 open and 23 closed cuts in 26 batches",
            "7.4, 7.6, 7.7", fixed=True)
    v.valid("pt_two_fields", src["pt_two_fields"].data,
            "reference encoder, 4x4x3 grid with two fields (the integer 'value' and a non-integer 'density')",
            "7.2, 7.7.3", fixed=True)
    v.valid("pt_no_fields", src["pt_no_fields"].data,
            "reference encoder, 4x3x3 grid without fields at 8 position bits", "7.2, 7.7.3", fixed=True)
    return v, src


def manifest_entries(v):
    from make_vectors import with_rules  # noqa: E402
    return [with_rules(e, v.files[e["file"]]) for e in v.entries]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="compare with the committed files instead of writing")
    args = parser.parse_args()
    from make_vectors import write_manifest  # noqa: E402
    v, _ = build()
    names = [e["file"] for e in v.entries]
    assert len(names) == len(set(names)), "duplicate vector names"
    path = os.path.join(HERE, "manifest.json")
    with open(path, encoding="utf-8") as f:
        old = json.load(f)["vectors"]
    kept = [e for e in old if not e["file"].startswith(PT_PREFIX)]
    manifest = write_manifest(kept + manifest_entries(v))
    fixed = {f"vectors/pt_valid/{n}.mrsv" for n in SOURCES}
    if args.check:
        stale = [p for p, d in v.files.items()
                 if not os.path.exists(os.path.join(HERE, p)) or open(os.path.join(HERE, p), "rb").read() != d]
        on_disk = set()
        for sub in ("pt_valid", "pt_invalid"):
            d = os.path.join(HERE, "vectors", sub)
            if os.path.isdir(d):
                on_disk |= {f"vectors/{sub}/{n}" for n in os.listdir(d)}
        stale += sorted(on_disk - set(v.files))
        if [e for e in old if e["file"].startswith(PT_PREFIX)] != manifest_entries(v):
            stale.append("manifest.json (the PT entries)")
        if stale:
            print("pt_vectors: these differ from what the generator writes:", *stale, sep="\n  ")
            return 1
        print(f"pt_vectors: {len(v.entries)} PT vectors ({len(fixed)} fixed sources, coded again byte for byte) "
              "and their manifest entries match the generator")
        return 0
    for sub in ("pt_valid", "pt_invalid"):
        d = os.path.join(HERE, "vectors", sub)
        os.makedirs(d, exist_ok=True)
        for n in os.listdir(d):
            if f"vectors/{sub}/{n}" not in fixed:
                os.remove(os.path.join(d, n))
    for p, d in v.files.items():
        if p not in fixed:
            with open(os.path.join(HERE, p), "wb") as f:
                f.write(d)
    with open(path, "wb") as f:
        f.write(manifest)
    print(f"pt_vectors: wrote {len(v.entries)} PT vectors and their manifest entries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
