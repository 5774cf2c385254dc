#!/usr/bin/env python3
"""An independent reconstructor of 2-D grid streams (spec 8), written from the text alone.

It reads the stream's chunks (2.3) to find the stages of 8.7, obtains each stage's
decoded samples from a grid decoder (the reference `mrsv decode --canonical` of the
stage's prefix: grid decoding is covered by the grid vectors), and does everything
of 8.2 to 8.7 itself in plain Python integers: exact orient and incircle, the
Devillers-Teillaud perturbation over insertion ranks, a Delaunay triangulation kept
by Lawson flips, greedy insertion by exact rational errors with ties to the smallest
index, the border rule and the stages. It shares no code with the reference
reconstructor, so agreeing hashes check both.

No-data (8.1): a position marked in the mask takes the sample the synthesis gives
it. `mrsv decode` writes the no-data value there instead, so for a stream with a
mask this script decodes a second copy of each prefix with the GMSK and GRES chunks
removed and `has_mask` and `has_residual` cleared (the bands are coded without
skipped positions, 5.3, so they decode the same; only the residual skips masked
positions, 5.5), and takes the masked positions' samples from it: the residual is
taken as 0 there, which is how this script reads "computed as if it were not
marked" (the residual is not coded at masked positions, so 8.1 leaves r open there;
the reference agrees on both mask vectors). The masked positions are those where the
first copy holds the no-data value (a terrain sample never equals -32768).

  python3 conformance/reconstruct_reference.py IN.mrsv OUT --mrsv PATH/TO/mrsv
      [--max-error E] [--triangles N] [--progressive] [--no-border-rule] [--remove-vertices]
      [--no-border-cleanup]
      [--region X0,Y0,X1,Y1]
      [--bytes N] [--levels K] [--canonical]
  writes the canonical output of 8.2 to OUT (--canonical is accepted and implied);
  refuses (exit 1, a message) what 8.1 and 8.7 refuse.
"""
import argparse
import heapq
import os
import struct
import subprocess
import sys
import tempfile
from fractions import Fraction

SIGNATURE = bytes([0x8E, 0x4D, 0x52, 0x53, 0x56, 0x0D, 0x0A, 0x1A, 0x0A])
INTEGER_TYPES = {1: ("uint8", "B", 1), 2: ("int16", "h", 2), 3: ("uint16", "H", 2), 4: ("int32", "i", 4)}
TYPE_NAMES = {1: "uint8", 2: "int16", 3: "uint16", 4: "int32", 5: "float32", 6: "float64"}


class Refused(Exception):
    pass


# --- the stream: chunks (2.3), GHDR (3.1), WHDR (5.2), bands (4.4) ---------------------

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


def chunks(data):
    """(type, start, end) of each complete chunk; an incomplete last chunk is ignored (2.5.1)."""
    out, p = [], 12
    while p + 8 <= len(data):
        length = struct.unpack_from("<I", data, p + 4)[0]
        end = p + 12 + length
        if end > len(data):
            break
        out.append((data[p:p + 4], p, end))
        p = end
    return out


class Stream:
    def __init__(self, data):
        if len(data) < 12 or data[:9] != SIGNATURE:
            raise Refused("not an MRSV stream")
        self.data = data
        self.chunks = chunks(data)
        if not self.chunks or self.chunks[0][0] != b"GHDR":
            raise Refused("not a grid stream (no GHDR)")
        _, p, _ = self.chunks[0]
        q = p + 8
        (self.num_dims, self.sample_type, self.coding, self.grid_flags,
         self.sx, self.sy, self.sz, self.nodata_bits) = struct.unpack_from("<BBBBIIIQ", data, q)
        self.levels = [0, 0, 0]
        self.has_mask = False
        for t, p, e in self.chunks:
            if t == b"WHDR":
                q = p + 8
                self.levels = list(data[q + 1:q + 4])
                self.has_mask = bool(data[q + 6] & 1)

    def band_levels(self):
        """The level of each band of the plan, in band order (4.4): the scaling block
        (level M), then the detail bands of levels M..1, one per nonzero mask of the
        axes split at that level."""
        m = max(self.levels)
        out = [m]
        for j in range(m, 0, -1):
            split = sum(1 for a in range(3) if self.levels[a] >= j)
            out += [j] * ((1 << split) - 1)
        return out

    def stages(self, levels_k=0):
        """8.7: the (end offset, s) of each stage of the bytes read."""
        gbnd = [e for t, _, e in self.chunks if t == b"GBND"]
        last = self.chunks[-1][2]
        if self.coding == 0 or not gbnd:
            stages = [(last, 0)]
        else:
            lv = self.band_levels()
            big_l = max(self.levels)
            stages = [(gbnd[0], big_l)]
            for l in range(big_l, 0, -1):
                idx = [i for i, x in enumerate(lv) if x == l and i > 0]
                if idx and idx[-1] < len(gbnd):
                    stages.append((gbnd[idx[-1]], l - 1))
            kept = [st for st in stages if st[1] >= levels_k]
            if not kept:
                raise Refused(f"--levels {levels_k} leaves no stage")
            if levels_k == 0:
                kept[-1] = (last, kept[-1][1])  # the last stage ends with the last byte read
            return kept
        if levels_k > 0:
            raise Refused(f"--levels {levels_k} leaves no stage")
        return stages


def strip_mask(data):
    """The prefix without GMSK and GRES, has_mask and has_residual cleared (see the header)."""
    out = bytearray(data[:12])
    for t, p, e in chunks(data):
        if t in (b"GMSK", b"GRES"):
            continue
        piece = bytearray(data[p:e])
        if t == b"WHDR":
            piece[8 + 6] &= ~3
            struct.pack_into("<I", piece, len(piece) - 4, crc32c(bytes(piece[:-4])))
        out += piece
    return bytes(out)


def decode_samples(mrsv, data, stream):
    """The sample field (8.1) of a prefix, via `mrsv decode --canonical`."""
    def run(prefix):
        with tempfile.TemporaryDirectory(prefix="mrsv-rref-") as tmp:
            src, dst = os.path.join(tmp, "in.mrsv"), os.path.join(tmp, "out.bin")
            with open(src, "wb") as f:
                f.write(prefix)
            r = subprocess.run([mrsv, "decode", "--quiet", "--canonical", src, dst], capture_output=True)
            if r.returncode != 0 or not os.path.exists(dst):
                raise Refused("the grid decoder failed: " + (r.stdout + r.stderr).decode(errors="replace"))
            out = open(dst, "rb").read()
        nl = out.index(b"\n")
        head = out[:nl].split()
        count = int(head[7])
        if count == 0:
            raise Refused("the bytes read hold no samples")
        name, code, size = INTEGER_TYPES[stream.sample_type]
        return list(struct.unpack("<%d%s" % (count, code), out[nl + 1:nl + 1 + count * size]))

    values = run(data)
    if stream.has_mask:
        bits = 8 * INTEGER_TYPES[stream.sample_type][2]
        nodata = stream.nodata_bits
        if stream.sample_type in (2, 4) and nodata >= 1 << (bits - 1):
            nodata -= 1 << bits
        plain = run(strip_mask(data))
        values = [b if a == nodata else a for a, b in zip(values, plain)]
    return values


# --- 8.3: predicates and the perturbation -----------------------------------------------

def orient(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def incircle(a, b, c, d):
    adx, ady = a[0] - d[0], a[1] - d[1]
    bdx, bdy = b[0] - d[0], b[1] - d[1]
    cdx, cdy = c[0] - d[0], c[1] - d[1]
    al, bl, cl = adx * adx + ady * ady, bdx * bdx + bdy * bdy, cdx * cdx + cdy * cdy
    return (adx * (bdy * cl - bl * cdy) - ady * (bdx * cl - bl * cdx) + al * (bdx * cdy - bdy * cdx))


# --- 8.4 to 8.7: the mesh ----------------------------------------------------------------

class Mesh:
    def __init__(self, X, Y):
        self.X, self.Y = X, Y
        self.rank = {}        # vertex (grid index) -> rank (8.5)
        self.edge = {}        # directed edge (u, v) -> w of the counter-clockwise triangle (u, v, w)
        self.tris = {}        # canonical triangle -> [id, points it holds]
        self.next_id = 0
        self.values = None
        self.step = 1
        self.heap = []
        self.border = True
        corners = [0, X - 1, X * Y - 1, X * (Y - 1)]
        for c in corners:
            self.rank[c] = len(self.rank)
        a, b, c, d = corners
        # The rectangle as two triangles, then Lawson on the diagonal (8.4, informative).
        self.removed, self.added = [], []
        if self.conflicts(a, b, c, d):
            self._add(a, b, d)
            self._add(b, c, d)
        else:
            self._add(a, b, c)
            self._add(a, c, d)

    def xy(self, i):
        return (i % self.X, i // self.X)

    # triangles ------------------------------------------------------------------------
    def _key(self, a, b, c):
        m = min(a, b, c)
        return (a, b, c) if a == m else (b, c, a) if b == m else (c, a, b)

    def _add(self, a, b, c):
        assert orient(self.xy(a), self.xy(b), self.xy(c)) > 0, "a flat or clockwise triangle"
        self.edge[(a, b)] = c
        self.edge[(b, c)] = a
        self.edge[(c, a)] = b
        k = self._key(a, b, c)
        self.tris[k] = [self.next_id, []]
        self.next_id += 1
        self.added.append(k)
        return k

    def _remove(self, a, b, c):
        del self.edge[(a, b)], self.edge[(b, c)], self.edge[(c, a)]
        k = self._key(a, b, c)
        self.removed.append((k, self.tris.pop(k)))

    def conflicts(self, a, b, c, d):
        """8.3: d conflicts with the counter-clockwise (a, b, c)."""
        pa, pb, pc, pd = self.xy(a), self.xy(b), self.xy(c), self.xy(d)
        det = incircle(pa, pb, pc, pd)
        if det != 0:
            return det > 0
        for p in sorted((a, b, c, d), key=lambda v: -self.rank[v])[:2]:
            if p == d:
                return False
            if p == a:
                o = orient(pd, pb, pc)
            elif p == b:
                o = orient(pa, pd, pc)
            else:
                o = orient(pa, pb, pd)
            if o != 0:
                return o > 0
        raise AssertionError("two steps did not decide (8.3)")

    def _legalize(self, p, u, v):
        """(u, v, p) is a triangle; flip (u, v) while the vertex across it conflicts."""
        stack = [(u, v)]
        while stack:
            u, v = stack.pop()
            if (u, v) not in self.edge or self.edge[(u, v)] != p:
                continue
            q = self.edge.get((v, u))
            if q is None:
                continue
            if self.conflicts(u, v, p, q):
                self._remove(u, v, p)
                self._remove(v, u, q)
                self._add(u, q, p)
                self._add(q, v, p)
                stack.append((u, q))
                stack.append((q, v))

    def locate(self, g):
        """A triangle holding the point g (inside or on its border)."""
        pg = self.xy(g)
        for k in self.tris:
            a, b, c = k
            pa, pb, pc = self.xy(a), self.xy(b), self.xy(c)
            if orient(pa, pb, pg) >= 0 and orient(pb, pc, pg) >= 0 and orient(pc, pa, pg) >= 0:
                return k
        raise AssertionError("point outside the mesh")

    def insert(self, g, tri):
        """Insert the point g, held by triangle tri; redistribute the points of the cavity."""
        self.rank[g] = len(self.rank)
        self.removed, self.added = [], []
        a, b, c = tri
        pg = self.xy(g)
        on = None
        for (u, v, w) in ((a, b, c), (b, c, a), (c, a, b)):
            if orient(self.xy(u), self.xy(v), pg) == 0:
                on = (u, v, w)
        if on is None:
            self._remove(a, b, c)
            for u, v in ((a, b), (b, c), (c, a)):
                self._add(u, v, g)
            for u, v in ((a, b), (b, c), (c, a)):
                self._legalize(g, u, v)
        else:
            u, v, w = on
            x = self.edge.get((v, u))
            self._remove(u, v, w)
            self._add(v, w, g)
            self._add(w, u, g)
            if x is not None:
                self._remove(v, u, x)
                self._add(u, x, g)
                self._add(x, v, g)
            outer = [(v, w), (w, u)] + ([(u, x), (x, v)] if x is not None else [])
            for s, t in outer:
                self._legalize(g, s, t)
        points = []
        for k, (tid, pts) in self.removed:
            points.extend(pts)
        self._distribute(points, [k for k in dict.fromkeys(self.added) if k in self.tris])

    def _distribute(self, points, keys):
        live = [k for k in keys if k in self.tris]
        geo = [(k, self.xy(k[0]), self.xy(k[1]), self.xy(k[2])) for k in live]
        seen = set()
        for p in points:
            if p in seen or p in self.rank:
                continue
            seen.add(p)
            pp = self.xy(p)
            for k, pa, pb, pc in geo:
                if orient(pa, pb, pp) >= 0 and orient(pb, pc, pp) >= 0 and orient(pc, pa, pp) >= 0:
                    self.tris[k][1].append(p)
                    break
            else:
                raise AssertionError("a point of the cavity left outside it")
        for k in live:
            self._push(k)

    # errors (8.5) -----------------------------------------------------------------------
    def on_side(self, g):
        x, y = self.xy(g)
        return x == 0 or y == 0 or x == self.X - 1 or y == self.Y - 1

    def _push(self, k):
        tid, pts = self.tris[k]
        if not pts:
            return
        a, b, c = k
        pa, pb, pc = self.xy(a), self.xy(b), self.xy(c)
        va, vb, vc = self.values[a], self.values[b], self.values[c]
        area = orient(pa, pb, pc)
        best = None
        for g in pts:
            if self.border and self.on_side(g):
                continue
            pg = self.xy(g)
            num = abs(area * self.values[g] - (orient(pg, pb, pc) * va + orient(pa, pg, pc) * vb
                                                + orient(pa, pb, pg) * vc))
            if num == 0:
                continue
            e = Fraction(num, area)
            if best is None or e > best[0] or (e == best[0] and g < best[1]):
                best = (e, g)
        if best is not None:
            heapq.heappush(self.heap, (-best[0], best[1], tid, k))

    def worst(self):
        while self.heap:
            ne, g, tid, k = self.heap[0]
            if k in self.tris and self.tris[k][0] == tid:
                return -ne, g, k
            heapq.heappop(self.heap)
        return None

    def rebuild(self):
        """Assign every lattice point that is not a vertex to one triangle holding it."""
        step, X, Y = self.step, self.X, self.Y
        xs = sorted(set(list(range(0, X, step)) + [X - 1]))
        ys = sorted(set(list(range(0, Y, step)) + [Y - 1]))
        for k in self.tris:
            self.tris[k][1] = []
        self.heap = []
        assigned = set(self.rank)
        for k in self.tris:
            a, b, c = k
            pa, pb, pc = self.xy(a), self.xy(b), self.xy(c)
            x0, x1 = min(pa[0], pb[0], pc[0]), max(pa[0], pb[0], pc[0])
            y0, y1 = min(pa[1], pb[1], pc[1]), max(pa[1], pb[1], pc[1])
            pts = self.tris[k][1]
            for y in ys:
                if y < y0 or y > y1:
                    continue
                for x in xs:
                    if x < x0 or x > x1:
                        continue
                    g = x + X * y
                    if g in assigned:
                        continue
                    pg = (x, y)
                    if orient(pa, pb, pg) >= 0 and orient(pb, pc, pg) >= 0 and orient(pc, pa, pg) >= 0:
                        pts.append(g)
                        assigned.add(g)
        assert len(assigned) == len(xs) * len(ys) + len([v for v in self.rank if v not in
                                                          {x + X * y for x in xs for y in ys}])
        for k in self.tris:
            self._push(k)

    # stages (8.6, 8.7) ----------------------------------------------------------------
    def border_rule(self, bound):
        X, Y, step = self.X, self.Y, self.step
        sides = [[(x, 0) for x in range(X)], [(x, Y - 1) for x in range(X)],
                 [(0, y) for y in range(Y)], [(X - 1, y) for y in range(Y)]]
        for n, side in enumerate(sides):
            size = X if n < 2 else Y
            pos = sorted(set(list(range(0, size, step)) + [size - 1]))
            pts = [side[t] for t in pos]
            ids = [x + X * y for x, y in pts]
            u = [self.values[i] for i in ids]
            isv = [i in self.rank for i in ids]
            new = []
            vert = [k for k in range(len(pos)) if isv[k]]
            work = list(zip(vert, vert[1:]))
            while work:
                i, j = work.pop()
                if j - i < 2:
                    continue
                ti, tj = pos[i], pos[j]
                best = None
                for k in range(i + 1, j):
                    tk = pos[k]
                    num = abs(u[k] * (tj - ti) - u[i] * (tj - tk) - u[j] * (tk - ti))
                    if best is None or num > best[0]:
                        best = (num, k)
                num, k = best
                if Fraction(num, tj - ti) > bound:
                    new.append(k)
                    work.append((i, k))
                    work.append((k, j))
            for k in sorted(new):
                g = ids[k]
                self.insert(g, self.holder(g))

    def holder(self, g):
        for k, (tid, pts) in self.tris.items():
            if g in pts:
                return k
        return self.locate(g)

    def greedy(self, bound, limit):
        while True:
            w = self.worst()
            if w is None:
                return
            e, g, k = w
            if bound is not None and e <= bound:
                return
            if limit is not None and len(self.tris) >= limit:
                return
            self.insert(g, k)

    def check_delaunay(self):
        """8.4: no vertex across an edge conflicts with the triangle on the other side."""
        for (u, v), p in self.edge.items():
            q = self.edge.get((v, u))
            if q is not None:
                assert not self.conflicts(u, v, p, q), "not Delaunay at edge %d-%d" % (u, v)

    def canonical(self):
        verts = sorted(self.rank)
        number = {v: n for n, v in enumerate(verts)}
        out = bytearray(b"mrsv-canonical-grid-mesh 1 2 %d %d\n" % (len(verts), len(self.tris)))
        for v in verts:
            x, y = self.xy(v)
            out += struct.pack("<IIIi", x, y, 0, self.values[v])
        cells = []
        for a, b, c in self.tris:
            t = (number[a], number[b], number[c])
            m = t.index(min(t))
            cells.append(t[m:] + t[:m])
        for t in sorted(cells):
            out += struct.pack("<III", *t)
        return bytes(out)


def parse_bound(text):
    """8.5: digits, at most one '.', at most 9 digits after it, at most 2^31; exact."""
    if not text or text.count(".") > 1 or not all(ch.isdigit() or ch == "." for ch in text):
        raise Refused(f"--max-error '{text}' is not a decimal")
    whole, _, frac = text.partition(".")
    if len(frac) > 9 or not (whole + frac):
        raise Refused(f"--max-error '{text}' is not a decimal")
    e = Fraction(int(whole + frac or "0"), 10 ** len(frac))
    if e > 2 ** 31:
        raise Refused(f"--max-error {text} above 2^31")
    return e


def parse_region(text, X, Y):
    """8.1 a region: "x0,y0,x1,y1", a non-empty box inside the X x Y grid."""
    v = [int(t) for t in text.split(",")]
    if len(v) != 4 or not (0 <= v[0] < v[2] <= X and 0 <= v[1] < v[3] <= Y):
        raise Refused(f"--region {text}: not a box inside the {X} x {Y} grid")
    return v


def crop(values, X, box):
    """The samples of box (x0, y0, x1, y1) of a field X samples wide, x fastest."""
    x0, y0, x1, y1 = box
    return [values[x + X * y] for y in range(y0, y1) for x in range(x0, x1)]


def reconstruct(data, mrsv, max_error=None, triangles=None, progressive=False, border=True, levels=0,
                log=None, remove=False, region=None, border_cleanup=True):
    stream = Stream(data)
    if stream.sample_type not in INTEGER_TYPES:
        raise Refused(f"{TYPE_NAMES.get(stream.sample_type, '?')} samples: 8.1 accepts integer samples only")
    if stream.num_dims != 2:
        raise Refused(f"{stream.num_dims}-D grid: this reconstructor does 2-D grids (8.1)")
    X, Y = stream.sx, stream.sy
    box = None
    if region is not None:  # 8.1: the box's samples of the whole decode, one stage
        if progressive or levels:
            raise Refused("8.1: a region is meshed in one stage, without --progressive or --levels")
        box = parse_region(region, X, Y)
        X, Y = box[2] - box[0], box[3] - box[1]
    if not (2 <= X <= 65536 and 2 <= Y <= 65536):
        raise Refused(f"a {X} x {Y} grid: 8.1 accepts 2 <= X, Y <= 65536")
    bound = parse_bound(max_error) if max_error is not None else None
    if bound is None and triangles is None:
        raise Refused("give --max-error, --triangles or both")
    if remove and (bound is None or progressive):
        raise Refused("8.8: the vertex-removal pass needs --max-error and no --progressive")
    stages = [(len(data), 0)] if box else stream.stages(levels)
    if not progressive:
        stages = stages[-1:]
    mesh = Mesh(X, Y)
    mesh.border = border and bound is not None
    for end, s in stages:
        mesh.values = decode_samples(mrsv, data[:end], stream)
        if box:
            mesh.values = crop(mesh.values, stream.sx, box)
        mesh.step = 1 << s
        sb = bound * (1 << (s + 1)) if bound is not None and s > 0 else bound
        mesh.heap = []
        if mesh.border:
            # The border rule inserts side points only; the greedy errors are computed after it.
            mesh.rebuild()
            mesh.border_rule(sb)
        mesh.rebuild()
        mesh.greedy(sb, triangles)
        mesh.check_delaunay()
        if log:
            log(f"stage s={s} end={end}: {len(mesh.rank)} vertices, {len(mesh.tris)} triangles")
    cleanup = border_cleanup and mesh.border and not progressive
    if remove or cleanup:  # 8.8: 9.7's pass, as quadtree_reference.py writes it from chapter 9
        import quadtree_reference as qr  # here: that module imports this one
        field = qr.Field(X, Y, mesh.values)
        tris = [(mesh.xy(a), mesh.xy(b), mesh.xy(c)) for a, b, c in mesh.tris]
        if remove:
            return qr.canonical(field, qr.remove_vertices(field, bound, tris))
        return qr.canonical(field, qr.remove_vertices(field, bound, tris, passes=1, border_zone=True))
    return mesh.canonical()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--mrsv", required=True, help="the grid decoder: an mrsv binary (for `decode` only)")
    parser.add_argument("--max-error")
    parser.add_argument("--triangles", type=int)
    parser.add_argument("--progressive", action="store_true")
    parser.add_argument("--no-border-rule", action="store_true")
    parser.add_argument("--remove-vertices", action="store_true")
    parser.add_argument("--no-border-cleanup", action="store_true")
    parser.add_argument("--region")
    parser.add_argument("--bytes", type=int)
    parser.add_argument("--levels", type=int, default=0)
    parser.add_argument("--canonical", action="store_true", help="(implied)")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()
    data = open(args.input, "rb").read()
    if args.bytes is not None:
        data = data[:args.bytes]
    try:
        if args.triangles is not None and args.triangles < 1:
            raise Refused("--triangles must be a positive integer")
        out = reconstruct(data, args.mrsv, args.max_error, args.triangles, args.progressive,
                          not args.no_border_rule, args.levels,
                          None if args.quiet else (lambda m: print(m, file=sys.stderr)), args.remove_vertices,
                          args.region, not args.no_border_cleanup)
    except Refused as e:
        print(f"refused: {e}", file=sys.stderr)
        return 1
    with open(args.output, "wb") as f:
        f.write(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
