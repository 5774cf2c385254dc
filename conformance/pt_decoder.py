#!/usr/bin/env python3
"""An independent decoder of PT streams (spec 7), written from the text alone.

It reads the container (2.2 to 2.5, the checks a PT stream needs), THDR with every
check of 7.2 in order, TBAS (7.4), and each TSPL (7.7): split flags, cuts as walks
over links, vt's values, the region's flood fill and the split with exact integer
orient3d; it undoes splits to show any level and writes canonical output (7.8).
It shares no code with the reference decoder, so agreeing hashes check both.

Every value it decodes is recorded as (kind, model, value), per coded string, so
that pt_vectors.py can write a stream again (the range encoder of pm_coder.py and
the symbol models of array_coder.py) with one value changed: an invalid vector that
breaks exactly one rule.

  python3 conformance/pt_decoder.py IN.mrsv OUT [--vertices N]
      writes the canonical output of the finest level (or of the level with N
      vertices); on an error prints "E<code> offset <n>: <element>" and exits 1.
"""
import math
import struct
import sys

SIGNATURE = bytes([0x8E, 0x4D, 0x52, 0x53, 0x56, 0x0D, 0x0A, 0x1A, 0x0A])
CUM_START = [0, 16352, 24528, 28616, 30660, 31682, 32193, 32448, 32576, 32640, 32672, 32688, 32696,
             32700, 32702, 32703]
CONTENT_HEADERS = (b"GHDR", b"PHDR", b"THDR")
KNOWN_CRITICAL = (b"GHDR", b"GRAW", b"WHDR", b"GMSK", b"GBND", b"GRES", b"PHDR", b"PBAS", b"PSPL",
                  b"THDR", b"TBAS", b"TSPL", b"MEND")
MAX_LINK = 1024  # vertices in the link of a split vertex (7.6.1)
SPLIT_GROUP = 32  # vertices per group flag (7.7.1)


class PTError(Exception):
    def __init__(self, code, offset, element, message=""):
        super().__init__(f"E{code} offset {offset}: {element} {message}".strip())
        self.code, self.offset, self.element, self.detail = code, offset, element, message


class StringEnd(Exception):
    """A byte wanted past the end of a coded string (5.6): the string is in error."""


class SplitInvalid(Exception):
    """A rule of 7.5.2, 7.6 or 7.7.1 to 7.7.3 broken (303), or of 7.4 (302)."""


def _crc_table():
    table = []
    for i in range(256):
        c = i
        for _ in range(8):
            c = (c >> 1) ^ (0x82F63B78 if c & 1 else 0)
        table.append(c)
    return table


_CRC = _crc_table()


def crc32c(data):
    crc = 0xFFFFFFFF
    for b in data:
        crc = (crc >> 8) ^ _CRC[(crc ^ b) & 0xFF]
    return crc ^ 0xFFFFFFFF


# --- 5.6: the range decoder, with models kept by name ---------------------------------

class Models:
    """7.5.3: one set for the whole stream. Bit models and symbol models by key."""

    def __init__(self):
        self.bits = {}
        self.symbols = {}


class RangeDecoder:
    def __init__(self, data, models, ops):
        self.data, self.pos, self.models, self.ops = data, 0, models, ops
        if self._next() != 0:
            raise ValueError("first byte")  # the caller reports rule 1 (206)
        self.code = 0
        for _ in range(4):
            self.code = (self.code << 8) | self._next()
        self.range = 0xFFFFFFFF
        self.depth = 0  # inside signed(), unsigned() or small(): record the value, not its parts

    def _record(self, op):
        if self.depth == 0:
            self.ops.append(op)

    def _next(self):
        if self.pos >= len(self.data):
            raise StringEnd()  # the decoder MAY stop here (5.6, 7.4, 7.7)
        b = self.data[self.pos]
        self.pos += 1
        return b

    def _normalise(self):
        while self.range < (1 << 24):
            self.range = (self.range << 8) & 0xFFFFFFFF
            self.code = ((self.code << 8) | self._next()) & 0xFFFFFFFF

    def bit(self, key):
        p0 = self.models.bits.get(key, 1024)
        bound = (self.range >> 11) * p0
        if self.code < bound:
            self.range = bound
            self.models.bits[key] = p0 + ((2048 - p0) >> 5)
            b = 0
        else:
            self.code -= bound
            self.range -= bound
            self.models.bits[key] = p0 - (p0 >> 5)
            b = 1
        self._record(("bit", key, b))
        self._normalise()
        return b

    def symbol(self, key):
        m = self.models.symbols.get(key)
        if m is None:
            m = self.models.symbols[key] = [list(CUM_START), 0]
        cum, count = m

        def start(i):
            return (1 << 15) if i == 16 else cum[i] + 4 * i
        r = self.range >> 15
        s = 0
        for i in range(1, 16):
            if start(i) * r <= self.code:
                s = i
        self.code -= start(s) * r
        self.range = (start(s + 1) - start(s)) * r if s < 15 else self.range - start(15) * r
        w = 5 if count < 64 else 7
        for i in range(1, 16):
            if i > s:
                cum[i] += (32704 - cum[i]) >> w
            else:
                cum[i] -= cum[i] >> w
        m[1] = min(count + 1, 64)
        self._record(("sym", key, s))
        self._normalise()
        return s

    def direct(self, n):
        v = 0
        for _ in range(n):
            self.range >>= 1
            b = 1 if self.code >= self.range else 0
            if b:
                self.code -= self.range
            v = (v << 1) | b
            self._normalise()
        self._record(("dir", n, v))
        return v

    def _value(kind):
        """Records signed(), unsigned() and small() as one value each."""
        def wrap(f):
            def g(self, key):
                self.depth += 1
                try:
                    v = f(self, key)
                finally:
                    self.depth -= 1
                self._record((kind, key, v))
                return v
            return g
        return wrap

    # 6.5.1
    @_value("unsigned")
    def unsigned(self, name):
        n = 0
        while self.bit((name, "length", n)) == 1:
            n += 1
            if n == 31:
                raise SplitInvalid(f"{name}: a length prefix of 31 bits")
        if n == 0:
            return 0
        h = self.bit((name, "first_low_bit", n))
        r = self.direct(n - 1)
        return (1 << n) + h * (1 << (n - 1)) + r - 1

    # 7.5.1
    @_value("signed")
    def signed(self, name):
        n = self.symbol((name, "length"))
        if n == 15:
            n = 15 + self.symbol((name, "length_high"))
        if n == 0:
            return 0
        a = (1 << (n - 1)) + self.direct(n - 1)
        return -a if self.direct(1) == 1 else a

    # 7.5.2
    @_value("small")
    def small(self, key):
        s = self.symbol(key)
        if s < 15:
            return s
        return 15 + self.unsigned("escape")


# --- 7.3: orientation ------------------------------------------------------------------

def orient3d(a, b, c, d):
    bx, by, bz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    cx, cy, cz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    dx, dy, dz = d[0] - a[0], d[1] - a[1], d[2] - a[2]
    det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx)
    return (det > 0) - (det < 0)


# 7.6.1: with v at stored position i, the link triangle is the corners at these positions
LINK_POSITIONS = ((1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1))


class Link:
    """7.6.1: the link of v in the tets given as {slot: corners}."""

    def __init__(self, v, tets):
        self.tri = {}        # slot -> (p, q, r)
        self.nxt = {}        # (p, x) -> r, from the triangle (p, x, r)
        self.edge_slot = {}  # directed edge (a, b) -> slot of the triangle holding it
        self.duplicate = False
        self.degree = {}
        for slot, t in tets:
            i = t.index(v)
            p, q, r = (t[j] for j in LINK_POSITIONS[i])
            self.tri[slot] = (p, q, r)
            for a, b, c in ((p, q, r), (q, r, p), (r, p, q)):
                if (a, b) in self.nxt:
                    self.duplicate = True
                self.nxt[(a, b)] = c
                self.edge_slot[(a, b)] = slot
                self.degree[a] = self.degree.get(a, 0) + 1
        self.vertices = sorted(self.degree)
        self.boundary_edges = [e for e in self.edge_slot if (e[1], e[0]) not in self.edge_slot]
        self.boundary_vertices = sorted({x for e in self.boundary_edges for x in e})
        self.neighbours = {}
        for (a, b) in self.edge_slot:
            self.neighbours.setdefault(a, set()).add(b)
            self.neighbours.setdefault(b, set()).add(a)

    def has_boundary(self):
        return bool(self.boundary_edges)

    def rotation(self, p, s=None):
        """7.6.1; raises SplitInvalid when it fails."""
        d = self.degree[p]
        if p in self.boundary_vertices:
            starts = sorted(x for (a, x) in self.nxt if a == p and (x, p) not in self.edge_slot)
            if not starts:
                raise SplitInvalid("rotation: no start")
            R = [starts[0]]
            for i in range(d):
                nx = self.nxt.get((p, R[i]))
                if nx is None:
                    raise SplitInvalid("rotation: no next")
                R.append(nx)
            if (p, R[d]) in self.nxt:
                raise SplitInvalid("rotation: does not end at the boundary")
            return R
        R = [s]
        for i in range(d - 1):
            nx = self.nxt.get((p, R[i]))
            if nx is None or nx == s:
                raise SplitInvalid("rotation: no next or back at the start")
            R.append(nx)
        if self.nxt.get((p, R[d - 1])) != s:
            raise SplitInvalid("rotation: does not close")
        return R

    def sphere_or_disk(self):
        """7.4 rule 6 (a) to (d)."""
        if self.duplicate:
            return False
        for p in self.vertices:
            try:
                self.rotation(p, min(self.neighbours[p]))
            except SplitInvalid:
                return False
        slots = list(self.tri)
        seen, stack = {slots[0]}, [slots[0]]
        while stack:
            p, q, r = self.tri[stack.pop()]
            for a, b in ((p, q), (q, r), (r, p)):
                o = self.edge_slot.get((b, a))
                if o is not None and o not in seen:
                    seen.add(o)
                    stack.append(o)
        if len(seen) != len(slots):
            return False
        m, F, B = len(self.vertices), len(slots), len(self.boundary_edges)
        E = (3 * F + B) // 2
        return m - E + F == (1 if B else 2)


# --- the stream ---------------------------------------------------------------------

class Header:
    pass


def parse_thdr(payload, p):
    """7.2, every check in order. p is the chunk's offset."""
    q = p + 8
    n = len(payload)
    if n < 56:
        raise PTError(117, p + 4, "THDR.chunk_length")
    h = Header()
    (h.position_bits, h.field_count, reserved, h.vertex_count, h.base_vertex_count, h.base_tet_count,
     h.tet_count, h.batch_count) = struct.unpack_from("<BBHIIIII", payload, 0)
    h.origin = struct.unpack_from("<3d", payload, 24)
    h.position_step = struct.unpack_from("<d", payload, 48)[0]
    if not 1 <= h.position_bits <= 30:
        raise PTError(301, q, "THDR.position_bits")
    if h.field_count > 8:
        raise PTError(301, q + 1, "THDR.field_count")
    if n != 56 + 40 * h.field_count:
        raise PTError(117, p + 4, "THDR.chunk_length")
    if reserved:
        raise PTError(105, q + 2, "THDR.reserved")
    if h.vertex_count > 1 << 28:
        raise PTError(301, q + 4, "THDR.vertex_count")
    if not 4 <= h.base_vertex_count <= h.vertex_count:
        raise PTError(301, q + 8, "THDR.base_vertex_count")
    if not 1 <= h.base_tet_count <= 1 << 30:
        raise PTError(301, q + 12, "THDR.base_tet_count")
    h.S = h.vertex_count - h.base_vertex_count
    if not h.base_tet_count + h.S <= h.tet_count <= 1 << 30:
        raise PTError(301, q + 16, "THDR.tet_count")
    if h.batch_count > h.S:
        raise PTError(301, q + 20, "THDR.batch_count")
    if (h.batch_count == 0) != (h.S == 0):
        raise PTError(301, q + 20, "THDR.batch_count")
    for a in range(3):
        if not math.isfinite(h.origin[a]):
            raise PTError(301, q + 24 + 8 * a, "THDR.origin")
    if not (math.isfinite(h.position_step) and h.position_step > 0):
        raise PTError(301, q + 48, "THDR.position_step")
    h.fields = []
    for f in range(h.field_count):
        o = 56 + 40 * f
        r = q + o
        bits = payload[o]
        if not 1 <= bits <= 30:
            raise PTError(301, r, f"THDR.field[{f}].bits")
        if any(payload[o + 1:o + 8]):
            raise PTError(105, r + 1, f"THDR.field[{f}].reserved")
        forigin, fstep = struct.unpack_from("<2d", payload, o + 8)
        if not math.isfinite(forigin):
            raise PTError(301, r + 8, f"THDR.field[{f}].origin")
        if not (math.isfinite(fstep) and fstep > 0):
            raise PTError(301, r + 16, f"THDR.field[{f}].step")
        name = payload[o + 24:o + 40]
        z = name.find(0)
        body, rest = (name, b"") if z < 0 else (name[:z], name[z:])
        if any(not 0x20 <= c <= 0x7E for c in body) or any(rest):
            raise PTError(301, r + 24, f"THDR.field[{f}].name")
        h.fields.append((bits, forigin, fstep, bytes(body)))
    return h


def frame(data):
    """2.2 to 2.5: [(type, payload, offset)], complete (MEND seen). Raises PTError."""
    if len(data) < 12:
        raise PTError(101, len(data), "file header")
    if data[:9] != SIGNATURE:
        raise PTError(103 if data[1:5] == b"MRSV" else 102, 0, "signature")
    if (data[9], data[10]) != (0, 1):
        raise PTError(104, 9, "version")
    if data[11]:
        raise PTError(105, 11, "header_flags")
    pos, chunks, complete, meta_seen = 12, [], False, False
    while pos < len(data):
        if len(data) - pos < 8:
            raise PTError(110, pos, "chunk header")
        ctype = data[pos:pos + 4]
        length = struct.unpack_from("<I", data, pos + 4)[0]
        if not all(0x41 <= c <= 0x5A or 0x61 <= c <= 0x7A for c in ctype):
            raise PTError(114, pos, "chunk_type")
        if length > 1 << 30:
            raise PTError(112, pos + 4, "chunk_length")
        if pos + 12 + length > len(data):
            raise PTError(111, pos + 4, "chunk_length")
        payload = data[pos + 8:pos + 8 + length]
        if struct.unpack_from("<I", data, pos + 8 + length)[0] != crc32c(data[pos:pos + 8 + length]):
            raise PTError(113, pos + 8 + length, "crc")
        critical = 0x41 <= ctype[0] <= 0x5A
        if ctype == b"MEND":
            if length:
                raise PTError(117, pos + 4, "MEND")
            if not chunks:
                raise PTError(116, pos, "MEND")
            if pos + 12 < len(data):
                raise PTError(118, pos + 12, "MEND")
            complete = True
            chunks.append((ctype, payload, pos))
            break
        if critical and ctype not in KNOWN_CRITICAL:
            raise PTError(115, pos, ctype.decode())
        if not chunks and ctype not in CONTENT_HEADERS:
            raise PTError(116, pos, ctype.decode())
        if chunks and ctype in CONTENT_HEADERS:
            raise PTError(116, pos, ctype.decode())
        if ctype == b"meta":
            if meta_seen:
                raise PTError(116, pos, "meta")
            meta_seen = True
        chunks.append((ctype, payload, pos))
        pos += 12 + length
    return chunks, complete


class PTStream:
    """A decoded PT stream: header, the mesh at its finest level and every split."""

    def __init__(self, data):
        self.ops = []          # [(chunk offset, [ops])], one list per coded string
        self.splits = []       # [(vs, vt, moved slots, e)]
        self.batches = []      # [split_count]
        self.positions, self.values, self.tets = [], [], []
        self.has_base = False
        chunks, self.complete = frame(data)
        self.h = None
        if not chunks:
            return  # a prefix of the file header alone (2.5.1)
        if chunks[0][0] != b"THDR":
            raise PTError(904, 12, chunks[0][0].decode(), "not a PT stream")
        self.h = h = parse_thdr(chunks[0][1], chunks[0][2])
        self.models = Models()
        for ctype, payload, p in chunks[1:]:
            critical = 0x41 <= ctype[0] <= 0x5A
            if ctype == b"MEND":
                if not self.has_base:
                    raise PTError(116, p, "MEND")
                if (len(self.batches) != h.batch_count or sum(self.batches) != h.S
                        or len(self.tets) != h.tet_count):
                    raise PTError(304, p, "MEND")
                continue
            if not critical:
                continue
            if ctype == b"TBAS":
                if self.has_base:
                    raise PTError(116, p, "TBAS")
                self.base_mesh(payload, p + 8)
                self.has_base = True
            elif ctype == b"TSPL":
                if not self.has_base:
                    raise PTError(116, p, "TSPL")
                self.batch(payload, p)
            else:
                raise PTError(116, p, ctype.decode())
        self.level = len(self.splits)

    # 7.4
    def base_mesh(self, payload, q):
        h = self.h
        ops = []
        self.ops.append((q - 8, ops))
        try:
            try:
                rd = RangeDecoder(payload, self.models, ops)
            except ValueError:
                raise PTError(206, q, "TBAS", "first byte not 0")
            pos, val = [0, 0, 0], [0] * h.field_count
            for v in range(h.base_vertex_count):
                for a in range(3):
                    pos[a] += rd.signed(("base_position", a))
                    if not 0 <= pos[a] < 1 << h.position_bits:
                        raise SplitInvalid("coordinate")
                for f in range(h.field_count):
                    val[f] += rd.signed(("base_field", f))
                    if not 0 <= val[f] < 1 << h.fields[f][0]:
                        raise SplitInvalid("value")
                self.positions.append(tuple(pos))
                self.values.append(tuple(val))
            used = 0
            for t in range(h.base_tet_count):
                corners = []
                for j in range(4):
                    if rd.bit(("base_new_vertex", j)) == 1:
                        if used >= h.base_vertex_count:
                            raise SplitInvalid("too many vertices")
                        corners.append(used)
                        used += 1
                    else:
                        back = rd.unsigned("base_back_reference")
                        if back >= used:
                            raise SplitInvalid("back reference")
                        corners.append(used - 1 - back)
                self.tets.append(corners)
            if used != h.base_vertex_count:
                raise SplitInvalid("unused vertices")
        except StringEnd:
            raise PTError(206, q, "TBAS", "string ends early")
        except SplitInvalid as e:
            raise PTError(302, q, "TBAS", str(e))
        if rd.pos != len(payload):
            raise PTError(206, q, "TBAS", "bytes left over")
        P = self.positions
        for t in self.tets:
            if len(set(t)) != 4 or orient3d(*(P[c] for c in t)) != 1:
                raise PTError(302, q, "TBAS", "tet not positive")
        incident = {}
        for slot, t in enumerate(self.tets):
            for c in t:
                incident.setdefault(c, []).append(slot)
        for v in range(h.base_vertex_count):
            if not Link(v, [(s, self.tets[s]) for s in incident[v]]).sphere_or_disk():
                raise PTError(302, q, "TBAS", f"link of {v}")
        self.incident = {v: set(s) for v, s in incident.items()}

    # 7.7
    def batch(self, payload, p):
        h = self.h
        q = p + 8
        if len(self.batches) >= h.batch_count:
            raise PTError(304, p, "TSPL")
        if len(payload) < 4:
            raise PTError(117, p + 4, "TSPL.chunk_length")
        split_count = struct.unpack_from("<I", payload)[0]
        if not 1 <= split_count <= h.S - sum(self.batches):
            raise PTError(304, q, "TSPL.split_count")
        ops = []
        self.ops.append((p, ops))
        try:
            try:
                rd = RangeDecoder(payload[4:], self.models, ops)
            except ValueError:
                raise PTError(206, q + 4, "TSPL", "first byte not 0")
            n0 = len(self.positions)
            done, v, previous_group = 0, 0, 0
            while done < split_count:
                if v == n0:
                    raise SplitInvalid("flags end")
                group_end = min(v + SPLIT_GROUP, n0)
                previous_group = rd.bit(("group_flag", previous_group))
                if previous_group == 0:
                    v = group_end
                    continue
                split_in_group = False
                while v < group_end and done < split_count:
                    if v == group_end - 1 and not split_in_group:
                        flag = 1  # implied: the group holds a split vertex
                    else:
                        flag = rd.bit(("split_flag", min(len(self.incident[v]) // 2, 15)))
                    if flag == 1:
                        self.vertex_split(rd, v)
                        done += 1
                        split_in_group = True
                    v += 1
        except StringEnd:
            raise PTError(206, q + 4, "TSPL", "string ends early")
        except SplitInvalid as e:
            raise PTError(303, q + 4, "TSPL.vertex_split", str(e))
        if rd.pos != len(payload) - 4:
            raise PTError(206, q + 4, "TSPL", "bytes left over")
        self.batches.append(split_count)

    def vertex_split(self, rd, vs):
        h = self.h
        L = Link(vs, [(s, self.tets[s]) for s in self.incident[vs]])
        if len(L.vertices) > MAX_LINK:
            raise SplitInvalid("link too large")
        cut = self.cut(rd, L)
        k = len(cut)
        N = len(self.positions)
        vt_pos = []
        for a in range(3):
            S = sum(self.positions[c][a] for c in cut)
            pr = min(max(2 * S // k - self.positions[vs][a], 0), (1 << h.position_bits) - 1)
            x = pr + rd.signed(("position", a))
            if not 0 <= x < 1 << h.position_bits:
                raise SplitInvalid("vt coordinate")
            vt_pos.append(x)
        vt_val = []
        for f in range(h.field_count):
            S = sum(self.values[c][f] for c in cut)
            top = (1 << h.fields[f][0]) - 1
            pr = min(max(2 * S // k - self.values[vs][f], 0), top)
            x = pr + rd.signed(("field", f))
            if not 0 <= x <= top:
                raise SplitInvalid("vt value")
            vt_val.append(x)
        closed = not L.has_boundary()
        e = k if closed else k - 1
        edges = [(cut[i], cut[(i + 1) % k]) for i in range(e)]
        if len(self.tets) + e > h.tet_count:
            raise SplitInvalid("more tets than tet_count")
        # 7.6.3 the region
        seeds, blocks = set(), set()
        for a, b in edges:
            if (b, a) not in L.edge_slot or (a, b) not in L.edge_slot:
                raise SplitInvalid("cut along the link's boundary")
            seeds.add(L.edge_slot[(b, a)])
            blocks.add(L.edge_slot[(a, b)])
        if seeds & blocks:
            raise SplitInvalid("cut does not separate")
        consecutive = {frozenset(x) for x in edges}
        region, stack = set(seeds), list(seeds)
        while stack:
            p_, q_, r_ = L.tri[stack.pop()]
            for a, b in ((p_, q_), (q_, r_), (r_, p_)):
                if frozenset((a, b)) in consecutive:
                    continue
                o = L.edge_slot.get((b, a))
                if o is not None and o not in region:
                    region.add(o)
                    stack.append(o)
        if region & blocks:
            raise SplitInvalid("region reaches a block")
        # 7.6.4 checks
        P = self.positions + [tuple(vt_pos)]
        for slot in sorted(region):
            t = [N if c == vs else c for c in self.tets[slot]]
            if orient3d(*(P[c] for c in t)) != 1:
                raise SplitInvalid("moved tet not positive")
        for a, b in edges:
            if orient3d(P[N], P[a], P[b], P[vs]) != 1:
                raise SplitInvalid("new tet not positive")
        # changes
        self.positions.append(tuple(vt_pos))
        self.values.append(tuple(vt_val))
        self.incident[N] = set()
        for slot in region:
            t = self.tets[slot]
            t[t.index(vs)] = N
            self.incident[vs].discard(slot)
            self.incident[N].add(slot)
        for a, b in edges:
            slot = len(self.tets)
            self.tets.append([N, a, b, vs])
            for c in (N, a, b, vs):
                self.incident[c].add(slot)
        self.splits.append((vs, N, sorted(region), e, [[N, a, b, vs] for a, b in edges]))

    def cut(self, rd, L):
        """7.7.2: the walk."""
        m = len(L.vertices)
        if not L.has_boundary():
            c0i = rd.small("cut_start")
            if c0i >= m:
                raise SplitInvalid("cut_start")
            c0 = L.vertices[c0i]
            R = L.rotation(c0, min(L.neighbours[c0]))
            j = rd.small(("cut_first", min(len(R), 15)))
            if j >= len(R):
                raise SplitInvalid("cut_first")
            walk, prev, cur = [c0], c0, R[j]
            boundary = False
        else:
            Bv = L.boundary_vertices
            b = rd.small("path_start")
            if b >= len(Bv):
                raise SplitInvalid("path_start")
            c0 = Bv[b]
            R = L.rotation(c0)
            if len(R) < 3:
                raise SplitInvalid("path start without an interior edge")
            t = rd.small(("path_first", min(len(R), 15)))
            if t > len(R) - 3:
                raise SplitInvalid("path_first")
            walk, prev, cur = [c0], c0, R[t + 1]
            boundary = True
        bset = set(L.boundary_vertices)
        while True:
            if cur == c0:
                if boundary:
                    raise SplitInvalid("open cut back at its start")
                return walk
            if cur in walk:
                raise SplitInvalid("cut revisits a vertex")
            walk.append(cur)
            if boundary and cur in bset:
                return walk
            R = L.rotation(cur, prev)
            t = rd.small(("turn", min(len(R), 15)))
            if t > len(R) - 2:
                raise SplitInvalid("turn")
            prev, cur = cur, R[t + 1]

    # 7.6.5 and 7.8
    def set_level(self, n):
        n = max(0, min(n, len(self.splits)))
        while self.level > n:
            self.level -= 1
            vs, vt, moved, e, _ = self.splits[self.level]
            del self.tets[len(self.tets) - e:]
            for slot in moved:
                t = self.tets[slot]
                t[t.index(vt)] = vs
        while self.level < n:
            vs, vt, moved, e, new = self.splits[self.level]
            for slot in moved:
                t = self.tets[slot]
                t[t.index(vs)] = vt
            self.tets.extend([list(t) for t in new])
            self.level += 1

    def canonical(self):
        h = self.h
        if h is None:
            return b"mrsv-canonical-empty 1\n"
        if not self.has_base:
            return f"mrsv-canonical-tets 1 0 0 {h.position_bits} {h.field_count}\n".encode()
        V = h.base_vertex_count + self.level
        out = bytearray(f"mrsv-canonical-tets 1 {V} {len(self.tets)} {h.position_bits} {h.field_count}\n".encode())
        for v in range(V):
            out += struct.pack("<3I", *self.positions[v])
            out += struct.pack("<%dI" % h.field_count, *self.values[v])
        for t in self.tets:
            out += struct.pack("<4I", *t)
        return bytes(out)

    def canonical_at(self, vertices):
        """The level with `vertices` vertices, as `mrsv decode --canonical --vertices` picks it (7.8)."""
        self.set_level(vertices - self.h.base_vertex_count)
        return self.canonical()


def main(argv):
    args = list(argv[1:])
    vertices = None
    if "--vertices" in args:
        i = args.index("--vertices")
        vertices = int(args[i + 1])
        del args[i:i + 2]
    data = open(args[0], "rb").read()
    try:
        s = PTStream(data)
    except PTError as e:
        print(str(e))
        return 1
    out = s.canonical() if vertices is None or not s.has_base else s.canonical_at(vertices)
    if len(args) > 1:
        open(args[1], "wb").write(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
