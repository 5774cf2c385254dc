// spec: 9.4 the max-error test of a triangle, 9.5 of a border run.
#include "reconstruct/quadtree_error.h"

#include <algorithm>
#include <type_traits>

namespace mrsv::quadtree {
namespace {

int64_t floorDiv(int64_t a, int64_t b) {  // b > 0
  const int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

}  // namespace

ErrorTest::ErrorTest(const SampleField& field, const ErrorBound& bound)
    : field_(field), bound_(bound) {
  if (!field.values.empty()) {
    const auto [lo, hi] = std::minmax_element(field.values.begin(), field.values.end());
    range_ = static_cast<uint64_t>(int64_t{*hi} - *lo);
  }
}

int64_t ErrorTest::thresholdWide(int64_t d) const {
  const __int128 t = static_cast<__int128>(bound_.num) * d / bound_.den;
  return t > INT64_MAX ? INT64_MAX : static_cast<int64_t>(t);
}

// q: the vertices relative to q[0] (q[0] = 0). With w_k the edge function
// that is d at vertex k and 0 on the opposite edge, the interpolant times d is
// sum v_k w_k; relative to v_0 it is u_1 w_1 + u_2 w_2 = A x + B y (w_1 and
// w_2 vanish at q[0]). Acc is int64_t when |sample - v_0| * d * 16 fits, else
// __int128 (spec 9.4 bounds every term by 12 * range * d).
template <class Acc>
bool ErrorTest::scanTriangle(const int64_t q[3][2], int64_t d, int64_t threshold) const {
  const uint32_t width = field_.size[0];
  const uint32_t x0 = static_cast<uint32_t>(q[0][0]), y0 = static_cast<uint32_t>(q[0][1]);
  const int32_t* base = field_.values.data() + (uint64_t{y0} * width + x0);
  // Vertex offsets relative to the first vertex.
  const int64_t x1 = q[1][0] - x0, y1 = q[1][1] - y0, x2 = q[2][0] - x0, y2 = q[2][1] - y0;
  const int64_t a[3] = {y1 - y2, y2, -y1}, b[3] = {x2 - x1, -x2, x1}, c[3] = {d, 0, 0};
  const Acc v0 = base[0];
  const Acc u1 = base[y1 * int64_t{width} + x1] - v0, u2 = base[y2 * int64_t{width} + x2] - v0;
  const Acc A = u1 * a[1] + u2 * a[2], B = u1 * b[1] + u2 * b[2];
  // Pairwise, not over an initializer list: this runs once per triangle test.
  const int64_t ylo = std::min(int64_t{0}, std::min(y1, y2)), yhi = std::max(int64_t{0}, std::max(y1, y2));
  const int64_t xlo = std::min(int64_t{0}, std::min(x1, x2)), xhi = std::max(int64_t{0}, std::max(x1, x2));
  if ((xhi - xlo + 1) * (yhi - ylo + 1) <= 64) {
    // A small box: every point of it, with the edge functions themselves
    // (w_0 = a_0 x + b_0 y + d, w_k = a_k x + b_k y), cheaper than the row
    // bounds' divisions.
    const int32_t* row = base + ylo * int64_t{width};
    if constexpr (std::is_same_v<Acc, int64_t>) {
      // Without a branch per point (whether a point of the box is inside is
      // as good as random to the branch predictor): a point is inside when
      // the three edge functions' OR has no sign bit, and within when
      // 0 <= diff + threshold <= 2 threshold, one unsigned compare. The
      // samples enter without v0 subtracted: in a box of at most 64 points,
      // d <= 128 and |s d| < 2^39.
      const uint64_t span = 2 * static_cast<uint64_t>(threshold);
      for (int64_t y = ylo; y <= yhi; ++y, row += width) {
        int64_t w0 = a[0] * xlo + b[0] * y + d, w1 = a[1] * xlo + b[1] * y, w2 = a[2] * xlo + b[2] * y;
        int64_t fit = threshold - (A * xlo + B * y) - v0 * d;  // diff + threshold = row[x] d + fit
        uint64_t bad = 0;
        for (int64_t x = xlo; x <= xhi; ++x) {
          const uint64_t inside = ~static_cast<uint64_t>(w0 | w1 | w2) >> 63;
          bad |= inside & (static_cast<uint64_t>(row[x] * d + fit) > span);
          w0 += a[0], w1 += a[1], w2 += a[2], fit -= A;
        }
        if (bad) return false;
      }
      return true;
    }
    for (int64_t y = ylo; y <= yhi; ++y, row += width) {
      const Acc row_term = B * y;
      for (int64_t x = xlo; x <= xhi; ++x) {
        if (a[0] * x + b[0] * y + d < 0 || a[1] * x + b[1] * y < 0 || a[2] * x + b[2] * y < 0) continue;
        const Acc diff = (row[x] - v0) * d - (A * x + row_term);
        if (diff > threshold || diff < -threshold) return false;
      }
    }
    return true;
  }
  // Edge k admits a_k x + r_k(y) >= 0, r_k(y) = b_k y + c_k: x >= -floor(r / a)
  // when a > 0, x <= floor(r / -a) when a < 0. The floors follow the rows by
  // quotient and remainder steps, without a division per row.
  struct Bound {
    int64_t den, q, rem, dq, drem;
  } bound[3];
  int nb = 0;
  bool lower[3];
  for (int k = 0; k < 3; ++k) {
    if (a[k] == 0) continue;  // a horizontal edge: its side is ylo..yhi already
    Bound& e = bound[nb];
    lower[nb++] = a[k] > 0;
    e.den = a[k] > 0 ? a[k] : -a[k];
    const int64_t r = b[k] * ylo + c[k];
    e.q = floorDiv(r, e.den), e.rem = r - e.q * e.den;
    e.dq = floorDiv(b[k], e.den), e.drem = b[k] - e.dq * e.den;
  }
  const int32_t* row = base + ylo * int64_t{width};
  for (int64_t y = ylo; y <= yhi; ++y, row += width) {
    int64_t lo = xlo, hi = xhi;
    for (int k = 0; k < nb; ++k) {
      Bound& e = bound[k];
      if (lower[k]) lo = std::max(lo, -e.q);
      else hi = std::min(hi, e.q);
      e.q += e.dq, e.rem += e.drem;
      if (e.rem >= e.den) e.rem -= e.den, ++e.q;
    }
    const Acc row_term = B * y;
    for (int64_t x = lo; x <= hi; ++x) {
      const Acc diff = (row[x] - v0) * d - (A * x + row_term);
      if (diff > threshold || diff < -threshold) return false;
    }
  }
  return true;
}

uint32_t ErrorTest::shapePoints(int64_t dx1, int64_t dy1, int64_t dx2, int64_t dy2, int64_t d) const {
  if (shape_start_.empty()) shape_start_.assign(size_t{kShapeSide} * kShapeSide * kShapeSide * kShapeSide, 0);
  const size_t key = static_cast<size_t>(
      ((dy2 + kShapeReach) * kShapeSide + (dx2 + kShapeReach)) * kShapeSide * kShapeSide +
      (dy1 + kShapeReach) * kShapeSide + (dx1 + kShapeReach));
  if (shape_start_[key] != 0) return shape_start_[key] - 1;
  const uint32_t start = static_cast<uint32_t>(shape_points_.size());
  // The edge functions of scanTriangle: w_0 = a_0 x + b_0 y + d, w_k = a_k x + b_k y.
  const int64_t a0 = dy1 - dy2, b0 = dx2 - dx1;
  const int64_t ylo = std::min<int64_t>({0, dy1, dy2}), yhi = std::max<int64_t>({0, dy1, dy2});
  const int64_t xlo = std::min<int64_t>({0, dx1, dx2}), xhi = std::max<int64_t>({0, dx1, dx2});
  const int64_t width = field_.size[0];
  for (int64_t y = ylo; y <= yhi; ++y)
    for (int64_t x = xlo; x <= xhi; ++x) {
      const int64_t w0 = a0 * x + b0 * y + d, w1 = dy2 * x - dx2 * y, w2 = dx1 * y - dy1 * x;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      if (w0 == d || w1 == d || w2 == d) continue;  // a vertex: exact
      shape_points_.push_back({y * width + x, static_cast<int32_t>(w1), static_cast<int32_t>(w2)});
    }
  shape_points_.push_back({0, -1, -1});
  shape_start_[key] = start + 1;
  return start;
}

bool ErrorTest::smallTriangleWithin(int64_t x0, int64_t y0, int64_t dx1, int64_t dy1, int64_t dx2, int64_t dy2,
                                    int64_t d) const {
  const uint32_t start = shapePoints(dx1, dy1, dx2, dy2, d);
  const int64_t width = field_.size[0];
  const int32_t* base = field_.values.data() + (y0 * width + x0);
  // As scanTriangle<int64_t>: every term relative to the first vertex's sample.
  const int64_t v0 = base[0], u1 = base[dy1 * width + dx1] - v0, u2 = base[dy2 * width + dx2] - v0;
  const int64_t threshold = thresholdFor(d);
  for (const ShapePoint* point = &shape_points_[start]; point->w1 >= 0; ++point) {
    const int64_t diff = (base[point->offset] - v0) * d - (u1 * point->w1 + u2 * point->w2);
    if (diff > threshold || diff < -threshold) return false;
  }
  return true;
}

bool ErrorTest::triangleWithin(const uint32_t p[3][2]) const {
  int64_t q[3][2];
  for (int k = 0; k < 3; ++k) q[k][0] = p[k][0], q[k][1] = p[k][1];
  const int64_t dx1 = q[1][0] - q[0][0], dy1 = q[1][1] - q[0][1], dx2 = q[2][0] - q[0][0], dy2 = q[2][1] - q[0][1];
  const int64_t d = dx1 * dy2 - dy1 * dx2;
  const bool fits = narrow(d);
  const auto near = [](int64_t t) { return t >= -kShapeReach && t <= kShapeReach; };
  if (fits && d > 0 && near(dx1) && near(dy1) && near(dx2) && near(dy2))
    return smallTriangleWithin(q[0][0], q[0][1], dx1, dy1, dx2, dy2, d);
  const int64_t threshold = thresholdFor(d);
  if (fits) return scanTriangle<int64_t>(q, d, threshold);
  return scanTriangle<__int128>(q, d, threshold);
}

bool ErrorTest::sampleWithinWide(int64_t d, int64_t w1, int64_t w2, int64_t s0, int64_t s1, int64_t s2,
                                 int64_t s) const {
  // Every term in 128 bits, with w0 = d - w1 - w2 (the edge functions at a
  // point sum to d).
  const __int128 diff = static_cast<__int128>(s) * d -
                        (static_cast<__int128>(s0) * (d - w1 - w2) + static_cast<__int128>(s1) * w1 +
                         static_cast<__int128>(s2) * w2);
  const __int128 threshold = thresholdFor(d);
  return diff <= threshold && diff >= -threshold;
}

bool ErrorTest::runWithin(uint64_t first, uint64_t step, uint32_t n) const {
  const int32_t* v = field_.values.data();
  const __int128 v0 = v[first], u = v[first + step * n] - v0;
  const int64_t threshold = thresholdFor(n);
  for (uint32_t k = 1; k < n; ++k) {
    const __int128 diff = (v[first + step * k] - v0) * n - u * k;
    if (diff > threshold || diff < -threshold) return false;
  }
  return true;
}

}  // namespace mrsv::quadtree
