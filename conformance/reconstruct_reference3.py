#!/usr/bin/env python3
"""An independent reconstructor of 3-D grid streams (spec 10), written from the text alone.

Like reconstruct_reference.py (chapter 8), it reads the stream's chunks to find the
stages of 8.7 and obtains each stage's sample field (8.1) from a grid decoder (the
reference `mrsv decode --canonical` of the stage's prefix, with the same mask handling);
everything of 10.2 to 10.7 it does itself in plain Python integers:

  - orient and insphere of 10.2, exact, and the conflict test with the perturbation of
    10.2 (five points in decreasing lexicographic order);
  - DT(V) (10.2) kept by Bowyer-Watson on the finite tets only: the cavity of a new point
    is every tet it conflicts with (a search from the tets that hold it through faces of
    conflicting tets), and each boundary face of the cavity is joined to the point,
    except the faces on a side of the box that hold the point (those are dropped: the
    point lies in them). It uses no infinite vertex and none of 10.3's in-circle rule;
    after every stage it checks the mesh against the definition of 10.2: the tets are
    positive, their orient values add up to 6 (X-1)(Y-1)(Z-1), and no vertex across a
    face conflicts with the tet on the other side (with --check-global, no vertex at all
    conflicts with any tet: R10.2-3 word for word);
  - the errors of 10.4 as exact Fractions, the greedy order of 10.5 (largest error,
    then smallest index), the tet limit, the trilinear pre-pass of 10.6 and the stages
    and bounds of 10.7.

It shares no code with the reference reconstructor, so agreeing hashes check both.

  python3 conformance/reconstruct_reference3.py IN.mrsv OUT --mrsv PATH/TO/mrsv
      [--max-error E] [--tets N] [--progressive] [--distance mesh|trilinear]
      [--bytes N] [--levels K] [--canonical] [--check-global]
  writes the canonical output of 8.2 to OUT (--canonical is accepted and implied);
  refuses (exit 1, a message) what 10.1 and 8.7 refuse.
"""
import argparse
import heapq
import os
import struct
import sys
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import reconstruct_reference as rr  # noqa: E402  (stream chunks, stages of 8.7, the sample field of 8.1)

Refused = rr.Refused
CAP = Fraction(1 << 34)


# --- 10.2: predicates --------------------------------------------------------------------

def orient(a, b, c, d):
    bx, by, bz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    cx, cy, cz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    dx, dy, dz = d[0] - a[0], d[1] - a[1], d[2] - a[2]
    return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx)


def det3(r0, r1, r2):
    return (r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
            + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]))


def insphere(a, b, c, d, e):
    """- det of the rows (p'x, p'y, p'z, |p'|^2), p' = p - e, for p = a, b, c, d."""
    rows = []
    for p in (a, b, c, d):
        x, y, z = p[0] - e[0], p[1] - e[1], p[2] - e[2]
        rows.append((x, y, z, x * x + y * y + z * z))
    det = 0
    for col in range(4):
        minor = [[r[k] for k in range(4) if k != col] for r in rows[1:]]
        det += (-1) ** col * rows[0][col] * det3(*minor)
    return -det


class Volume:
    def __init__(self, X, Y, Z):
        self.X, self.Y, self.Z = X, Y, Z
        self.pts = {}          # index -> (x, y, z): the vertices
        self.tets = {}         # tet id -> (a, b, c, d) positive, vertex indices
        self.faces = {}        # frozenset face -> set of tet ids having it
        self.next_id = 0
        self.values = None
        self.step = 1
        self.held = {}         # tet id -> lattice points (non-vertices) assigned to it
        self.heap = []
        corners = [self.index(x, y, z) for z in (0, Z - 1) for y in (0, Y - 1) for x in (0, X - 1)]
        # DT of the eight corners straight from the definition of 10.2 (R10.2-3): every
        # positive tet of four corners that no other corner conflicts with.
        for c in corners:
            self.pts[c] = self.xyz(c)
        from itertools import combinations
        for q in combinations(corners, 4):
            o = orient(*[self.pts[v] for v in q])
            if o == 0:
                continue
            if o < 0:
                q = (q[0], q[1], q[3], q[2])
            if not any(self.conflicts(q, v) for v in corners if v not in q):
                self._add(q)

    def index(self, x, y, z):
        return x + self.X * (y + self.Y * z)

    def xyz(self, i):
        return (i % self.X, (i // self.X) % self.Y, i // (self.X * self.Y))

    # tets ---------------------------------------------------------------------------------
    def _add(self, t):
        p = [self.pts[v] for v in t]
        assert orient(*p) > 0, "a flat or negative tet"
        tid = self.next_id
        self.next_id += 1
        self.tets[tid] = t
        for k in range(4):
            self.faces.setdefault(frozenset(t[:k] + t[k + 1:]), set()).add(tid)
        self.held[tid] = []
        return tid

    def _remove(self, tid):
        t = self.tets.pop(tid)
        for k in range(4):
            f = frozenset(t[:k] + t[k + 1:])
            s = self.faces[f]
            s.discard(tid)
            if not s:
                del self.faces[f]
        return self.held.pop(tid)

    def conflicts(self, t, e):
        """10.2: the point e (an index, not a corner of t) conflicts with the positive tet t."""
        p = [self.pts[v] for v in t]
        pe = self.pts[e] if e in self.pts else self.xyz(e)
        s = insphere(p[0], p[1], p[2], p[3], pe)
        if s != 0:
            return s > 0
        order = sorted([(self.xyz(v), k) for k, v in enumerate(t)] + [(pe, 4)], reverse=True)
        for _, k in order:
            if k == 4:
                return False
            q = list(p)
            q[k] = pe
            o = orient(*q)
            if o != 0:
                return o > 0
        raise AssertionError("the perturbation did not decide")

    def contains(self, t, g):
        p = [self.pts[v] for v in t]
        for k in range(4):
            q = list(p)
            q[k] = g
            if orient(*q) < 0:
                return False
        return True

    def on_box_side(self, face):
        """The three corners of the face share a coordinate on a side of the box."""
        ps = [self.pts[v] for v in face]
        lasts = (self.X - 1, self.Y - 1, self.Z - 1)
        for a in range(3):
            if ps[0][a] == ps[1][a] == ps[2][a] and ps[0][a] in (0, lasts[a]):
                return True
        return False

    def insert(self, g, start=None):
        """DT(V + {g}) by Bowyer-Watson on the finite tets (see the header)."""
        pg = self.xyz(g)
        if start is None:
            start = [tid for tid, t in self.tets.items() if self.contains(t, pg)]
        self.pts[g] = pg
        cavity, stack = set(), list(start)
        while stack:
            tid = stack.pop()
            if tid in cavity or tid not in self.tets:
                continue
            t = self.tets[tid]
            if not self.conflicts(t, g):
                assert tid not in start, "a tet holding the point does not conflict with it"
                continue
            cavity.add(tid)
            for k in range(4):
                for n in self.faces[frozenset(t[:k] + t[k + 1:])]:
                    if n not in cavity:
                        stack.append(n)
        new = []
        for tid in cavity:
            t = self.tets[tid]
            for k in range(4):
                f = frozenset(t[:k] + t[k + 1:])
                others = self.faces[f] - {tid}
                if others and next(iter(others)) in cavity:
                    continue
                q = t[:k] + (g,) + t[k + 1:]
                o = orient(*[self.pts[v] for v in q])
                if o == 0:
                    assert not others and self.on_box_side(f), "a flat tet off the box's sides"
                    continue
                assert o > 0, "the cavity is not star-shaped from the point"
                new.append(q)
        held = []
        for tid in cavity:
            held.extend(self._remove(tid))
        ids = [self._add(q) for q in new]
        self._distribute(held, ids)
        return ids

    # errors (10.4) ------------------------------------------------------------------------
    def _distribute(self, points, ids):
        for g in points:
            if g in self.pts:
                continue
            pg = self.xyz(g)
            for tid in ids:
                if self.contains(self.tets[tid], pg):
                    self.held[tid].append(g)
                    break
            else:
                raise AssertionError("a lattice point of the cavity left outside it")
        for tid in ids:
            self._push(tid)

    def error(self, t, g):
        p = [self.pts[v] for v in t]
        pg = self.xyz(g)
        d = orient(*p)
        s = 0
        for k in range(4):
            q = list(p)
            q[k] = pg
            lam = orient(*q)
            assert lam >= 0
            s += lam * self.values[t[k]]
        return Fraction(abs(self.values[g] * d - s), d)

    def _push(self, tid):
        best = None
        t = self.tets[tid]
        for g in self.held[tid]:
            e = self.error(t, g)
            if e == 0:
                continue
            if best is None or e > best[0] or (e == best[0] and g < best[1]):
                best = (e, g)
        if best is not None:
            heapq.heappush(self.heap, (-best[0], best[1], tid))

    def worst(self):
        while self.heap:
            ne, g, tid = self.heap[0]
            if tid in self.tets and g in self.held[tid]:
                return -ne, g, tid
            heapq.heappop(self.heap)
        return None

    def lattice(self, step):
        axes = []
        for n in (self.X, self.Y, self.Z):
            axes.append(sorted(set(list(range(0, n, step)) + [n - 1])))
        return axes

    def rebuild(self):
        """Assign every lattice point that is not a vertex to one tet holding it."""
        xs, ys, zs = self.lattice(self.step)
        for tid in self.held:
            self.held[tid] = []
        self.heap = []
        assigned = set(self.pts)
        for tid, t in self.tets.items():
            p = [self.pts[v] for v in t]
            lo = [min(q[a] for q in p) for a in range(3)]
            hi = [max(q[a] for q in p) for a in range(3)]
            for z in zs:
                if not lo[2] <= z <= hi[2]:
                    continue
                for y in ys:
                    if not lo[1] <= y <= hi[1]:
                        continue
                    for x in xs:
                        if not lo[0] <= x <= hi[0]:
                            continue
                        g = self.index(x, y, z)
                        if g in assigned:
                            continue
                        if self.contains(t, (x, y, z)):
                            self.held[tid].append(g)
                            assigned.add(g)
        total = len(xs) * len(ys) * len(zs)
        lattice_vertices = sum(1 for v in self.pts if self.xyz(v)[0] in xs and self.xyz(v)[1] in ys
                               and self.xyz(v)[2] in zs)
        assert len(assigned) - len(self.pts) == total - lattice_vertices, "a lattice point in no tet"
        for tid in self.tets:
            self._push(tid)

    def greedy(self, bound, limit):
        """10.5: stop when every error is within the bound (or none is positive), or at the limit."""
        while True:
            w = self.worst()
            if w is None:
                return
            e, g, tid = w
            if bound is not None and e <= bound:
                return
            if limit and len(self.tets) >= limit:
                return
            self.insert(g, [tid])

    def trilinear_pass(self, bound, s):
        """10.6: the lattice points off the previous lattice whose trilinear distance exceeds the bound."""
        step, prev = 1 << s, 1 << (s + 1)
        lasts = (self.X - 1, self.Y - 1, self.Z - 1)
        xs, ys, zs = self.lattice(step)

        def on_prev(c, last):
            return c % prev == 0 or c == last

        chosen = []
        for z in zs:
            for y in ys:
                for x in xs:
                    g = self.index(x, y, z)
                    if g in self.pts:
                        continue
                    c = (x, y, z)
                    if all(on_prev(c[a], lasts[a]) for a in range(3)):
                        continue
                    corners = [((), 1)]
                    den = 1
                    for a in range(3):
                        if on_prev(c[a], lasts[a]):
                            corners = [(k + (c[a],), w) for k, w in corners]
                            continue
                        lo = c[a] // prev * prev
                        hi = min(lo + prev, lasts[a])
                        den *= hi - lo
                        corners = ([(k + (lo,), w * (hi - c[a])) for k, w in corners]
                                   + [(k + (hi,), w * (c[a] - lo)) for k, w in corners])
                    num = sum(w * self.values[self.index(*k)] for k, w in corners)
                    if Fraction(abs(self.values[g] * den - num), den) > bound:
                        chosen.append(g)
        for g in chosen:   # increasing index
            self.insert(g)
        return len(chosen)

    # checks of 10.2 -----------------------------------------------------------------------
    def check(self, global_check=False):
        volume = 0
        for t in self.tets.values():
            o = orient(*[self.pts[v] for v in t])
            assert o > 0
            volume += o
        assert volume == 6 * (self.X - 1) * (self.Y - 1) * (self.Z - 1), "the tets do not tile the box"
        for f, ids in self.faces.items():
            assert len(ids) in (1, 2), "a face of three tets"
            if len(ids) == 1:
                assert self.on_box_side(f), "a free face inside the box"
                continue
            a, b = (self.tets[i] for i in ids)
            (va,) = set(a) - f
            (vb,) = set(b) - f
            assert not self.conflicts(a, vb) and not self.conflicts(b, va), "not Delaunay across a face"
        if global_check:
            for t in self.tets.values():
                for v in self.pts:
                    if v not in t:
                        assert not self.conflicts(t, v), "a vertex conflicts with a tet (R10.2-3)"

    def canonical(self):
        verts = sorted(self.pts)
        number = {v: n for n, v in enumerate(verts)}
        out = bytearray(b"mrsv-canonical-grid-mesh 1 3 %d %d\n" % (len(verts), len(self.tets)))
        for v in verts:
            x, y, z = self.xyz(v)
            out += struct.pack("<IIIi", x, y, z, self.values[v])
        cells = []
        for t in self.tets.values():
            n = [number[v] for v in t]
            inversions = sum(1 for i in range(4) for j in range(i + 1, 4) if n[i] > n[j])
            s = sorted(n)
            if inversions % 2:
                s[2], s[3] = s[3], s[2]
            cells.append(tuple(s))
        for c in sorted(cells):
            out += struct.pack("<IIII", *c)
        return bytes(out)


def reconstruct(data, mrsv, max_error=None, tets=None, progressive=False, distance="mesh", levels=0,
                global_check=False, log=None):
    stream = rr.Stream(data)
    if stream.sample_type not in rr.INTEGER_TYPES:
        raise Refused(f"{rr.TYPE_NAMES.get(stream.sample_type, '?')} samples: 10.1 accepts integer samples only")
    if stream.num_dims != 3:
        raise Refused(f"{stream.num_dims}-D grid: this reconstructor does 3-D grids (10.1)")
    X, Y, Z = stream.sx, stream.sy, stream.sz
    if not all(2 <= n <= 32768 for n in (X, Y, Z)):
        raise Refused(f"a {X} x {Y} x {Z} grid: 10.1 accepts 2 <= X, Y, Z <= 32768")
    bound = rr.parse_bound(max_error) if max_error is not None else None
    if bound is None and not tets:
        raise Refused("give --max-error, --tets or both (10.1)")
    stages = stream.stages(levels)
    if not progressive:
        stages = stages[-1:]
    mesh = None
    for end, s in stages:
        values = rr.decode_samples(mrsv, data[:end], stream)
        if mesh is None:
            mesh = Volume(X, Y, Z)
        mesh.values = values
        mesh.step = 1 << s
        sb = None
        if bound is not None:
            sb = min(bound * (1 << (s + 1)) if s > 0 else bound, CAP)
        extra = 0
        if distance == "trilinear" and bound is not None:
            extra = mesh.trilinear_pass(bound, s)
        mesh.rebuild()
        mesh.greedy(sb, tets)
        mesh.check(global_check)
        if log:
            log(f"stage s={s} end={end}: {extra} by 10.6, {len(mesh.pts)} vertices, {len(mesh.tets)} tets")
    return mesh.canonical()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--mrsv", required=True, help="the grid decoder: an mrsv binary (for `decode` only)")
    parser.add_argument("--max-error")
    parser.add_argument("--tets", type=int)
    parser.add_argument("--progressive", action="store_true")
    parser.add_argument("--distance", choices=("mesh", "trilinear"), default="mesh")
    parser.add_argument("--bytes", type=int)
    parser.add_argument("--levels", type=int, default=0)
    parser.add_argument("--canonical", action="store_true", help="(implied)")
    parser.add_argument("--check-global", action="store_true", help="check R10.2-3 against every vertex")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()
    data = open(args.input, "rb").read()
    if args.bytes is not None:
        data = data[:args.bytes]
    try:
        if args.tets is not None and args.tets < 0:
            raise Refused("--tets must not be negative")
        out = reconstruct(data, args.mrsv, args.max_error, args.tets, args.progressive, args.distance,
                          args.levels, args.check_global,
                          None if args.quiet else (lambda m: print(m, file=sys.stderr)))
    except Refused as e:
        print(f"refused: {e}", file=sys.stderr)
        return 1
    with open(args.output, "wb") as f:
        f.write(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
