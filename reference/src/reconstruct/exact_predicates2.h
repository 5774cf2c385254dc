// Exact 2-D predicates on grid points, with the symbolic perturbation that
// makes the Delaunay triangulation of any ranked point set unique. spec: 8.3.
//
// Coordinates are grid indices in [0, 2^16] (spec 8.1 bounds the sides), so
// differences fit in 17 bits: orient2d's products in 35 bits (64-bit exact)
// and incircle's terms in 2 x 35 = 70 bits (128-bit exact). No floating
// point: every implementation gets the same signs.
#pragma once

#include <cstdint>
#include <utility>

namespace mrsv::reconstruct {

struct Point2 {
  int32_t x = 0, y = 0;
};

// Twice the signed area of (a, b, c): positive when counter-clockwise.
inline int64_t orient2d(Point2 a, Point2 b, Point2 c) {
  return (int64_t{b.x} - a.x) * (int64_t{c.y} - a.y) - (int64_t{b.y} - a.y) * (int64_t{c.x} - a.x);
}

inline int sign(int64_t v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

// The sign of the in-circle determinant: +1 when d lies inside the circle
// through the counter-clockwise triangle (a, b, c), -1 outside, 0 on it.
inline int incircle(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int64_t adx = int64_t{a.x} - d.x, ady = int64_t{a.y} - d.y;
  const int64_t bdx = int64_t{b.x} - d.x, bdy = int64_t{b.y} - d.y;
  const int64_t cdx = int64_t{c.x} - d.x, cdy = int64_t{c.y} - d.y;
  // Lifts and minors below 2^35 (64 bits); their products, 64 x 64 -> 128
  // bits (one multiplication each), and the sum below 2^72. No branch on
  // the size: measured cheaper than a 64-bit path for small triangles.
  const __int128 det = __int128{adx * adx + ady * ady} * (bdx * cdy - bdy * cdx) +
                       __int128{bdx * bdx + bdy * bdy} * (cdx * ady - cdy * adx) +
                       __int128{cdx * cdx + cdy * cdy} * (adx * bdy - ady * bdx);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// Lexicographic order (x, then y).
inline bool lexLess(Point2 p, Point2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

// Whether d conflicts with the counter-clockwise triangle (a, b, c): inside
// its circle, the cocircular case decided by the symbolic perturbation of
// Devillers and Teillaud over the points' ranks (spec 8.3; distinct numbers,
// one per vertex): of the four points the one of highest rank is looked at
// first; if it is d, d is outside; if it is a vertex of the triangle, the
// answer is the orientation of the triangle with that vertex replaced by d,
// unless zero, in which case the next highest decides the same way. Two steps
// always decide (the triangle is not flat and the points are distinct).
// With ranks in lexicographic order this is the rule of CGAL's
// Delaunay_triangulation_2. That is inCircleConflict below; cocircularConflict
// is its cocircular case alone (incircle 0), for a caller that has the sign.
inline bool cocircularConflict(Point2 a, Point2 b, Point2 c, Point2 d, const uint64_t rank[4]) {
  int order[4] = {0, 1, 2, 3};  // by decreasing rank
  for (int i = 1; i < 4; ++i)
    for (int j = i; j > 0 && rank[order[j - 1]] < rank[order[j]]; --j) std::swap(order[j - 1], order[j]);
  for (int i = 0; i < 2; ++i) {
    int64_t o = 0;
    if (order[i] == 3) return false;
    if (order[i] == 2) o = orient2d(a, b, d);
    else if (order[i] == 1) o = orient2d(a, d, c);
    else o = orient2d(d, b, c);
    if (o != 0) return o > 0;
  }
  return false;  // not reached for a proper triangle
}

inline bool inCircleConflict(Point2 a, Point2 b, Point2 c, Point2 d, const uint64_t rank[4]) {
  const int s = incircle(a, b, c, d);
  return s != 0 ? s > 0 : cocircularConflict(a, b, c, d, rank);
}

}  // namespace mrsv::reconstruct
