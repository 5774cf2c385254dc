// spec: 8.5 greedy insertion, 8.6 the border rule, 8.7 stages.
#include "mrsv/terrain_insertion.h"

#include <algorithm>
#include <type_traits>

#include "reconstruct/candidate_queue.h"
#include "reconstruct/delaunay2.h"
#include "reconstruct/line_insertion.h"
#include "reconstruct/run_scan.h"

namespace mrsv {

using reconstruct::Delaunay2;
using reconstruct::orient2d;
using reconstruct::Point2;

namespace {

using reconstruct::Candidate;
using reconstruct::CandidateQueue;

int64_t floorDiv(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// a = q b + r with 0 <= r < b (b > 0): one division, no branch.
void floorDivMod(int64_t a, int64_t b, int64_t* q, int64_t* r) {
  const int64_t tq = a / b, tr = a % b;
  const int64_t borrow = tr < 0;  // C++ division rounds toward zero
  *q = tq - borrow, *r = tr + (b & -borrow);
}

}  // namespace

struct TerrainInserter::State {
  uint32_t nx, ny;
  Delaunay2 dt;
  std::vector<uint8_t> is_vertex;       // per sample
  std::vector<uint64_t> vertex_sample;  // per vertex
  // Per vertex: the last stage's value, set at the end of refine() (read
  // at every insertion, the sample would be a cache miss of its own: the
  // scans read short_values).
  std::vector<int32_t> vertex_value;
  CandidateQueue queue;                 // triangles whose worst sample is beyond the bound
  // This stage's bound: candidates within it are never inserted, so they are
  // not queued (num < 0: no bound).
  __int128 bound_num = -1;
  int64_t bound_den = 1;
  bool narrow = false;                  // errors fit 64-bit arithmetic this stage
  // The stage's samples as 16-bit integers when they all fit (terrains in
  // metres do), else empty: the scans read half the cache lines, and at the
  // larger bounds they read about a thousand samples per insertion. Padded
  // with kPadding samples for run_scan (AVX2).
  std::vector<int16_t> short_values;
  static constexpr size_t kPadding = 4;
  const reconstruct::RunScanFunction run_scan = reconstruct::runScanAvx2();
  // A scan's runs of samples, one per lattice row of the triangle.
  using Run = reconstruct::SampleRun;
  std::vector<Run> runs;
  // The current stage.
  const SampleField* field = nullptr;
  int64_t step = 1;  // 2^shift
  bool skip_border = false;

  State(uint32_t x, uint32_t y)
      : nx(x), ny(y), dt(int32_t(x - 1), int32_t(y - 1)), is_vertex(uint64_t{x} * y), runs(size_t{y} + 1) {
    for (uint32_t v = 0; v < 4; ++v) {
      const Point2 p = dt.point(v);
      vertex_sample.push_back(uint64_t(p.y) * nx + uint64_t(p.x));
      is_vertex[vertex_sample.back()] = 1;
      vertex_value.push_back(0);
    }
  }

  // The lattice coordinates of an axis of n samples within [lo, hi], in order:
  // multiples of step, and n - 1.
  // (lo >= 0; step is a power of 2.)
  template <class F>
  void forLattice(int64_t lo, int64_t hi, int64_t n, F&& f) const {
    for (int64_t c = (lo + step - 1) & ~(step - 1); c <= hi; c += step) f(c);
    if (((n - 1) & (step - 1)) != 0 && lo <= n - 1 && n - 1 <= hi) f(n - 1);
  }

  // A sample on an edge shared by two triangles has the same error in both
  // (spec 8.5), so one of them counts it: the one that sees the edge with
  // ex > 0, or ex = 0 and ey > 0, for its barycentric numerator ex x + ey y
  // + e0 (the other sees -ex, -ey); an edge on the rectangle's border, with
  // no neighbour, is counted. Every sample is still in some triangle's scan,
  // the worst of all is the same, and each is queued once.
  static bool countsEdge(int64_t ex, int64_t ey, uint32_t neighbour) {
    return neighbour == Delaunay2::kNone || ex > 0 || (ex == 0 && ey > 0);
  }

  // A triangle's worst lattice sample: the error num / den (num = 0: none
  // but its corners, or all exact) and the sample's index.
  template <class W>
  struct Worst {
    W num;
    int64_t den;
    uint64_t sample;
  };

  // spec 8.5: a triangle's worst lattice sample, exactly, queued when
  // beyond the bound.
  void scan(uint32_t t) {
    queue.prefetch(t);
    const bool shorts = !short_values.empty();
    if (step == 1) {
      if (shorts) record(t, scanWith<int64_t, true, int16_t>(t));
      else if (narrow) record(t, scanWith<int64_t, true, int32_t>(t));
      else record(t, scanWith<__int128, true, int32_t>(t));
    } else if (shorts) {
      record(t, scanWith<int64_t, false, int16_t>(t));
    } else if (narrow) {
      record(t, scanWith<int64_t, false, int32_t>(t));
    } else {
      record(t, scanWith<__int128, false, int32_t>(t));
    }
  }

  // The same, as a candidate, for maxError().
  Candidate candidate(uint32_t t) {
    Worst<__int128> w;
    if (step == 1) w = narrow ? widen(scanWith<int64_t, true, int32_t>(t)) : scanWith<__int128, true, int32_t>(t);
    else w = narrow ? widen(scanWith<int64_t, false, int32_t>(t)) : scanWith<__int128, false, int32_t>(t);
    Candidate c;
    c.num = w.num, c.den = w.den, c.sample = w.sample;
    return c;
  }
  template <class W>
  static Worst<__int128> widen(const Worst<W>& w) {
    return {__int128{w.num}, w.den, w.sample};
  }

  // One edge's limit on a row's x range. The edge's barycentric numerator
  // w = ex x + ey y + e0 is >= 0 where x >= -floor(N / m) (ex > 0: a lower
  // limit) or x <= floor(N / m) (ex < 0: an upper one), with m = |ex| and
  // N = ey y + e0. floor(N / m) is carried from lattice row to lattice row as
  // a quotient and remainder, so the rows after the first need no division.
  struct RowLimit {
    int64_t q, r, m;  // N = q m + r, 0 <= r < m
    int64_t dq, dr;   // N's step from row to row, ey * step = dq m + dr, 0 <= dr < m
    bool upper;
    template <class E>
    void start(const E& e, int64_t y, int64_t step) {  // e.ex != 0
      upper = e.ex < 0;
      m = upper ? -e.ex : e.ex;
      const int64_t n = e.ey * y + e.e0;
      floorDivMod(n, m, &q, &r);
      floorDivMod(e.ey * step, m, &dq, &dr);
    }
  };

  // Fills `count` runs, one per lattice row, between a lower and an upper
  // limit, x in [x0, x1], and leaves both limits on the row after them. The
  // limits are stepped in locals without branches (a carry of the remainder
  // is as likely as not), so that the loop keeps them in registers.
  static Run* fillRuns(Run* run, int64_t count, RowLimit& lower, RowLimit& upper, int64_t x0, int64_t x1) {
    int64_t lq = lower.q, lr = lower.r, uq = upper.q, ur = upper.r;
    const int64_t lm = lower.m, ldq = lower.dq, ldr = lower.dr;
    const int64_t um = upper.m, udq = upper.dq, udr = upper.dr;
    for (const Run* end = run + count; run != end; ++run) {
      run->lo = std::max(x0, -lq), run->hi = std::min(x1, uq);
      lq += ldq, lr += ldr, uq += udq, ur += udr;
      const int64_t lc = -int64_t(lr >= lm), uc = -int64_t(ur >= um);  // all ones on a carry
      lq -= lc, lr -= lm & lc, uq -= uc, ur -= um & uc;
    }
    lower.q = lq, lower.r = lr, upper.q = uq, upper.r = ur;
    return run;
  }

  // W holds |value - za| * den and the interpolant's numerator: int64_t when
  // the stage's value range allows (checked in refine()), else __int128.
  // kUnit: the lattice step is 1 (the single stage and every last stage).
  // S: the samples' type, int16_t from short_values (with W = int64_t:
  // 16-bit values always allow it) or int32_t from the field.
  template <class W, bool kUnit, class S>
  Worst<W> scanWith(uint32_t t) {
    // The corners from the triangulation (its insertion has just read them).
    const auto& tv = dt.triangle(t);
    const Point2 a = dt.point(tv[0]), b = dt.point(tv[1]), c = dt.point(tv[2]);
    const int64_t den = orient2d(a, b, c);
    const S* values;
    if constexpr (std::is_same_v<S, int16_t>) values = short_values.data();
    else values = field->values.data();
    const int64_t nx64 = nx;
    if (kUnit && den <= 3) {
      // Pick's theorem, den = 2 I + B - 2 with I grid points inside and B on
      // the border, and an edge holds gcd(dx, dy) - 1 points besides its
      // ends, a gcd that divides den: den = 1, no point but the corners;
      // den = 2, the midpoint of the one edge whose coordinate differences
      // are even; den = 3, the centroid when it is a grid point (I = 1),
      // else the two points at the thirds of the one edge whose differences
      // are multiples of 3 (B = 5). (On a lattice of step 1, every sample.)
      W best_num = 0;
      int64_t best = 0;
      // (x, y) with the error numerator e; points in increasing index.
      const auto take = [&](int64_t x, int64_t y, int64_t e) {
        if (skip_border && (x == 0 || y == 0 || x == nx64 - 1 || y == int64_t{ny} - 1)) return;
        const W size = W(e < 0 ? -e : e);
        if (size > best_num) best_num = size, best = y * nx64 + x;
      };
      const auto value = [&](int64_t x, int64_t y) { return int64_t{values[y * nx64 + x]}; };
      // Whether t counts the points of its edge from u to w (edge i).
      const auto counts = [&](const Point2& u, const Point2& w, int i) {
        return countsEdge(int64_t{u.y} - w.y, int64_t{w.x} - u.x, dt.neighbours(t)[i]);
      };
      if (den == 2) {
        const Point2& u = ((b.x ^ c.x) | (b.y ^ c.y)) & 1 ? ((c.x ^ a.x) | (c.y ^ a.y)) & 1 ? a : c : b;
        const Point2& w = &u == &a ? b : &u == &b ? c : a;
        const int64_t mx = (int64_t{u.x} + w.x) >> 1, my = (int64_t{u.y} + w.y) >> 1;
        if (counts(u, w, &u == &b ? 0 : &u == &c ? 1 : 2))
          take(mx, my, 2 * value(mx, my) - value(u.x, u.y) - value(w.x, w.y));
      } else if (den == 3) {
        const int64_t sx = int64_t{a.x} + b.x + c.x, sy = int64_t{a.y} + b.y + c.y;
        if (sx % 3 == 0 && sy % 3 == 0) {
          take(sx / 3, sy / 3, 3 * value(sx / 3, sy / 3) - value(a.x, a.y) - value(b.x, b.y) - value(c.x, c.y));
        } else {
          const auto thirds = [](const Point2& p, const Point2& q) { return (q.x - p.x) % 3 == 0 && (q.y - p.y) % 3 == 0; };
          const Point2& u = thirds(b, c) ? b : thirds(c, a) ? c : a;
          const Point2& w = &u == &a ? b : &u == &b ? c : a;
          if (counts(u, w, &u == &b ? 0 : &u == &c ? 1 : 2)) {
            const int64_t dx = (w.x - u.x) / 3, dy = (w.y - u.y) / 3;
            const int64_t zu = value(u.x, u.y), zw = value(w.x, w.y);
            const int64_t x1 = u.x + dx, y1 = u.y + dy, x2 = u.x + 2 * dx, y2 = u.y + 2 * dy;
            const int64_t e1 = 3 * value(x1, y1) - 2 * zu - zw, e2 = 3 * value(x2, y2) - zu - 2 * zw;
            if (y1 * nx64 + x1 < y2 * nx64 + x2) take(x1, y1, e1), take(x2, y2, e2);
            else take(x2, y2, e2), take(x1, y1, e1);
          }
        }
      }
      return {best_num, den, uint64_t(best)};
    }
    // Their values from the field (beside the samples about to be read).
    const int64_t za = values[a.y * nx64 + a.x];
    const int64_t zb = values[b.y * nx64 + b.x] - za, zc = values[c.y * nx64 + c.x] - za;
    const int64_t st = kUnit ? 1 : step;
    // Barycentric numerators as functions of the sample (x, y): w = ex * x + ey * y + e0.
    struct Edge {
      int64_t ex, ey, e0;
      int64_t at(int64_t x, int64_t y) const { return ex * x + ey * y + e0; }
    };
    auto edge = [](Point2 u, Point2 v) {
      return Edge{int64_t{u.y} - v.y, int64_t{v.x} - u.x, int64_t{u.x} * v.y - int64_t{u.y} * v.x};
    };
    const Edge edges[3] = {edge(b, c), edge(c, a), edge(a, b)};
    const Edge &eb = edges[1], &ec = edges[2];
    // The rows' limits: the edges that t does not count (countsEdge) taken
    // as w - 1 >= 0, that is w > 0.
    Edge limits[3] = {edges[0], edges[1], edges[2]};
    bool left_out[3];
    for (int i = 0; i < 3; ++i) {
      left_out[i] = !countsEdge(edges[i].ex, edges[i].ey, dt.neighbours(t)[i]);
      limits[i].e0 -= left_out[i];
    }
    int64_t x0 = std::min(std::min(a.x, b.x), c.x), x1 = std::max(std::max(a.x, b.x), c.x);
    int64_t y0 = std::min(std::min(a.y, b.y), c.y), y1 = std::max(std::max(a.y, b.y), c.y);
    if (skip_border) {
      x0 = std::max<int64_t>(x0, 1), x1 = std::min<int64_t>(x1, nx64 - 2);
      y0 = std::max<int64_t>(y0, 1), y1 = std::min<int64_t>(y1, int64_t{ny} - 2);
    }
    int top = 0, mid = 1, bottom = 2;  // the corners by y
    const int64_t ys[3] = {a.y, b.y, c.y};
    if (ys[mid] < ys[top]) std::swap(mid, top);
    if (ys[bottom] < ys[mid]) std::swap(bottom, mid);
    if (ys[mid] < ys[top]) std::swap(mid, top);
    int64_t first_y = kUnit ? y0 : (y0 + st - 1) & ~(st - 1);  // y0 >= 0
    int64_t last_row = y1;
    // The row of the top corner holds no other point of the triangle when
    // the two others lie below it, nor does the bottom corner's when they
    // lie above: a corner is a vertex, never a candidate, so those rows are
    // left out (most of a small triangle's rows are one or two samples long).
    // So is a horizontal edge's row when t does not count that edge.
    if (first_y == ys[top] && (kUnit ? ys[mid] > ys[top] || left_out[bottom] : ys[mid] == ys[top] && left_out[bottom]))
      first_y += st;
    if (last_row == ys[bottom] && (kUnit ? ys[mid] < ys[bottom] || left_out[top] : ys[mid] == ys[bottom] && left_out[top]))
      --last_row;

    // First the rows' runs: the rows from the top vertex to the middle one
    // (by y) lie between the two edges from the top, the rest between the
    // long edge (top to bottom) and the short one from the middle: two
    // limits per row, one lower and one upper (a row's run between two
    // boundary points of the triangle satisfies the third edge). Edge i is
    // opposite corner i. Apart from the sample loop below, this loop keeps
    // few values live, so neither spills registers.
    RowLimit along, beside;  // the long edge, the current short edge
    Run* run = runs.data();
    int64_t y = first_y;
    const auto limitRows = [&](int64_t end) {  // the rows from y to end (y <= end)
      const int64_t count = kUnit ? end - y + 1 : (end - y) / st + 1;
      run = along.upper ? fillRuns(run, count, beside, along, x0, x1) : fillRuns(run, count, along, beside, x0, x1);
      y += count * st;
    };
    if (y <= last_row) {
      along.start(limits[mid], y, st);
      // Rows above the middle vertex's, or every row when the short edge
      // from the middle is horizontal.
      const int64_t split = ys[mid] == ys[bottom] ? last_row : std::min(last_row, ys[mid] - 1);
      if (y <= split) {
        beside.start(limits[bottom], y, st);
        limitRows(split);
      }
      if (y <= last_row) {
        beside.start(limits[top], y, st);
        limitRows(last_row);
      }
    }
    const Run* const runs_end = run;

    // Then the samples. The error numerator at (x, y) is (value - za) den -
    // Q(x, y), with the interpolant's numerator Q = wb zb + wc zc linear:
    // Q(x, y) = Q(x0, y) + qx (x - x0), and Q(x0, y) steps by a constant from
    // lattice row to row. Every point of the bounding box has |wb|, |wc| <=
    // 2 nx ny, so Q, its steps between box points and the error fit where
    // refine() chose int64_t; a step is only taken as a constant when the box
    // is at least a step wide (tall), so that it too is the difference of two
    // box points. The loop computes value den - (Q + za den) in U, unsigned
    // (wrapping) arithmetic: za den alone may not fit, but the result does,
    // and modulo 2^64 (2^128) it is exact.
    using U = std::conditional_t<std::is_same_v<W, int64_t>, uint64_t, unsigned __int128>;
    const U uden = U(W(den));
    const U qx = U(W(eb.ex) * zb + W(ec.ex) * zc);
    const U qy = U(W(eb.ey) * zb + W(ec.ey) * zc);
    const U dz = kUnit || st <= x1 - x0 ? qx * U(st) : U(0);
    const U dq_row = kUnit || st <= y1 - y0 ? qy * U(st) : U(0);
    const U offset = U(W(za)) * uden;
    const auto qAt = [&](int64_t x, int64_t row_y) {
      return U(W(eb.at(x, row_y)) * zb + W(ec.at(x, row_y)) * zc) + offset;
    };
    W best_num = 0;
    U twice_best = 0;
    const S* best = nullptr;
    const int64_t last = nx64 - 1;
    // The last column and row are lattice points even when not multiples of step.
    const bool last_apart = !kUnit && (last & (st - 1)) != 0;
    // Samples come in increasing index order: on a tie the first stays.
    const auto consider = [&](const S* v, U q) {
      W e = W(U(W(*v)) * uden - q);
      // |e| > best_num (>= 0) exactly when e + best_num, taken unsigned,
      // exceeds 2 best_num (no overflow: both are below 2^62 where W is
      // int64_t, refine()): one comparison, no absolute value.
      if (U(e) + U(best_num) > twice_best) {
        best_num = e < 0 ? -e : e, best = v;
        twice_best = U(best_num) * 2;
      }
    };
    // The lattice samples of row y in [lo, hi], Q(x0, y) + za den being qr.
    const auto visitRow = [&](const S* v, int64_t lo, int64_t hi, U qr) {
      const int64_t first = kUnit ? lo : (lo + st - 1) & ~(st - 1);
      if (first <= hi) {
        U q = qr + qx * U(first - x0);
        for (const S *p = v + first, *end = v + hi; p <= end; p += st, q += dz) consider(p, q);
      }
      if (last_apart && lo <= last && last <= hi) consider(v + last, qr + qx * U(last - x0));
    };
    if constexpr (kUnit && std::is_same_v<S, int16_t>) {
      if (run_scan && den < (int64_t{1} << 31)) {
        if (run == runs.data()) return {0, den, 0};
        const reconstruct::RunScan rs{values + first_y * nx64, nx64, runs.data(), runs_end - runs.data(), x0, den,
                                      uint64_t(qAt(x0, first_y)), uint64_t(dq_row), uint64_t(qx)};
        const reconstruct::RunWorst w = run_scan(rs);
        return {w.size, den, w.at ? uint64_t(w.at - values) : 0};
      }
    }
    if (run != runs.data()) {
      U q_row = qAt(x0, first_y);
      const S* v = values + first_y * nx64;
      const int64_t row_step = st * nx64;
      for (const Run* r = runs.data(); r != runs_end; ++r, v += row_step, q_row += dq_row)
        if (r->lo <= r->hi) visitRow(v, r->lo, r->hi, q_row);
    }
    // The last row, when not a multiple of step, by division.
    const int64_t last_y = int64_t{ny} - 1;
    if (!kUnit && (last_y & (st - 1)) != 0 && y0 <= last_y && last_y <= last_row) {
      int64_t lo = x0, hi = x1;
      for (const Edge& e : limits) {
        if (e.ex == 0) continue;
        const int64_t n = e.ey * last_y + e.e0;
        if (e.ex > 0) lo = std::max(lo, -floorDiv(n, e.ex));
        else hi = std::min(hi, floorDiv(n, -e.ex));
      }
      if (lo <= hi) visitRow(values + last_y * nx64, lo, hi, qAt(x0, last_y));
    }
    return {best_num, den, best ? uint64_t(best - values) : 0};
  }

  // Triangle t's worst sample queued when beyond the bound (and its error is
  // not 0), else t taken out of the queue.
  template <class W>
  void record(uint32_t t, const Worst<W>& worst) {
    const W num = worst.num;
    const int64_t den = worst.den;
    // (Beyond the bound: in 64 x 64 -> 128-bit products when the bound's
    // numerator fits 64 bits, as it does but for huge bounds and shifts.)
    const bool beyond = num > 0 && (bound_num < 0 ||
                        (bound_num <= INT64_MAX && std::is_same_v<W, int64_t>
                             ? __int128{int64_t(num)} * bound_den > __int128{int64_t(bound_num)} * den
                             : __int128{num} * bound_den > bound_num * den));
    if (beyond) {
      Candidate found;
      found.num = num;
      found.den = den;
      found.sample = worst.sample;
      queue.set(t, found);
      return;
    }
    queue.remove(t);
  }

  // Every vertex's rank (spec 8.3) is its insertion number, corners 0 to 3:
  // ties of cocircular vertices go to the older ones (decision D47).
  // t is the triangle whose worst sample it is, which holds it.
  void insertSample(uint64_t sample, uint32_t t) {
    const Point2 p{int32_t(sample % nx), int32_t(sample / nx)};
    const uint32_t v = dt.insert(p, dt.vertexCount(), t);
    is_vertex[sample] = 1;
    vertex_sample.push_back(sample);
    // The triangles made or changed are those around the new vertex (its
    // star), each once: walk around it from t, which holds it.
    uint32_t s = t;
    do {
      scan(s);
      s = dt.nextAround(s, v);
    } while (s != t && s != Delaunay2::kNone);
    if (s == t) return;
    // On a side of the rectangle: the rest of the star, the other way.
    for (s = dt.previousAround(t, v); s != Delaunay2::kNone; s = dt.previousAround(s, v)) scan(s);
  }

  // spec 8.6: each side refined by 1-D insertion from its own samples.
  void borderRule(__int128 bound_num, int64_t bound_den) {
    struct Side {
      uint64_t start, stride, count;
    };
    const Side sides[4] = {{0, 1, nx},
                           {uint64_t{ny - 1} * nx, 1, nx},
                           {0, nx, ny},
                           {nx - 1, nx, ny}};
    for (const Side& s : sides) {
      std::vector<int64_t> positions, values;
      std::vector<uint8_t> kept;
      forLattice(0, int64_t(s.count) - 1, int64_t(s.count), [&](int64_t c) {
        const uint64_t sample = s.start + uint64_t(c) * s.stride;
        positions.push_back(c);
        values.push_back(field->values[sample]);
        kept.push_back(is_vertex[sample]);
      });
      reconstruct::insertAlongLine(positions, values, bound_num, bound_den, &kept);
      uint32_t hint = 0;
      for (size_t k = 0; k < positions.size(); ++k) {
        const uint64_t sample = s.start + uint64_t(positions[k]) * s.stride;
        if (!kept[k] || is_vertex[sample]) continue;
        const Point2 p{int32_t(sample % nx), int32_t(sample / nx)};
        hint = dt.locate(p, hint);
        dt.insert(p, dt.vertexCount(), hint);  // hint holds p after it
        is_vertex[sample] = 1;
        vertex_sample.push_back(sample);
      }
    }
  }
};

TerrainInserter::TerrainInserter(uint32_t size_x, uint32_t size_y)
    : state_(std::make_unique<State>(size_x, size_y)) {}
TerrainInserter::~TerrainInserter() = default;

bool TerrainInserter::refine(const SampleField& field, unsigned shift, const InsertionLimits& limits,
                             std::string* error, const InsertionProgress& progress) {
  State& s = *state_;
  if (field.size[0] != s.nx || field.size[1] != s.ny || field.size[2] != 1) {
    *error = "the field's sizes differ from the mesh's grid";
    return false;
  }
  if (!limits.max_error.set() && limits.max_cells == 0) {
    *error = "no limit: give a maximum error or a triangle count";
    return false;
  }
  if (shift > 16) {
    *error = "lattice shift above 16";
    return false;
  }
  s.field = &field;
  s.step = int64_t{1} << shift;
  // spec 8.7: a stage on a lattice of step 2^shift > 1 stops at 2^(shift+1)
  // times the bound (decision D46: coarse stages, which see blurred samples,
  // then place few vertices the finer stages would not have chosen).
  // An unset bound is num = -1 and is never shifted (a shift of a negative
  // value is undefined behaviour).
  const __int128 bound_num =
      limits.max_error.set() ? __int128{limits.max_error.num} << (shift == 0 ? 0 : shift + 1) : -1;
  const int64_t bound_den = limits.max_error.den;
  const bool border = limits.border_rule && limits.max_error.set();
  if (border) s.borderRule(bound_num, bound_den);
  s.bound_num = limits.max_error.set() ? bound_num : -1;
  s.bound_den = bound_den;
  s.queue.clear();
  // 64-bit errors when |value - za| * den and |wb zb + wc zc| stay below 2^62:
  // den <= 2 nx ny, the weights sum to den.
  const auto [lo, hi] = std::minmax_element(field.values.begin(), field.values.end());
  const __int128 range = field.values.empty() ? 0 : __int128{*hi} - *lo;
  s.narrow = range * 4 * s.nx * s.ny < (__int128{1} << 62);
  s.short_values.clear();
  if (!field.values.empty() && *lo >= INT16_MIN && *hi <= INT16_MAX) {
    s.short_values.reserve(field.values.size() + State::kPadding);
    s.short_values.assign(field.values.begin(), field.values.end());
    s.short_values.resize(field.values.size() + State::kPadding, 0);
  }
  s.skip_border = border;
  for (uint32_t t = 0; t < s.dt.triangleCount(); ++t) s.scan(t);

  uint64_t since_progress = 0;
  while (!s.queue.empty()) {
    // (Only candidates beyond the bound are queued: the queue runs empty
    // when the worst is within it.)
    if (limits.max_cells != 0 && s.dt.triangleCount() >= limits.max_cells) break;
    s.insertSample(s.queue.topSample(), s.queue.top());
    if (progress && ++since_progress == 4096) {
      since_progress = 0;
      if (!progress(s.dt.triangleCount())) break;
    }
  }
  s.vertex_value.resize(s.vertex_sample.size());
  for (size_t v = 0; v < s.vertex_sample.size(); ++v) s.vertex_value[v] = field.values[s.vertex_sample[v]];
  return true;
}

// Every triangle scanned again: informative, and not worth a per-triangle
// array that the insertion would write at every scan.
double TerrainInserter::maxError() const {
  State& s = *state_;
  if (!s.field) return 0;
  double worst = 0;
  for (uint32_t t = 0; t < s.dt.triangleCount(); ++t) {
    const Candidate c = s.candidate(t);
    worst = std::max(worst, double(c.num) / double(c.den));
  }
  return worst;
}

uint64_t TerrainInserter::vertexCount() const { return state_->dt.vertexCount(); }
uint64_t TerrainInserter::cellCount() const { return state_->dt.triangleCount(); }

void TerrainInserter::mesh(GridMesh* out) const {
  const State& s = *state_;
  out->dims = 2;
  out->size[0] = s.nx, out->size[1] = s.ny, out->size[2] = 1;
  out->points.resize(s.dt.vertexCount());
  out->values.resize(s.dt.vertexCount());
  for (uint32_t v = 0; v < s.dt.vertexCount(); ++v) {
    const Point2 p = s.dt.point(v);
    out->points[v] = {uint32_t(p.x), uint32_t(p.y), 0};
    out->values[v] = s.vertex_value[v];
  }
  out->cells.resize(s.dt.triangleCount());
  for (uint32_t t = 0; t < s.dt.triangleCount(); ++t) {
    const auto& c = s.dt.triangle(t);
    out->cells[t] = {c[0], c[1], c[2], 0};
  }
}

}  // namespace mrsv
