#!/usr/bin/env python3
"""Generates the filter tables of the B-spline wavelets (spec 4.2, 4.3).

Semi-orthogonal, endpoint-interpolating cardinal B-spline wavelets on a bounded
interval (Quak & Weyrich; Stollnitz, DeRose & Salesin, "Wavelets for Computer
Graphics", ch. 7), orders k = 1..4. Everything is computed in exact rational
arithmetic (`fractions`), from first principles:

  * B-splines of order k (degree d = k-1) on the knots 0 (k times), 1, ..., n-1,
    n (k times), as exact piecewise polynomials on the unit intervals;
  * the refinement matrix P (coarse B-splines with knot spacing 2 written in the
    fine B-splines with knot spacing 1: both live on [0, 2n]);
  * the Gram matrix G of the fine B-splines (exact integrals);
  * a minimal-support basis Q of the orthogonal complement of the coarse space
    in the fine space, P^T G Q = 0.

The tables are then checked, exactly, against the matrices computed from
scratch for many interval counts n: P and G rebuilt from the tables equal the
true ones, P^T G Q = 0 and [P|Q] is invertible.

  python3 tools/wavelets/make_filters.py           write the three outputs
  python3 tools/wavelets/make_filters.py --check   fail if the committed files differ
  python3 tools/wavelets/make_filters.py --golden  also print the golden hashes of an
      independent Python fixed-point synthesis (spec 4.5) for wavelet_fixed_test.cpp

Outputs: reference/src/wavelet/filter_tables.h, filter_tables.cpp and
spec/tables/wavelet-filters.md.
"""
import argparse
import os
import sys
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
OUT_H = os.path.join(ROOT, "reference", "src", "wavelet", "filter_tables.h")
OUT_CPP = os.path.join(ROOT, "reference", "src", "wavelet", "filter_tables.cpp")
OUT_MD = os.path.join(ROOT, "spec", "tables", "wavelet-filters.md")

ORDERS = (1, 2, 3, 4)
TAP_FRAC_BITS = 24           # spec 4.2: kTapFracBits
VALUE_LIMIT = (1 << 35) - 1  # spec 4.5: kValueLimit
VERIFY_SPAN = 12             # n_min .. n_min + VERIFY_SPAN are verified exactly
ZERO = Fraction(0)
ONE = Fraction(1)


# --- exact polynomials and B-splines ---------------------------------------

def poly_mul(a, b):
    r = [ZERO] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b):
                r[i + j] += x * y
    return r


def poly_add(a, b):
    r = [ZERO] * max(len(a), len(b))
    for i, x in enumerate(a):
        r[i] += x
    for i, x in enumerate(b):
        r[i] += x
    return r


def poly_integral(p, m):
    """Integral of p(x) over [m, m+1]."""
    return sum((c * (Fraction(m + 1) ** (e + 1) - Fraction(m) ** (e + 1)) / (e + 1)
                for e, c in enumerate(p)), ZERO)


def knot_vector(n, k, spacing):
    """Endpoint-interpolating knots on [0, n*spacing]: multiplicity k at both ends."""
    d = k - 1
    return [0] * d + [spacing * m for m in range(n + 1)] + [spacing * n] * d


def bsplines(t, k):
    """The B-splines of order k on knot vector t (integers), by the Cox-de Boor
    recursion on exact polynomials. Each is a dict: unit interval m -> the
    coefficients (lowest power first) of its polynomial on [m, m+1]."""
    cur = []
    for i in range(len(t) - 1):
        cur.append({m: [ONE] for m in range(t[i], t[i + 1])})
    for order in range(2, k + 1):
        nxt = []
        for i in range(len(t) - order):
            pieces = {}
            den1 = t[i + order - 1] - t[i]
            den2 = t[i + order] - t[i + 1]
            if den1:
                f = [Fraction(-t[i], den1), Fraction(1, den1)]
                for m, p in cur[i].items():
                    pieces[m] = poly_add(pieces.get(m, [ZERO]), poly_mul(f, p))
            if den2:
                f = [Fraction(t[i + order], den2), Fraction(-1, den2)]
                for m, p in cur[i + 1].items():
                    pieces[m] = poly_add(pieces.get(m, [ZERO]), poly_mul(f, p))
            nxt.append(pieces)
        cur = nxt
    assert len(cur) == len(t) - k
    return cur


# --- exact linear algebra ---------------------------------------------------

def zeros(rows, cols):
    return [[ZERO] * cols for _ in range(rows)]


def transpose(a):
    return [list(r) for r in zip(*a)]


def matmul(a, b):
    bt = transpose(b)
    out = []
    for row in a:
        nz = [(l, x) for l, x in enumerate(row) if x]
        out.append([sum((x * col[l] for l, x in nz), ZERO) for col in bt])
    return out


def rref(a):
    """Reduced row echelon form; returns (matrix, pivot columns)."""
    m = [r[:] for r in a]
    rows = len(m)
    cols = len(m[0]) if rows else 0
    pivots = []
    r = 0
    for c in range(cols):
        p = next((i for i in range(r, rows) if m[i][c]), None)
        if p is None:
            continue
        m[r], m[p] = m[p], m[r]
        inv = 1 / m[r][c]
        m[r] = [x * inv for x in m[r]]
        for i in range(rows):
            if i != r and m[i][c]:
                f = m[i][c]
                m[i] = [x - f * y for x, y in zip(m[i], m[r])]
        pivots.append(c)
        r += 1
        if r == rows:
            break
    return m, pivots


def nullspace(a, cols):
    if not a:
        return [[ONE if i == j else ZERO for i in range(cols)] for j in range(cols)]
    m, pivots = rref(a)
    basis = []
    for f in (c for c in range(cols) if c not in pivots):
        v = [ZERO] * cols
        v[f] = ONE
        for i, c in enumerate(pivots):
            v[c] = -m[i][f]
        basis.append(v)
    return basis


def rank(a):
    return len(rref(a)[1]) if a else 0


def solve_square(a, b):
    m, pivots = rref([row[:] + [b[i]] for i, row in enumerate(a)])
    assert pivots == list(range(len(a))), "singular local system"
    return [m[i][len(a)] for i in range(len(a))]


# --- P, G, Q from scratch ---------------------------------------------------

def exact_level(n, k):
    """Exact P ((2n+d) x (n+d)) and fine Gram G ((2n+d) x (2n+d)) for n coarse
    intervals, both with unit knot spacing at the fine level."""
    fine = bsplines(knot_vector(2 * n, k, 1), k)
    coarse = bsplines(knot_vector(n, k, 2), k)
    nf, nc = len(fine), len(coarse)
    p = zeros(nf, nc)
    # On each fine unit interval exactly k fine B-splines are nonzero and their
    # polynomials are independent, so matching a coarse B-spline's polynomial
    # there gives those k coefficients; different intervals must agree.
    for j in range(nc):
        found = {}
        for m in range(2 * n):
            idx = [i for i in range(nf) if m in fine[i]]
            assert len(idx) == k
            target = (coarse[j].get(m, [ZERO]) + [ZERO] * k)[:k]
            a = [[(fine[i][m] + [ZERO] * k)[e] for i in idx] for e in range(k)]
            for i, v in zip(idx, solve_square(a, target)):
                assert found.setdefault(i, v) == v, "refinement is inconsistent"
        for i, v in found.items():
            p[i][j] = v
    g = zeros(nf, nf)
    for i in range(nf):
        for j in range(i, nf):
            s = sum((poly_integral(poly_mul(pc, fine[j][m]), m)
                     for m, pc in fine[i].items() if m in fine[j]), ZERO)
            g[i][j] = g[j][i] = s
    return p, g


def exact_gram(n, k):
    """Exact Gram matrix of the B-splines with n unit intervals."""
    b = bsplines(knot_vector(n, k, 1), k)
    g = zeros(len(b), len(b))
    for i in range(len(b)):
        for j in range(i, len(b)):
            s = sum((poly_integral(poly_mul(pc, b[j][m]), m)
                     for m, pc in b[i].items() if m in b[j]), ZERO)
            g[i][j] = g[j][i] = s
    return g


def window_nullspace(m, s, e):
    return nullspace([row[s:e + 1] for row in m], e - s + 1)


def minimal_support_wavelets(p, g):
    """A basis of {q : P^T G q = 0} by increasing end and, for each end, the
    latest start: the minimal-support basis. Returns [(start, taps)]."""
    m = matmul(transpose(p), g)
    nf = len(p)
    found = []
    dim = 0
    for e in range(nf):
        new_dim = len(window_nullspace(m, 0, e))
        assert new_dim <= dim + 1, "two wavelets end at the same index"
        if new_dim == dim:
            continue
        for s in range(e, -1, -1):
            here = window_nullspace(m, s, e)
            before = window_nullspace(m, s, e - 1) if e > s else []
            if len(here) > len(before):
                assert len(here) == 1, "minimal support is not unique"
                found.append((s, [ZERO] * s + here[0] + [ZERO] * (nf - 1 - e)))
                break
        dim = new_dim
    return found


def normalise(taps):
    """Scale so the largest |tap| is 1 and the first tap of largest magnitude is +1."""
    big = max(abs(x) for x in taps)
    first = next(x for x in taps if abs(x) == big)
    return [x / first for x in taps]


def trim(column):
    """(first row, taps) of a column vector's nonzero span."""
    nz = [i for i, x in enumerate(column) if x]
    return nz[0], column[nz[0]:nz[-1] + 1]


# --- the per-order structure ------------------------------------------------

class Order:
    """Left-boundary columns, interior taps and Gram band of one order."""

    def __init__(self, k):
        self.k = k
        d = self.d = k - 1
        probe = 4 * k + 4
        p, g = exact_level(probe, k)
        self.p_left = [trim([row[j] for row in p]) for j in range(d)]
        self.p_interior_first, self.p_interior = trim([row[d] for row in p])
        self.p_interior_first -= 2 * d  # column j starts at row 2j + offset
        wavelets = minimal_support_wavelets(p, g)
        assert len(wavelets) == probe
        self.q_left = [(s, normalise(t)) for s, t in
                       (trim(v[:]) for _, v in wavelets[:d])]
        s, taps = trim(wavelets[d][1])
        self.q_interior_first = s - 2 * d
        self.q_interior = normalise(taps)
        assert len(self.q_interior) == 3 * k - 1
        # Gram: boundary rows 0..2d-1 as bands A[i][i+o], o = -d..d; the rest
        # of the left half is Toeplitz with g[|o|].
        self.g_band = [g[2 * d + 2][2 * d + 2 + o] for o in range(d + 1)]
        self.g_boundary = [[g[i][i + o] if 0 <= i + o < len(g) else ZERO
                            for o in range(-d, d + 1)] for i in range(2 * d)]
        self.n_min = None

    # Matrices rebuilt from the tables, exactly as the decoder does (spec 4.3).
    def p_columns(self, n):
        d = self.d
        nf, nc = 2 * n + d, n + d
        cols = []
        for j in range(nc):
            if j < d:
                cols.append(self.p_left[j])
            elif j < n:
                cols.append((2 * j + self.p_interior_first, self.p_interior))
            else:
                first, taps = self.p_left[nc - 1 - j]
                cols.append((nf - first - len(taps), taps[::-1]))
        return cols

    def q_columns(self, n):
        d = self.d
        nf = 2 * n + d
        cols = []
        for j in range(n):
            if j < d:
                cols.append(self.q_left[j])
            elif j < n - d:
                cols.append((2 * j + self.q_interior_first, self.q_interior))
            else:
                first, taps = self.q_left[n - 1 - j]
                cols.append((nf - first - len(taps), taps[::-1]))
        return cols

    def gram_from_table(self, n_intervals):
        d = self.d
        size = n_intervals + d
        g = zeros(size, size)
        for i in range(size):
            for j in range(max(0, i - d), min(size, i + d + 1)):
                a, b = i, j
                if a + b > size - 1:  # the right half mirrors the left
                    a, b = size - 1 - a, size - 1 - b
                if a < 2 * d:
                    v = self.g_boundary[a][b - a + d]
                elif b < 2 * d:
                    v = self.g_boundary[b][a - b + d]
                else:
                    v = self.g_band[abs(a - b)]
                g[i][j] = v
        return g

    @staticmethod
    def dense(cols, rows):
        m = zeros(rows, len(cols))
        for j, (first, taps) in enumerate(cols):
            if first < 0 or first + len(taps) > rows:
                return None
            for r, v in enumerate(taps):
                m[first + r][j] = v
        return m

    def separated(self, n):
        """The ends do not interact (spec 4.3): no fine row is reached by a
        column of both the left and the right boundary blocks of P and Q, so
        every fine row is a left-boundary, an interior or a right-boundary row."""
        d = self.d
        if n < 1 or n < 2 * d:
            return False

        def rows(cols):
            reached = set()
            for first, taps in cols:
                reached.update(range(first, first + len(taps)))
            return reached

        pc, qc = self.p_columns(n), self.q_columns(n)
        return not rows(pc[:d] + qc[:d]) & rows(pc[n:] + qc[n - d:])

    def verify(self, n):
        """Exact check of the tables at n coarse intervals; returns a problem or None."""
        k, d = self.k, self.d
        nf, nc = 2 * n + d, n + d
        if n < 1 or (d > 0 and n < 2 * d):
            return "fewer intervals than boundary columns"
        p_true, g_true = exact_level(n, k)
        p = self.dense(self.p_columns(n), nf)
        if p != p_true:
            return "P from the tables differs"
        if self.gram_from_table(2 * n) != g_true:
            return "fine Gram from the tables differs"
        if self.gram_from_table(n) != exact_gram(n, k):
            return "coarse Gram from the tables differs"
        q = self.dense(self.q_columns(n), nf)
        if q is None:
            return "Q column outside the level"
        if any(x for row in matmul(matmul(transpose(p), g_true), q) for x in row):
            return "P^T G Q != 0"
        pq = [pr + qr for pr, qr in zip(p, q)]
        if rank(pq) != nf:
            return "[P|Q] is singular"
        return None


def find_n_min(o):
    """Smallest n from which the tables are valid and the ends are separated,
    checked for every n up to n + VERIFY_SPAN. Returns (n_min, log)."""
    log = []
    for n in range(1, 8 * o.k + 4):
        problem = o.verify(n)
        sep = o.separated(n)
        log.append((n, problem, sep))
        if problem is None and sep:
            later = [m for m in range(n + 1, n + VERIFY_SPAN + 1)
                     if o.verify(m) is not None or not o.separated(m)]
            if not later:
                return n, log
    raise AssertionError("no n_min for order %d" % o.k)


def coarse_gram_check(o):
    """The coarse Gram P^T G P equals 2 * the unit Gram of the coarse level
    (the encoder's analysis, spec 4.8, relies on it), for n_min..n_min+3."""
    for n in range(o.n_min, o.n_min + 4):
        p, g = exact_level(n, o.k)
        lhs = matmul(matmul(transpose(p), g), p)
        rhs = [[2 * x for x in row] for row in o.gram_from_table(n)]
        assert lhs == rhs, "coarse Gram mismatch"


# --- fixed point --------------------------------------------------------------

def to_fixed(x):
    """round(x * 2^24), ties away from zero (no ties occur: checked)."""
    v = x * (1 << TAP_FRAC_BITS)
    fl = v.numerator // v.denominator
    frac = v - fl
    assert frac != Fraction(1, 2), "a tap is a tie"
    r = fl + (1 if frac > Fraction(1, 2) else 0)
    assert abs(r) < (1 << 31)
    return r


def row_sums(o):
    """Over every fine row of [P|Q] at n_min..n_min+3: the largest sum of
    |integer taps|, the largest sum of |Q taps| (real), the largest count of
    Q taps, and whether every integer P row sums to 2^24 exactly."""
    worst_int = 0
    worst_q = ZERO
    worst_qn = 0
    p_exact = True
    for n in range(o.n_min, o.n_min + 4):
        nf = 2 * n + o.d
        acc_int = [0] * nf
        acc_q = [ZERO] * nf
        cnt_q = [0] * nf
        p_sum = [0] * nf
        for first, taps in o.p_columns(n):
            for r, v in enumerate(taps):
                acc_int[first + r] += abs(to_fixed(v))
                p_sum[first + r] += to_fixed(v)
                assert v >= 0
        for first, taps in o.q_columns(n):
            for r, v in enumerate(taps):
                acc_int[first + r] += abs(to_fixed(v))
                acc_q[first + r] += abs(v)
                cnt_q[first + r] += 1
        worst_int = max(worst_int, max(acc_int))
        worst_q = max(worst_q, max(acc_q))
        worst_qn = max(worst_qn, max(cnt_q))
        p_exact = p_exact and all(s == 1 << TAP_FRAC_BITS for s in p_sum)
    return worst_int, worst_q, worst_qn, p_exact


# --- emitters -------------------------------------------------------------------

def c_double(x):
    s = repr(float(x))
    if "e" not in s and "." not in s and "inf" not in s:
        s += ".0"
    return s


def c_list(values, per_line, indent="    "):
    lines = []
    for i in range(0, len(values), per_line):
        lines.append(indent + ", ".join(values[i:i + per_line]) + ",")
    return "\n".join(lines)


HEADER_NOTE = """\
// GENERATED by tools/wavelets/make_filters.py from exact rational arithmetic:
// do not edit. Regenerate with
//   python3 tools/wavelets/make_filters.py
// and check that the committed files are current with --check."""


def emit_header(orders):
    out = [HEADER_NOTE, """\
//
// Filter tables of the endpoint-interpolating B-spline wavelets, orders 1..4.
// spec: 4.2 (filters), spec/tables/wavelet-filters.md (the same numbers).
#pragma once

#include <cstdint>

namespace mrsv::wavelet {

// Fraction bits of the integer taps: tap_fixed = round(tap * 2^kTapFracBits). spec: 4.2
constexpr int kTapFracBits = %d;

// One column of a left-boundary block: its nonzero taps start at fine row
// first_row. The right-boundary block is the mirror image (spec 4.3); the
// *_reversed arrays hold the same taps last to first for it.
struct BoundaryColumn {
  int first_row;
  int count;
  const double* taps;
  const int32_t* fixed;
  const double* taps_reversed;
  const int32_t* fixed_reversed;
};

struct OrderFilters {
  int order;                 // k
  int min_coarse_intervals;  // n_min(k), spec 4.3
  // Refinement matrix P: columns 0..boundary-1 are p_left; interior column j
  // has taps p_interior starting at row 2j + p_interior_first.
  int p_boundary;
  const BoundaryColumn* p_left;
  int p_interior_count;
  int p_interior_first;
  const double* p_interior;
  const int32_t* p_interior_fixed;
  // Wavelet matrix Q, the same way.
  int q_boundary;
  const BoundaryColumn* q_left;
  int q_interior_count;
  int q_interior_first;
  const double* q_interior;
  const int32_t* q_interior_fixed;
  // Gram matrix of the B-splines with unit knot spacing: half bandwidth d = k-1,
  // interior band gram_band[|i-j|], left boundary rows i < gram_boundary_rows as
  // gram_boundary[i*(2d+1) + (j-i+d)]; the right end mirrors the left.
  int gram_half_band;
  const double* gram_band;
  int gram_boundary_rows;
  const double* gram_boundary;
  // Largest sum of |integer taps| of P and Q over any fine row (spec 4.6).
  int64_t max_row_tap_sum;
  // Largest sum of |Q taps| and count of Q taps over any fine row (spec 4.7).
  double max_row_q_sum;
  int max_row_q_count;
};

// The filters of order k, kMinOrder <= k <= kMaxOrder.
const OrderFilters& orderFilters(int order);

// Over all orders: the largest max_row_tap_sum (spec 4.6).
constexpr int64_t kMaxRowTapSum = %d;

}  // namespace mrsv::wavelet
""" % (TAP_FRAC_BITS, max(o.max_int for o in orders))]
    return "\n".join(out)


def emit_cpp(orders):
    out = [HEADER_NOTE, "// spec: 4.2, spec/tables/wavelet-filters.md", "",
           '#include "wavelet/filter_tables.h"', "", "namespace mrsv::wavelet {",
           "namespace {", ""]

    def arrays(prefix, values):
        out.append("constexpr double %s[] = {\n%s\n};" % (
            prefix, c_list([c_double(v) for v in values], 3)))
        out.append("constexpr int32_t %sFixed[] = {\n%s\n};" % (
            prefix, c_list([str(to_fixed(v)) for v in values], 6)))

    for o in orders:
        k = o.k
        for name, cols in (("P", o.p_left), ("Q", o.q_left)):
            for j, (_, taps) in enumerate(cols):
                arrays("k%sLeft%d_%d" % (name, k, j), taps)
                arrays("k%sLeft%d_%dReversed" % (name, k, j), taps[::-1])
        arrays("kPInterior%d" % k, o.p_interior)
        arrays("kQInterior%d" % k, o.q_interior)
        for name, cols in (("P", o.p_left), ("Q", o.q_left)):
            if cols:
                entries = [("{%d, %d, k%sLeft%d_%d, k%sLeft%d_%dFixed,\n     "
                            "k%sLeft%d_%dReversed, k%sLeft%d_%dReversedFixed}") % (
                    first, len(taps), name, k, j, name, k, j, name, k, j, name, k, j)
                    for j, (first, taps) in enumerate(cols)]
                out.append("constexpr BoundaryColumn k%sLeft%d[] = {\n%s\n};" % (
                    name, k, c_list(entries, 1)))
        out.append("constexpr double kGramBand%d[] = {\n%s\n};" % (
            k, c_list([c_double(v) for v in o.g_band], 3)))
        if o.g_boundary:
            flat = [c_double(v) for row in o.g_boundary for v in row]
            out.append("constexpr double kGramBoundary%d[] = {\n%s\n};" % (
                k, c_list(flat, 3)))
        out.append("")

    out.append("constexpr OrderFilters kOrders[] = {")
    for o in orders:
        k = o.k
        pl = "kPLeft%d" % k if o.p_left else "nullptr"
        ql = "kQLeft%d" % k if o.q_left else "nullptr"
        gb = "kGramBoundary%d" % k if o.g_boundary else "nullptr"
        out.append("    {%d, %d,\n     %d, %s, %d, %d, kPInterior%d, kPInterior%dFixed,\n"
                   "     %d, %s, %d, %d, kQInterior%d, kQInterior%dFixed,\n"
                   "     %d, kGramBand%d, %d, %s,\n     %d, %s, %d}," % (
                       k, o.n_min, len(o.p_left), pl, len(o.p_interior), o.p_interior_first,
                       k, k, len(o.q_left), ql, len(o.q_interior), o.q_interior_first, k, k,
                       o.d, k, len(o.g_boundary), gb, o.max_int, c_double(o.max_q),
                       o.max_qn))
    out.append("};")
    out.append("")
    out.append("}  // namespace")
    out.append("")
    out.append("const OrderFilters& orderFilters(int order) { return kOrders[order - 1]; }")
    out.append("")
    out.append("}  // namespace mrsv::wavelet")
    out.append("")
    return "\n".join(out)


def two_j(offset):
    return "2*j*" if offset == 0 else "2*j* %s %d" % ("+" if offset > 0 else "−", abs(offset))


def md_table(headers, rows):
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def emit_md(orders):
    names = {1: "Haar (piecewise constant)", 2: "linear", 3: "quadratic", 4: "cubic"}
    out = ["""\
# Wavelet filter tables

*Generated by `tools/wavelets/make_filters.py` from exact rational arithmetic; do not edit.*
Regenerate with `python3 tools/wavelets/make_filters.py`.

These tables are part of clause 4.2. The **integer taps** (`tap_fixed`, fraction bits
`kTapFracBits` = %d) define decoding (4.5); the exact rationals and the Gram matrices are
informative (they define the filters the integers approximate and the analysis of 4.8).
`tap_fixed = round(tap × 2^%d)`, rounding to nearest; no tap lies halfway.

For order *k* (degree *d* = *k* − 1) and a level with *n* coarse intervals there are
*n* + *d* coarse coefficients, *n* wavelet coefficients and 2*n* + *d* fine coefficients.
Rows and columns are numbered from 0. A **left-boundary column** *j* gives its taps for
fine rows `first_row`, `first_row` + 1, .... An **interior column** *j* has the interior
taps at fine rows 2*j* + `interior_first`, .... The right-boundary columns mirror the left
ones (4.3): column *C* − 1 − *j* of a matrix with *C* columns and *F* = 2*n* + *d* rows has
the taps of left column *j* in reverse order, its last tap at row *F* − 1 − `first_row`.
""" % (TAP_FRAC_BITS, TAP_FRAC_BITS)]
    summary = []
    for o in orders:
        summary.append((o.k, names[o.k], o.n_min, len(o.p_left), len(o.q_left),
                        len(o.p_interior), o.p_interior_first,
                        len(o.q_interior), o.q_interior_first, o.max_int))
    out.append(md_table(["*k*", "name", "n_min", "P boundary columns", "Q boundary columns",
                         "P interior taps", "P interior_first", "Q interior taps",
                         "Q interior_first", "max row sum of \\|tap_fixed\\|"], summary))
    for o in orders:
        k = o.k
        out.append("\n## Order %d (%s)\n" % (k, names[k]))
        out.append("n_min(%d) = %d.\n" % (k, o.n_min))
        out.append("### P, refinement (integer taps, normative)\n")
        rows = []
        for j, (first, taps) in enumerate(o.p_left):
            rows.append(("left %d" % j, first, " ".join(str(to_fixed(v)) for v in taps)))
        rows.append(("interior", two_j(o.p_interior_first),
                     " ".join(str(to_fixed(v)) for v in o.p_interior)))
        out.append(md_table(["column", "first row", "tap_fixed"], rows))
        out.append("\n### Q, wavelets (integer taps, normative)\n")
        rows = []
        for j, (first, taps) in enumerate(o.q_left):
            rows.append(("left %d" % j, first, " ".join(str(to_fixed(v)) for v in taps)))
        rows.append(("interior", two_j(o.q_interior_first),
                     " ".join(str(to_fixed(v)) for v in o.q_interior)))
        out.append(md_table(["column", "first row", "tap_fixed"], rows))
        out.append("\n### Exact taps (informative)\n")
        rows = []
        for j, (first, taps) in enumerate(o.p_left):
            rows.append(("P left %d" % j, first, ", ".join(str(v) for v in taps)))
        rows.append(("P interior", two_j(o.p_interior_first),
                     ", ".join(str(v) for v in o.p_interior)))
        for j, (first, taps) in enumerate(o.q_left):
            rows.append(("Q left %d" % j, first, ", ".join(str(v) for v in taps)))
        rows.append(("Q interior", two_j(o.q_interior_first),
                     ", ".join(str(v) for v in o.q_interior)))
        out.append(md_table(["column", "first row", "taps"], rows))
        out.append("\n### Gram matrix, unit knot spacing (informative)\n")
        out.append("Interior band ⟨N_i, N_(i+o)⟩ for o = 0..%d: %s.\n" % (
            o.d, ", ".join(str(v) for v in o.g_band)))
        if o.g_boundary:
            rows = [(i, ", ".join(str(v) for v in row)) for i, row in enumerate(o.g_boundary)]
            out.append("Left boundary rows, entries for columns *i* − %d .. *i* + %d "
                       "(0 outside the matrix):\n" % (o.d, o.d))
            out.append(md_table(["row *i*", "entries"], rows))
    return "\n".join(out) + "\n"


# --- independent fixed-point synthesis (spec 4.5), for the golden test vectors ---

GOLDEN_SIZES = (51, 29, 27)
GOLDEN_LEVELS = (2, 1, 1)
MASK64 = (1 << 64) - 1


def golden_input(k, count):
    """splitmix64 numbers as in reference/tests/wavelet_fixed_test.cpp."""
    s = (0x9E3779B97F4A7C15 * k) & MASK64
    out = []
    for _ in range(count):
        s = (s + 0x9E3779B97F4A7C15) & MASK64
        z = s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
        z ^= z >> 31
        out.append(z % (1 << 30) - (1 << 29))
    return out


def synthesize_fixed(o, sizes, levels, data):
    """spec 4.5 on a 3-D array (x fastest), written from the clause, not the C++."""
    d = o.d

    def n0(a):
        return -(-(sizes[a] - d) // (1 << levels[a]))

    def size(a, j):
        j = min(j, levels[a])
        return sizes[a] if levels[a] == 0 else (n0(a) << (levels[a] - j)) + d

    padded = [size(a, 0) for a in range(3)]
    stride = [1, padded[0], padded[0] * padded[1]]
    half = 1 << (TAP_FRAC_BITS - 1)
    for level in range(max(levels), 0, -1):
        box = [size(a, level - 1) for a in range(3)]
        for a in range(3):
            if levels[a] < level:
                continue
            n = n0(a) << (levels[a] - level)
            cols = ([(f, [to_fixed(v) for v in t]) for f, t in o.p_columns(n)] +
                    [(f, [to_fixed(v) for v in t]) for f, t in o.q_columns(n)])
            others = [b for b in range(3) if b != a]
            for u in range(box[others[0]]):
                for v in range(box[others[1]]):
                    base = u * stride[others[0]] + v * stride[others[1]]
                    line = [max(-VALUE_LIMIT, min(VALUE_LIMIT, data[base + i * stride[a]]))
                            for i in range(box[a])]
                    acc = [0] * box[a]
                    for j, (first, taps) in enumerate(cols):
                        for r, t in enumerate(taps):
                            acc[first + r] += t * line[j]
                    for i in range(box[a]):
                        data[base + i * stride[a]] = max(-VALUE_LIMIT, min(
                            VALUE_LIMIT, (acc[i] + half) >> TAP_FRAC_BITS))
    return data


def fnv1a(values):
    h = 1469598103934665603
    for x in values:
        x &= MASK64
        for b in range(8):
            h ^= (x >> (8 * b)) & 0xFF
            h = (h * 1099511628211) & MASK64
    return h


def golden(orders):
    for o in orders:
        d = o.d
        count = 1
        for a in range(3):
            n0 = -(-(GOLDEN_SIZES[a] - d) // (1 << GOLDEN_LEVELS[a]))
            count *= (n0 << GOLDEN_LEVELS[a]) + d
        data = synthesize_fixed(o, GOLDEN_SIZES, GOLDEN_LEVELS, golden_input(o.k, count))
        print("order %d: 0x%016x" % (o.k, fnv1a(data)))


def build(want_golden=False):
    orders = []
    for k in ORDERS:
        o = Order(k)
        o.n_min, log = find_n_min(o)
        for n, problem, sep in log:
            if n < o.n_min:
                print("order %d, n = %d: %s" % (k, n, problem or (
                    "ends not separated" if not sep else "a larger n fails")),
                    file=sys.stderr)
        coarse_gram_check(o)
        o.max_int, o.max_q, o.max_qn, p_exact = row_sums(o)
        assert p_exact, "integer P rows must sum to 2^24 exactly"
        assert o.max_int * VALUE_LIMIT + (1 << (TAP_FRAC_BITS - 1)) < 1 << 63
        print("order %d: n_min %d, max row sum %d (%.4f), max |Q| row sum %.4f, %d Q taps" % (
            k, o.n_min, o.max_int, o.max_int / 2 ** TAP_FRAC_BITS, o.max_q, o.max_qn),
            file=sys.stderr)
        orders.append(o)
    if want_golden:
        golden(orders)
    return {OUT_H: emit_header(orders), OUT_CPP: emit_cpp(orders), OUT_MD: emit_md(orders)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true", help="fail if the outputs differ")
    ap.add_argument("--golden", action="store_true",
                    help="print the golden synthesis hashes of wavelet_fixed_test.cpp")
    args = ap.parse_args()
    files = build(args.golden)
    stale = []
    for path, text in files.items():
        old = None
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                old = f.read()
        if old == text:
            continue
        if args.check:
            stale.append(os.path.relpath(path, ROOT))
        else:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            print("wrote", os.path.relpath(path, ROOT), file=sys.stderr)
    if stale:
        print("stale: " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
