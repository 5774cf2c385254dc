"""An independent writer of PM streams (spec 6), built from the text alone.

It holds a mesh as spec 6.3 describes it, codes a base mesh (6.4) and vertex splits
(6.6, 6.7) with pm_coder's range encoder, and gives the canonical output of every
level (6.8) by construction: the mesh it means to write, not a decoder's reading.
It shares no code with the reference encoder, so a vector it writes checks the
reference decoder against the text. Hooks let a caller write records that break a
rule (the `raw` calls), for the invalid vectors.
"""
import struct

from pm_coder import PROBABILITY_ONE, IntegerModels, RangeEncoder, zigzag

HALF = PROBABILITY_ONE // 2


class Models:
    """spec 6.5.3: one set for the whole stream, carried from chunk to chunk."""

    def __init__(self):
        self.base_position = [IntegerModels() for _ in range(3)]
        self.base_scalar = IntegerModels()
        self.base_new_vertex = [HALF] * 3
        self.base_back_reference = IntegerModels()
        self.split_flag = [HALF] * 16
        self.arc_start = [IntegerModels() for _ in range(16)]
        self.turn = [IntegerModels() for _ in range(16)]
        self.boundary_kind = [HALF] * 2
        self.fan_faces = IntegerModels()
        self.fan_interior = IntegerModels()
        self.move_fine = [HALF]
        self.vs_move = [IntegerModels() for _ in range(3)]
        self.tangent_position = [IntegerModels() for _ in range(2)]
        self.normal_position = IntegerModels()
        self.scalar = IntegerModels()


def truncated(rc, n, value):
    """spec 6.5.2, the encoder's side."""
    k = n.bit_length() - 1
    u = (1 << (k + 1)) - n
    if value < u:
        rc.direct(value, k)
    else:
        rc.direct(value + u, k + 1)


class Mesh:
    """spec 6.3: vertices (integer positions, scalars) and triangles, numbered in order."""

    def __init__(self, positions, triangles, scalars=None):
        self.positions = [list(p) for p in positions]
        self.triangles = [list(t) for t in triangles]
        self.scalars = list(scalars) if scalars is not None else None

    def copy(self):
        return Mesh(self.positions, self.triangles, self.scalars)

    def neighbours(self, v):
        out = set()
        for t in self.triangles:
            if v in t:
                out |= set(t) - {v}
        return out

    def ring(self, v):
        """spec 6.6.1: (w_0 .. w_(d-1), boundary)."""
        succ = {}
        for t in self.triangles:
            if v in t:
                i = t.index(v)
                succ[t[(i + 1) % 3]] = t[(i + 2) % 3]
        starts = set(succ) - set(succ.values())
        boundary = bool(starts)
        w = [min(starts) if boundary else min(succ)]
        while w[-1] in succ and (boundary or succ[w[-1]] != w[0]):
            w.append(succ[w[-1]])
        return w, boundary

    def canonical(self, position_bits, scalar_bits):
        """spec 6.8."""
        out = bytearray(b"mrsv-canonical-mesh 1 %d %d %d %d\n" % (
            len(self.positions), len(self.triangles), position_bits, scalar_bits))
        for v, p in enumerate(self.positions):
            out += struct.pack("<3i", *p)
            if scalar_bits:
                out += struct.pack("<i", self.scalars[v])
        for t in self.triangles:
            out += struct.pack("<3I", *t)
        return bytes(out)


def first_use_order(positions, triangles, scalars=None):
    """The mesh renumbered so that corners introduce vertices 0, 1, 2, ... (6.4)."""
    order = {}
    for t in triangles:
        for v in t:
            order.setdefault(v, len(order))
    inverse = sorted(order, key=order.get)
    return Mesh([positions[v] for v in inverse], [[order[v] for v in t] for t in triangles],
                [scalars[v] for v in inverse] if scalars is not None else None)


def header(mesh_vertices, base, batches, position_bits, scalar_bits=0, placement=0, move_detail=0,
           origin=(0.0, 0.0, 0.0), step=1.0, scalar_origin=0.0, scalar_step=0.0):
    """spec 6.2 mesh_header(): 72 bytes."""
    return struct.pack("<BBBBIIIII3dddd", placement, position_bits, scalar_bits, move_detail, mesh_vertices,
                       len(base.positions), len(base.triangles), batches, 0, *origin, step,
                       scalar_origin, scalar_step)


def encode_base(models, mesh, scalar_bits=0):
    """spec 6.4 base_mesh(): the PBAS payload."""
    rc = RangeEncoder()
    last, last_scalar = [0, 0, 0], 0
    for v, p in enumerate(mesh.positions):
        for axis in range(3):
            rc.signed(models.base_position[axis], p[axis] - last[axis])
        last = p
        if scalar_bits:
            rc.signed(models.base_scalar, mesh.scalars[v] - last_scalar)
            last_scalar = mesh.scalars[v]
    used = 0
    for t in mesh.triangles:
        for j, v in enumerate(t):
            if v == used:
                rc.bit(models.base_new_vertex, j, 1)
                used += 1
            else:
                rc.bit(models.base_new_vertex, j, 0)
                rc.unsigned(models.base_back_reference, used - 1 - v)
    return rc.finish()


def floor_div(a, b):
    return a // b  # Python's // is floor division, as spec 6.7.3 asks


def arc_normal(positions, p, ring, s, f, position_bits, shift=True, halve=True):
    """spec 6.7.3: the arc normal of p over F_s .. F_(s+f-1). `shift` and `halve` off
    give what a decoder that skips those steps would compute (to check a vector tells)."""
    d = len(ring)
    drop = max(0, position_bits - 20) if shift else 0
    u = [[floor_div(positions[ring[(s + i) % d]][k] - p[k], 1 << drop) for k in range(3)] for i in range(f + 1)]
    n = [0, 0, 0]
    for i in range(f):
        a, b = u[i], u[i + 1]
        n[0] += a[1] * b[2] - a[2] * b[1]
        n[1] += a[2] * b[0] - a[0] * b[2]
        n[2] += a[0] * b[1] - a[1] * b[0]
    while halve and max(abs(c) for c in n) >= 1 << 30:
        n = [c >> 1 for c in n]
    return n


def plane_axis(n):
    j = max(range(3), key=lambda k: (abs(n[k]), -k))
    return j if n[j] != 0 else None


def other_axes(j):
    return [k for k in range(3) if k != j]


def plane_offset(n, j, offsets):
    a = -sum(n[i] * offsets[i] for i in other_axes(j))
    if n[j] < 0:
        a = -a
    return floor_div(2 * a + abs(n[j]), 2 * abs(n[j]))


class Splitter:
    """Codes vertex splits (spec 6.7) over a mesh it keeps, with placement 0 (vs stays)."""

    def __init__(self, models, mesh, position_bits, scalar_bits=0):
        self.models, self.mesh = models, mesh.copy()
        self.bits, self.scalar_bits = position_bits, scalar_bits
        self.levels = [self.mesh.copy()]

    def begin_batch(self):
        self.rc = RangeEncoder()
        self.start = len(self.mesh.positions)
        self.prev = -1
        self.locked = set()

    def end_batch(self, split_count):
        return struct.pack("<I", split_count) + self.rc.finish()

    def flags(self, vs):
        """6.7.1 step 1: the split flags from prev + 1 up to vs."""
        for v in range(self.prev + 1, vs + 1):
            if v in self.locked:
                assert v != vs, "a locked vertex cannot be split"
                continue
            context = min(len(self.mesh.neighbours(v)), 15)
            self.rc.bit(self.models.split_flag, context, 1 if v == vs else 0)
        self.prev = vs

    def split(self, vs, a, b, vt_position, vt_scalar=None, residual_hook=None):
        """One interior split of vs at ring positions (a, b) putting vt at vt_position.
        residual_hook(name, value) may replace a coded value (invalid vectors)."""
        m = self.models
        hook = residual_hook or (lambda name, value: value)
        self.flags(vs)
        ring, boundary = self.mesh.ring(vs)
        assert not boundary, "the writer splits interior vertices"
        d = len(ring)
        pos = self.mesh.positions
        p = pos[vs]

        def sq(w):
            return sum((pos[w][k] - p[k]) ** 2 for k in range(3))
        widest = max(range(d), key=lambda i: (sq(ring[i]) + sq(ring[(i + 1) % d]), -i))
        self.rc.unsigned(m.arc_start[min(d, 15)], hook("arc_start", (widest - a) % d))
        k = (b - a) % d
        self.rc.unsigned(m.turn[min(d, 15)], hook("turn", zigzag(k - d // 2)))
        c = k + 2
        members = [ring[(a + i) % d] for i in range(k + 1)] + [vs]
        centroid = [floor_div(sum(pos[w][x] for w in members) + c // 2, c) for x in range(3)]
        n = arc_normal(pos, p, ring, a, c - 2, self.bits)
        j = plane_axis(n)
        axis = 2 if j is None else j
        for t, x in enumerate(other_axes(axis)):
            self.rc.signed(m.tangent_position[t], hook("tangent", vt_position[x] - centroid[x]))
        if j is None:
            predicted = centroid[axis]
        else:
            offsets = [vt_position[x] - p[x] for x in range(3)]
            predicted = min(max(p[axis] + plane_offset(n, axis, offsets), 0), (1 << self.bits) - 1)
        self.rc.signed(m.normal_position, hook("normal", vt_position[axis] - predicted))
        if self.scalar_bits:
            s = self.mesh.scalars
            mean = floor_div(sum(s[w] for w in members) + c // 2, c)
            self.rc.signed(m.scalar, hook("scalar", vt_scalar - mean))
        for w in ring:
            if vs < w < self.start:
                self.locked.add(w)
        # spec 6.6.2: apply the split.
        vt = len(pos)
        pos.append(list(vt_position))
        if self.scalar_bits:
            self.mesh.scalars.append(vt_scalar)
        moved = {(a + i) % d for i in range(k)}
        for i in moved:
            face = [ring[i], ring[(i + 1) % d]]
            for tri in self.mesh.triangles:
                if vs in tri and all(w in tri for w in face):
                    r = tri.index(vs)
                    if tri[(r + 1) % 3] == face[0]:
                        tri[r] = vt
        self.mesh.triangles.append([vs, ring[a], vt])
        self.mesh.triangles.append([vs, vt, ring[b % d]])
        self.levels.append(self.mesh.copy())
        return {"normal": n, "axis": axis, "centroid": centroid, "ring": ring, "predicted": predicted,
                "positions": [list(q) for q in pos[:vt]], "vs": vs, "a": a, "c": c, "vt": list(vt_position)}
