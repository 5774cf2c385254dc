// Exact orientation and triangle-intersection predicates on quantised
// positions. Coordinates are in [0, 2^30), so differences fit in 31 bits, a
// 2x2 minor in 63 and a 3x3 determinant in 95: __int128 holds every value
// exactly, and the decoder, doing the same arithmetic, agrees bit for bit.
#pragma once

#include <array>
#include <cstdint>

namespace mrsv::tetsimplify {

using IPoint = std::array<int32_t, 3>;
using Int128 = __int128;

// det[b - a, c - a, d - a]: positive when d lies on the side of the plane
// (a, b, c) that the right-hand rule over a -> b -> c points to.
inline Int128 orient3d(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d) {
  const int64_t bx = int64_t(b[0]) - a[0], by = int64_t(b[1]) - a[1], bz = int64_t(b[2]) - a[2];
  const int64_t cx = int64_t(c[0]) - a[0], cy = int64_t(c[1]) - a[1], cz = int64_t(c[2]) - a[2];
  const int64_t dx = int64_t(d[0]) - a[0], dy = int64_t(d[1]) - a[1], dz = int64_t(d[2]) - a[2];
  return Int128(bx) * (Int128(cy) * dz - Int128(cz) * dy) + Int128(by) * (Int128(cz) * dx - Int128(cx) * dz) +
         Int128(bz) * (Int128(cx) * dy - Int128(cy) * dx);
}

inline int sign(Int128 x) { return (x > 0) - (x < 0); }

// Whether the closed segment pq meets the closed triangle abc (abc not
// degenerate).
bool segmentMeetsTriangle(const IPoint& p, const IPoint& q, const IPoint& a, const IPoint& b, const IPoint& c);

// Whether two boundary triangles meet anywhere but in what they share: for
// triangles with no common vertex, whether they meet at all; with one common
// vertex, whether they meet elsewhere; with a common edge, whether they fold
// onto each other (coplanar, on the same side of it). Triangles are given by
// vertex ids (to find what they share) and the positions those ids index.
bool trianglesClash(const std::array<uint32_t, 3>& s, const std::array<uint32_t, 3>& t, const IPoint* positions);

}  // namespace mrsv::tetsimplify
