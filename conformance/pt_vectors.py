#!/usr/bin/env python3
"""Generates the conformance vectors of PT streams (spec 7) and their manifest entries.

Sources. The PT streams with splits in vectors/pt_valid/pt_grid_*.mrsv,
pt_two_fields.mrsv and pt_no_fields.mrsv were written once by the reference encoder
(`mrsv tetrahedralize --ascii` of small random uint8 grids, 4x3x3, 6x5x4 and 4x4x3,
then `mrsv encode`; pt_two_fields adds a non-integer field 'density' to the .vtu,
pt_no_fields is pt_grid_4x3x3's mesh without its field, at --bits 8). They were
written again from their decoded meshes when 7.7.1 took group flags (D87). They are fixed files, not
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
    build_python_valid(v, src)
    build_header_cases(v, src)
    build_order_cases(v, src)
    build_base_cases(v, src)
    build_split_cases(v, src)
    return v, src


def set_u32(payload, at, value, fmt="<I"):
    b = bytearray(payload)
    struct.pack_into(fmt, b, at, value)
    return bytes(b)


def tiny_stream(positions, tets, values=None, fields=(), position_bits=4, extra=b"", complete=True, **kw):
    """A stream of a base mesh alone (S = 0), written here from its vertices and tets."""
    n = len(positions)
    header = dict(position_bits=position_bits, vertex_count=n, base_vertex_count=n, base_tet_count=len(tets),
                  tet_count=len(tets), batch_count=0, fields=fields)
    header.update(kw)
    ops = tbas_ops(positions, values, tets)
    out = H + chunk(b"THDR", thdr(**header)) + chunk(b"TBAS", Writer().encode(ops)) + extra
    return out + (MEND if complete else b"")


# A positive tet (orient3d of (0,0,0), (1,0,0), (0,1,0), (0,0,1) is +1).
TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]


def renumber(positions, tets):
    """Vertices numbered in the order the tets first use them (7.4)."""
    order = {}
    for t in tets:
        for x in t:
            order.setdefault(x, len(order))
    pos = [None] * len(order)
    for x, i in order.items():
        pos[i] = positions[x]
    return pos, [[order[x] for x in t] for t in tets]


def build_python_valid(v, src):
    v.valid("pt_single_tet", tiny_stream(TET, [[0, 1, 2, 3]]),
            "written here: one positive tet, no splits (batch_count 0), 4 position bits", "7.2, 7.4")
    # Four tets around an interior vertex (numbered 0 by first use): its link is a sphere.
    a, b, c, d, e = (0, 0, 0), (8, 0, 0), (0, 8, 0), (0, 0, 8), (2, 2, 2)
    star = [[0, 1, 2, 3], [4, 0, 2, 3], [4, 1, 0, 3], [4, 1, 2, 0]]
    v.valid("pt_interior_vertex", tiny_stream([e, b, c, d, a], star, values=[[7], [0], [1], [2], [3]],
                                              fields=[(3, -1.5, 0.25, b"t", bytes(7))]),
            "written here: four tets around an interior vertex (a sphere link) and boundary vertices (disk "
            "links); one 3-bit field", "7.3, 7.4")
    A = src["pt_grid_6x5x4"]
    c = A.chunks
    t = index_of(c, b"TBAS")
    v.valid("pt_prefix_header_only", H + chunk(b"THDR", c[0][1]),
            "a prefix of THDR alone: the empty level (V = T = 0) with P and F from THDR", "7.1, 7.8")
    v.valid("pt_prefix_after_base", join(c[:t + 1]), "a prefix ending after TBAS: the base mesh", "7.1")
    v.valid("pt_prefix_after_batches", join(c[:t + 4]), "a prefix ending after the third TSPL", "7.1")
    B = src["pt_grid_4x3x3"]
    c = B.chunks
    t = index_of(c, b"TBAS")
    meta = (b"meta", b"description=a PT stream with metadata\n")
    xtra = (b"xtra", b"an unknown ancillary chunk, skipped")
    v.valid("pt_meta_and_ancillary", join(c[:1] + [meta] + c[1:t + 3] + [xtra] + c[t + 3:]),
            "the 4x3x3 stream with a meta chunk after THDR and an unknown ancillary chunk between batches",
            "7.1, 2.4")


def build_header_cases(v, src):
    A = src["pt_grid_4x3x3"]
    c = A.chunks
    P = c[0][1]
    h = A.stream.h
    q = 20

    def case(name, payload, error, error_name, offset, description):
        v.invalid(name, join([(b"THDR", payload)] + c[1:]), error, error_name, offset, "7.2", description)

    case("pt_thdr_short", P[:55], 117, "bad_chunk_length", 16, "a THDR payload of 55 bytes")
    case("pt_thdr_position_bits_zero", set_u32(P, 0, 0, "<B"), 301, "bad_mesh_header", q, "position_bits 0")
    case("pt_thdr_position_bits_31", set_u32(P, 0, 31, "<B"), 301, "bad_mesh_header", q, "position_bits 31")
    case("pt_thdr_position_bits_before_length", set_u32(P, 0, 0, "<B") + b"\0", 301, "bad_mesh_header", q,
         "position_bits 0 and a payload one byte too long: rule 2 comes before rule 4")
    case("pt_thdr_field_count_nine", set_u32(P, 1, 9, "<B"), 301, "bad_mesh_header", q + 1,
         "field_count 9 (the payload's length fits one field): rule 3 comes before rule 4")
    case("pt_thdr_length_mismatch", P + bytes(40), 117, "bad_chunk_length", 16,
         "one field and a payload of 136 bytes (56 + 40 x 2)")
    case("pt_thdr_reserved", set_u32(P, 2, 1, "<H"), 105, "reserved_nonzero", q + 2, "THDR.reserved 1")
    case("pt_thdr_vertex_count_above", set_u32(P, 4, (1 << 28) + 1), 301, "bad_mesh_header", q + 4,
         "vertex_count 2^28 + 1")
    case("pt_thdr_base_vertex_count_three", set_u32(P, 8, 3), 301, "bad_mesh_header", q + 8, "base_vertex_count 3")
    case("pt_thdr_base_vertex_count_above", set_u32(P, 8, h.vertex_count + 1), 301, "bad_mesh_header", q + 8,
         "base_vertex_count above vertex_count")
    case("pt_thdr_base_tet_count_zero", set_u32(P, 12, 0), 301, "bad_mesh_header", q + 12, "base_tet_count 0")
    case("pt_thdr_base_tet_count_above", set_u32(P, 12, (1 << 30) + 1), 301, "bad_mesh_header", q + 12,
         "base_tet_count 2^30 + 1")
    case("pt_thdr_tet_count_below_splits", set_u32(P, 16, h.base_tet_count + h.S - 1), 301, "bad_mesh_header",
         q + 16, "tet_count one below base_tet_count + S: every split adds at least one tet")
    case("pt_thdr_tet_count_above", set_u32(P, 16, (1 << 30) + 1), 301, "bad_mesh_header", q + 16,
         "tet_count 2^30 + 1")
    case("pt_thdr_batch_count_above_splits", set_u32(P, 20, h.S + 1), 301, "bad_mesh_header", q + 20,
         "batch_count S + 1")
    case("pt_thdr_batch_count_zero", set_u32(P, 20, 0), 301, "bad_mesh_header", q + 20,
         "batch_count 0 while S > 0")
    case("pt_thdr_origin_y_nan", set_u32(P, 32, float("nan"), "<d"), 301, "bad_mesh_header", q + 32,
         "origin[1] (y) a NaN")
    case("pt_thdr_origin_order", set_u32(set_u32(P, 40, float("inf"), "<d"), 48, 0.0, "<d"), 301,
         "bad_mesh_header", q + 40, "origin[2] infinite and position_step 0: rule 12 comes first")
    case("pt_thdr_position_step_zero", set_u32(P, 48, 0.0, "<d"), 301, "bad_mesh_header", q + 48,
         "position_step 0")
    case("pt_thdr_position_step_negative", set_u32(P, 48, -1.0, "<d"), 301, "bad_mesh_header", q + 48,
         "position_step -1")
    r = q + 56
    case("pt_thdr_field_bits_zero", set_u32(P, 56, 0, "<B"), 301, "bad_mesh_header", r, "field 0's bits 0")
    case("pt_thdr_field_bits_31", set_u32(P, 56, 31, "<B"), 301, "bad_mesh_header", r, "field 0's bits 31")
    case("pt_thdr_field_reserved", set_u32(P, 56 + 4, 1, "<B"), 105, "reserved_nonzero", r + 1,
         "field 0's fourth reserved byte 1: the offset of the first reserved byte")
    case("pt_thdr_field_origin_infinite", set_u32(P, 56 + 8, float("-inf"), "<d"), 301, "bad_mesh_header", r + 8,
         "field 0's origin -infinity")
    case("pt_thdr_field_step_zero", set_u32(P, 56 + 16, 0.0, "<d"), 301, "bad_mesh_header", r + 16,
         "field 0's step 0")
    case("pt_thdr_field_step_nan", set_u32(P, 56 + 16, float("nan"), "<d"), 301, "bad_mesh_header", r + 16,
         "field 0's step a NaN")
    case("pt_thdr_field_name_control", set_u32(P, 56 + 24 + 1, 0x7F, "<B"), 301, "bad_mesh_header", r + 24,
         "field 0's name with a byte 0x7F")
    case("pt_thdr_field_name_after_zero", set_u32(P, 56 + 24 + 15, 0x41, "<B"), 301, "bad_mesh_header", r + 24,
         "field 0's name with a byte 'A' after its first zero byte")
    F = src["pt_two_fields"]
    P2 = F.chunks[0][1]

    def case2(name, payload, error, error_name, offset, description):
        v.invalid(name, join([(b"THDR", payload)] + F.chunks[1:]), error, error_name, offset, "7.2", description)

    case2("pt_thdr_second_field_bits", set_u32(P2, 96, 0, "<B"), 301, "bad_mesh_header", q + 96,
          "two fields, field 1's bits 0")
    case2("pt_thdr_field_order", set_u32(set_u32(P2, 96, 0, "<B"), 56 + 24, 0x01, "<B"), 301, "bad_mesh_header",
          r + 24, "field 0's name with a byte 0x01 and field 1's bits 0: every rule of field 0 comes first")
    case2("pt_thdr_reserved_before_field_bits", set_u32(set_u32(P2, 2, 1, "<H"), 56, 0, "<B"), 105,
          "reserved_nonzero", q + 2, "THDR.reserved 1 and field 0's bits 0: rule 5 comes first")


def build_order_cases(v, src):
    A = src["pt_grid_4x3x3"]
    c = A.chunks
    t = index_of(c, b"TBAS")
    end = len(c) - 1
    ins = c[:t] + [(b"GRAW", b"\x2a")] + c[t:]
    v.invalid("pt_graw_after_thdr", join(ins), 116, "chunk_order", offset_of(ins, t), "7.1",
              "a GRAW chunk after THDR")
    ins = c[:t + 2] + [(b"PSPL", c[t + 1][1])] + c[t + 2:]
    v.invalid("pt_pspl_between_batches", join(ins), 116, "chunk_order", offset_of(ins, t + 2), "7.1",
              "a PSPL chunk (a progressive mesh's batch) among the TSPL chunks")
    ins = c[:t + 2] + [c[t]] + c[t + 2:]
    v.invalid("pt_second_tbas", join(ins), 116, "chunk_order", offset_of(ins, t + 2), "7.1",
              "a second TBAS after the first batch")
    ins = c[:t] + [c[t + 1], c[t]] + c[t + 2:]
    v.invalid("pt_tspl_before_tbas", join(ins), 116, "chunk_order", offset_of(ins, t), "7.1",
              "the first TSPL before TBAS")
    ins = c[:t] + [c[end]]
    v.invalid("pt_missing_tbas", join(ins), 116, "chunk_order", offset_of(ins, t), "7.1",
              "a complete stream of THDR and MEND: no TBAS")
    ins = c[:end - 1] + [c[end]]
    v.invalid("pt_missing_batch", join(ins), 304, "split_count_mismatch", offset_of(ins, end - 1), "7.1",
              "a complete stream without its last TSPL: fewer batches and splits than THDR announces")
    h = A.stream.h
    P = set_u32(c[0][1], 16, h.tet_count + 1)
    ins = [(b"THDR", P)] + c[1:]
    v.invalid("pt_tet_count_above_finest", join(ins), 304, "split_count_mismatch", offset_of(ins, end), "7.1",
              "tet_count one above the finest level's tets")
    data = join(c)
    p = offset_of(c, end - 1)
    v.invalid("pt_truncated_in_batch", data[:p + 8 + 10], 111, "chunk_past_end", p + 4, "2.3, 2.5.1",
              "the file ends 10 bytes into the payload of the last TSPL")
    v.invalid("pt_truncated_chunk_header", data[:p + 6], 110, "truncated_chunk_header", p, "2.3, 2.5.1",
              "the file ends 6 bytes into the header of the last TSPL")


def first(ops, pred, n=0):
    return [i for i, op in enumerate(ops) if pred(op)][n]


def replaced(ops, i, *new):
    return ops[:i] + list(new) + ops[i + 1:]


def build_base_cases(v, src):
    A = src["pt_grid_4x3x3"]
    c = A.chunks
    t = index_of(c, b"TBAS")
    q = offset_of(c, t) + 8
    s = A.stream
    h = s.h
    base = A.ops[0]
    s.set_level(0)
    positions, values = s.positions[:h.base_vertex_count], s.values[:h.base_vertex_count]
    tets = [list(x) for x in s.tets]
    s.set_level(len(s.splits))
    assert tbas_ops(positions, values, tets) == base

    def case(name, ops=None, error=302, error_name="bad_base_mesh", description="", strings=None):
        ops = [base if ops is None else ops] + A.ops[1:]
        v.invalid(name, join(A.rebuild(ops, strings=strings)), error, error_name, q, "7.4", description)

    case("pt_base_first_byte", strings={0: lambda b: b"\x01" + b[1:]}, error=206, error_name="bad_entropy_payload",
         description="TBAS's coded string starts with 1")
    case("pt_base_empty", strings={0: b""}, error=206, error_name="bad_entropy_payload",
         description="an empty TBAS payload: its first byte reads as 0, then the string ends")
    case("pt_base_truncated", strings={0: lambda b: b[:-1]}, error=206, error_name="bad_entropy_payload",
         description="TBAS's coded string without its last byte")
    case("pt_base_leftover", strings={0: lambda b: b + b"\0"}, error=206, error_name="bad_entropy_payload",
         description="one byte after TBAS's coded string")
    case("pt_base_truncated_before_error", ops=tbas_ops(positions, values, [[0, 1, 2, 3]] * len(tets)),
         strings={0: lambda b: b[:8]}, error=206, error_name="bad_entropy_payload",
         description="a TBAS string cut to 8 bytes whose values, read as zeros past the end, would also fail "
                     "rule 2 or 3: 206")
    i = first(base, lambda op: op[1] == ("base_position", 0))
    case("pt_base_coordinate_negative", replaced(base, i, ("signed", ("base_position", 0), -1)),
         description="the first vertex's x is -1")
    i = first(base, lambda op: op[1] == ("base_position", 2), 1)
    case("pt_base_coordinate_above", replaced(base, i, ("signed", ("base_position", 2), 1 << 16)),
         description="the second vertex's z is 2^16 at 16 position bits")
    i = first(base, lambda op: op[1] == ("base_field", 0), 2)
    case("pt_base_value_above", replaced(base, i, ("signed", ("base_field", 0), 1 << 16)),
         description="the third vertex's value is above 2^bits")
    all_new = tbas_ops(positions, values, [])
    all_new += [("bit", ("base_new_vertex", j), 1) for _ in tets for j in range(4)]
    case("pt_base_new_vertex_past_count", all_new,
         description="every corner a new vertex: the corner after the last base vertex fails")
    i = first(base, lambda op: op[1] == ("base_new_vertex", 0))
    case("pt_base_back_reference_too_far",
         replaced(base, i, ("bit", ("base_new_vertex", 0), 0), ("unsigned", "base_back_reference", 0)),
         description="the first corner a back reference while no vertex is in use")
    i = first(base, lambda op: op[0] == "unsigned")
    case("pt_base_back_reference_prefix_31", replaced(base, i, ("unsigned31", "base_back_reference", None)),
         description="a back reference whose length prefix has 31 one bits")
    few = [tets[0]] + [[tets[0][3]] * 4 for _ in tets[1:]]
    case("pt_base_unused_vertices", tbas_ops(positions, values, few),
         description="the tets after the first name only its vertices: used < base_vertex_count after the tets")
    k = max(i for i, x in enumerate(tets) if max(x) < min(max(y) for y in tets[i:]) or i == 0)
    late = [i for i in range(1, len(tets)) if max(tets[i]) < max(max(y) for y in tets[:i])
            or all(x < max(max(y) for y in tets[:i]) + 1 for x in tets[i])]
    k = [i for i in range(1, len(tets)) if max(tets[i]) <= max(max(y) for y in tets[:i])][-1]
    rep = [list(x) for x in tets]
    rep[k][1] = rep[k][0]
    case("pt_base_repeated_corner", tbas_ops(positions, values, rep),
         description=f"tet {k} with its corner 1 the same vertex as its corner 0")
    inv = [list(x) for x in tets]
    inv[k][0], inv[k][1] = inv[k][1], inv[k][0]
    case("pt_base_inverted_tet", tbas_ops(positions, values, inv),
         description=f"tet {k} with corners 0 and 1 swapped: orient3d is -1")
    dup = [list(x) for x in tets]
    dup[k] = list(tets[0])
    case("pt_base_duplicate_tet", tbas_ops(positions, values, dup),
         description=f"tet {k} replaced by a copy of tet 0: a directed link edge in two link triangles")
    # Two tets sharing one vertex: its link is two triangles, not connected (rule 6 c).
    bowtie = TET + [(-1, 0, 0), (0, -1, 0), (0, 0, -1)]
    bowtie = [(x + 1, y + 1, z + 1) for x, y, z in bowtie]
    data = tiny_stream(bowtie, [[0, 1, 2, 3], [0, 5, 4, 6]])
    assert ptd.orient3d(*(bowtie[i] for i in [0, 5, 4, 6])) == 1
    v.invalid("pt_base_bowtie_vertex", data, 302, "bad_base_mesh", 12 + 12 + 56 + 8, "7.4",
              "written here: two tets sharing only a vertex, whose link is two triangles that share no edge")
    # Two tets sharing one edge: the links of its ends are two triangles meeting at a vertex.
    edge = [(1, 1, 1), (2, 1, 1), (1, 2, 1), (1, 1, 2), (0, 1, 1), (1, 0, 1)]
    tets2 = [[0, 1, 2, 3], [0, 1, 4, 5]]
    if ptd.orient3d(*(edge[i] for i in tets2[1])) != 1:
        tets2[1] = [0, 1, 5, 4]
    tets2 = [[0, 1, 2, 3], [0, 1, 4, 5]] if ptd.orient3d(*(edge[i] for i in [0, 1, 4, 5])) == 1 else \
        [[0, 1, 2, 3], [1, 0, 4, 5]]
    v.invalid("pt_base_bowtie_edge", tiny_stream(edge, tets2), 302, "bad_base_mesh", 12 + 12 + 56 + 8, "7.4",
              "written here: two tets sharing only an edge, whose ends' links are not connected across an edge")


def build_split_cases(v, src):
    for name in ("pt_grid_4x3x3", "pt_grid_6x5x4"):
        src[name].stream.set_level(len(src[name].stream.splits))
    A = src["pt_grid_6x5x4"]
    c = A.chunks
    t = index_of(c, b"TBAS")
    h = A.stream.h

    def q_of(b):
        return offset_of(c, t + 1 + b) + 8

    def variant(b, ops):
        """The stream with batch b's values replaced (the strings after it as they were)."""
        all_ops = list(A.ops)
        all_ops[b + 1] = ops
        return join(A.rebuild(all_ops))

    def outcome(data):
        try:
            ptd.PTStream(data)
            return None
        except ptd.PTError as e:
            return e.code, e.offset, e.detail

    def case(name, b, ops, error=303, error_name="bad_vertex_split", description="", clause="7.7"):
        v.invalid(name, variant(b, ops), error, error_name, q_of(b) + 4, clause, description)

    def search(detail, kinds, values):
        """The first batch and value change (in batch order) that fails with `detail`."""
        for b in range(len(A.ops) - 1):
            ops = A.ops[b + 1]
            for i, op in enumerate(ops):
                if not kinds(op):
                    continue
                for x in values(op):
                    if x == op[2]:
                        continue
                    new = replaced(ops, i, (op[0], op[1], x))
                    got = outcome(variant(b, new))
                    if got and got[:2] == (303, q_of(b) + 4) and got[2] == detail:
                        return b, new, i
        raise AssertionError("no value gives " + detail)

    batch0 = A.ops[1]
    P = c[t + 1][1]
    # 7.7 rules 1 to 4 and 6
    ins = c[:-1] + [c[-2], c[-1]]
    v.invalid("pt_batch_beyond_count", join(ins), 304, "split_count_mismatch", offset_of(ins, len(c) - 1), "7.7",
              "a copy of the last TSPL after it: more TSPL chunks than batch_count")
    ins = c[:-1] + [(b"TSPL", b"\0\0"), c[-1]]
    v.invalid("pt_batch_beyond_count_short", join(ins), 304, "split_count_mismatch", offset_of(ins, len(c) - 1),
              "7.7", "a TSPL of 2 bytes after the last batch: rule 1 comes before rule 2")
    ins = c[:t + 1] + [(b"TSPL", P[:3])] + c[t + 2:]
    v.invalid("pt_batch_short", join(ins), 117, "bad_chunk_length", offset_of(ins, t + 1) + 4, "7.7",
              "the first TSPL with a payload of 3 bytes")
    ins = c[:t + 1] + [(b"TSPL", set_u32(P, 0, 0))] + c[t + 2:]
    v.invalid("pt_split_count_zero", join(ins), 304, "split_count_mismatch", q_of(0), "7.7", "split_count 0")
    ins = c[:t + 1] + [(b"TSPL", set_u32(P, 0, h.S + 1))] + c[t + 2:]
    v.invalid("pt_split_count_above", join(ins), 304, "split_count_mismatch", q_of(0), "7.7",
              "split_count S + 1 in the first batch")
    ins = c[:t + 1] + [(b"TSPL", P[:4] + b"\x01" + P[5:])] + c[t + 2:]
    v.invalid("pt_batch_first_byte", join(ins), 206, "bad_entropy_payload", q_of(0) + 4, "7.7",
              "the first TSPL's coded string starts with 1")
    ins = c[:t + 1] + [(b"TSPL", P[:4])] + c[t + 2:]
    v.invalid("pt_batch_empty_string", join(ins), 206, "bad_entropy_payload", q_of(0) + 4, "7.7",
              "the first TSPL with split_count and no coded string")
    ins = c[:t + 1] + [(b"TSPL", P[:-1])] + c[t + 2:]
    v.invalid("pt_batch_truncated", join(ins), 206, "bad_entropy_payload", q_of(0) + 4, "7.7",
              "the first TSPL's coded string without its last byte")
    ins = c[:t + 1] + [(b"TSPL", P + b"\0")] + c[t + 2:]
    v.invalid("pt_batch_leftover", join(ins), 206, "bad_entropy_payload", q_of(0) + 4, "7.7",
              "one byte after the first TSPL's coded string")
    # 7.7.1: the flags end before split_count splits
    s = ptd.PTStream(join(c[:t + 2]))
    n0 = len(s.positions)
    last = s.splits[-1][0]
    # After the last split: 0 flags to the end of its group, then a 0 group flag per group.
    group_end = min((last // ptd.SPLIT_GROUP + 1) * ptd.SPLIT_GROUP, n0)
    more = batch0 + [("bit", ("split_flag", min(len(s.incident[x]) // 2, 15)), 0) for x in range(last + 1, group_end)]
    more += [("bit", ("group_flag", 1 if x == group_end else 0), 0) for x in range(group_end, n0, ptd.SPLIT_GROUP)]
    ins = c[:t + 1] + [(b"TSPL", set_u32(P, 0, struct.unpack_from("<I", P)[0] + 1)[:4] + Writer().encode(more))]
    w = Writer()
    strings = [w.encode(A.ops[0]), w.encode(more)]
    ins = c[:t] + [(b"TBAS", strings[0]), (b"TSPL", set_u32(P, 0, struct.unpack_from("<I", P)[0] + 1)[:4] + strings[1])]
    ins += c[t + 2:]
    v.invalid("pt_flags_end", join(ins), 303, "bad_vertex_split", q_of(0) + 4, "7.7.1",
              "split_count one above the splits coded: every later vertex's flag is 0 and the flags run out")
    # 7.7.2: the cut
    i = first(batch0, lambda op: op[1] == "path_start")
    case("pt_path_start_out_of_range", 0, replaced(batch0, i, ("small", "path_start", 40)),
         description="an open cut's start index 40, beyond the link's boundary vertices", clause="7.7.2")
    b, new, _ = search("cut_start", lambda op: op[1] == "cut_start", lambda op: [op[2] + 60])
    case("pt_cut_start_out_of_range", b, new, description="a closed cut's start index beyond the link's vertices",
         clause="7.7.2")
    b, new, _ = search("cut_first", lambda op: op[1][0] == "cut_first" if isinstance(op[1], tuple) else False,
                       lambda op: [op[1][1]] if op[1][1] < 15 else [])
    case("pt_cut_first_out_of_range", b, new, description="a closed cut's first step index |R|", clause="7.7.2")
    b, new, _ = search("path_first", lambda op: op[1][0] == "path_first" if isinstance(op[1], tuple) else False,
                       lambda op: [op[1][1] - 2] if op[1][1] < 15 else [])
    case("pt_path_first_out_of_range", b, new, description="an open cut's first step |R| - 2", clause="7.7.2")
    b, new, _ = search("turn", lambda op: op[1][0] == "turn" if isinstance(op[1], tuple) else False,
                       lambda op: [op[1][1] - 1] if op[1][1] < 15 else [])
    case("pt_turn_out_of_range", b, new, description="a turn of |R| - 1", clause="7.7.2")
    turns = (lambda op: op[1][0] == "turn" if isinstance(op[1], tuple) else False)
    b, new, _ = search("cut revisits a vertex", turns, lambda op: range(min(op[1][1], 15) - 1))
    case("pt_cut_revisits_vertex", b, new, description="a turn that leads to a vertex the cut has visited",
         clause="7.7.2")
    b, new, _ = search("open cut back at its start", turns, lambda op: range(min(op[1][1], 15) - 1))
    case("pt_open_cut_back_at_start", b, new, description="an open cut's turn that leads back to c0",
         clause="7.7.2")
    i = first(batch0, turns)
    case("pt_turn_escape_prefix_31", 0, replaced(batch0, i, ("small31", batch0[i][1], None)),
         description="a turn escaped to unsigned() with a length prefix of 31 one bits", clause="7.5.2")
    # 7.7.3: vt's values
    i = first(batch0, lambda op: op[1] == ("position", 0))
    case("pt_vt_coordinate_negative", 0, replaced(batch0, i, ("signed", ("position", 0), -(1 << 16))),
         description="vt's x below 0", clause="7.7.3")
    i = first(batch0, lambda op: op[1] == ("position", 2))
    case("pt_vt_coordinate_above", 0, replaced(batch0, i, ("signed", ("position", 2), 1 << 16)),
         description="vt's z at or above 2^position_bits", clause="7.7.3")
    i = first(batch0, lambda op: op[1] == ("field", 0))
    case("pt_vt_value_above", 0, replaced(batch0, i, ("signed", ("field", 0), 1 << 16)),
         description="vt's value at or above 2^bits", clause="7.7.3")
    # 7.6.4: vt at vs (the new tets are flat) and vt far away (a moved tet inverts)
    sp = A.stream.splits[0]
    vs, vt = sp[0], sp[1]
    new = list(batch0)
    for a in range(3):
        i = first(new, lambda op: op[1] == ("position", a))
        d = new[i][2] + A.stream.positions[vs][a] - A.stream.positions[vt][a]
        new[i] = ("signed", ("position", a), d)
    case("pt_new_tets_flat", 0, new, description="the first split's vt placed at vs: its new tets are flat "
         "(orient3d 0), its moved tets as they were", clause="7.6.4")
    assert outcome(variant(0, new))[2] == "new tet not positive"
    b, new, _ = search("moved tet not positive", lambda op: op[1] in (("position", 0), ("position", 1)),
                       lambda op: [op[2] + 30000, op[2] - 30000])
    case("pt_moved_tet_inverted", b, new, description="vt moved far along x or y: a moved tet inverts",
         clause="7.6.4")
    # the tets of a split beyond THDR.tet_count
    Pt = set_u32(c[0][1], 16, h.tet_count - 1)
    ins = [(b"THDR", Pt)] + c[1:]
    v.invalid("pt_split_beyond_tet_count", join(ins), 303, "bad_vertex_split", offset_of(ins, len(c) - 2) + 12,
              "7.6.4", "tet_count one below the finest level's tets: the last split would pass it")
    # a split vertex whose link has 1,025 vertices: vs (0) over a fan of 1,023 triangles
    n = 1024
    pos = [(0, 0, 1), (0, 1, 0)] + [(i, 0, 0) for i in range(n)]
    tets = [[0, 1, 3, 2]] + [[0, 1, i + 3, i + 2] for i in range(1, n - 1)]
    pos, tets = renumber(pos, tets)
    ops = tbas_ops(pos, None, tets)
    assert all(ptd.orient3d(*(pos[x] for x in tt)) == 1 for tt in tets)
    w = Writer()
    header = thdr(position_bits=11, vertex_count=len(pos) + 1, base_vertex_count=len(pos),
                  base_tet_count=len(tets), tet_count=len(tets) + 1, batch_count=1)
    data = H + chunk(b"THDR", header) + chunk(b"TBAS", w.encode(ops))
    q = len(data) + 8
    split = [("bit", ("group_flag", 0), 1), ("bit", ("split_flag", 15), 1)]
    data += chunk(b"TSPL", struct.pack("<I", 1) + w.encode(split)) + MEND
    v.invalid("pt_link_too_large", data, 303, "bad_vertex_split", q + 4, "7.6.1",
              "written here: a split of a vertex whose link has 1,025 vertices (a fan of 1,023 tets)")


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
