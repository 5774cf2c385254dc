// The orientation of four points with integer coordinates, exactly.
// spec: 7.3 (a tet is positive when orient3d > 0).
//
// Coordinates lie in [0, 2^30), so differences fit in 31 bits, each product
// of three differences in 93 bits and the sum of the six products of the
// determinant in 96 bits: a signed 128-bit integer holds it with room to spare.
// No floating point, no filter: every implementation gets the same sign.
// Coordinates below 2^20 take a 64-bit path, exact by the bound below
// (orient3dBelow2to20, which callers that know the bound call directly).
#pragma once

#include <array>
#include <cstdint>

namespace mrsv {

using Point3i = std::array<int32_t, 3>;

// The sign of det[b - a, c - a, d - a] for coordinates in [0, 2^20): every
// difference is below 2^20 in magnitude, each 2x2 minor below 2^41, each
// product below 2^61 and the sum of three below 2^63, so 64-bit arithmetic
// is exact. For callers that know the bound for all their points (a PT
// decoder: position_bits <= 20), without orient3d's test of the bound.
inline int orient3dBelow2to20(const Point3i& a, const Point3i& b, const Point3i& c, const Point3i& d) {
  const int64_t bx = int64_t{b[0]} - a[0], by = int64_t{b[1]} - a[1], bz = int64_t{b[2]} - a[2];
  const int64_t cx = int64_t{c[0]} - a[0], cy = int64_t{c[1]} - a[1], cz = int64_t{c[2]} - a[2];
  const int64_t dx = int64_t{d[0]} - a[0], dy = int64_t{d[1]} - a[1], dz = int64_t{d[2]} - a[2];
  const int64_t det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// orient3d(a, b, c, d) from the differences B = b - a, C = c - a, D = d - a,
// for callers that test many tets sharing the corner a (a vertex split: every
// tet it changes or adds has vt as a corner) and subtract once per point.
// Below2to20: the bound of orient3dBelow2to20 on the points; otherwise the
// differences lie in (-2^30, 2^30) and the determinant is taken in 128 bits.
using Diff3 = std::array<int64_t, 3>;
inline int orientOfDifferences(const Diff3& b, const Diff3& c, const Diff3& d, bool below_2to20) {
  if (below_2to20) {
    const int64_t det = b[0] * (c[1] * d[2] - c[2] * d[1]) - b[1] * (c[0] * d[2] - c[2] * d[0]) +
                        b[2] * (c[0] * d[1] - c[1] * d[0]);
    return det > 0 ? 1 : (det < 0 ? -1 : 0);
  }
  const __int128 det = __int128{b[0]} * (__int128{c[1]} * d[2] - __int128{c[2]} * d[1]) -
                       __int128{b[1]} * (__int128{c[0]} * d[2] - __int128{c[2]} * d[0]) +
                       __int128{b[2]} * (__int128{c[0]} * d[1] - __int128{c[1]} * d[0]);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// The sign of det[b - a, c - a, d - a]: +1, 0 or -1.
inline int orient3d(const Point3i& a, const Point3i& b, const Point3i& c, const Point3i& d) {
  // Meshes quantised to 20 bits or less always take the 64-bit path; one OR
  // of the coordinates tests it.
  const int32_t any = a[0] | a[1] | a[2] | b[0] | b[1] | b[2] | c[0] | c[1] | c[2] | d[0] | d[1] | d[2];
  if ((any >> 20) == 0) return orient3dBelow2to20(a, b, c, d);
  const int64_t bx = int64_t{b[0]} - a[0], by = int64_t{b[1]} - a[1], bz = int64_t{b[2]} - a[2];
  const int64_t cx = int64_t{c[0]} - a[0], cy = int64_t{c[1]} - a[1], cz = int64_t{c[2]} - a[2];
  const int64_t dx = int64_t{d[0]} - a[0], dy = int64_t{d[1]} - a[1], dz = int64_t{d[2]} - a[2];
  const __int128 det = __int128{bx} * (__int128{cy} * dz - __int128{cz} * dy) -
                       __int128{by} * (__int128{cx} * dz - __int128{cz} * dx) +
                       __int128{bz} * (__int128{cx} * dy - __int128{cy} * dx);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

}  // namespace mrsv
