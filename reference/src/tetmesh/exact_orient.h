// The orientation of four points with integer coordinates, exactly.
// spec: 7.3 (a tet is positive when orient3d > 0).
//
// Coordinates lie in [0, 2^30), so differences fit in 31 bits, each product
// of three differences in 93 bits and the sum of the six products of the
// determinant in 96 bits: a signed 128-bit integer holds it with room to spare.
// No floating point, no filter: every implementation gets the same sign.
#pragma once

#include <array>
#include <cstdint>

namespace mrsv {

using Point3i = std::array<int32_t, 3>;

// The sign of det[b - a, c - a, d - a]: +1, 0 or -1.
inline int orient3d(const Point3i& a, const Point3i& b, const Point3i& c, const Point3i& d) {
  const __int128 bx = int64_t{b[0]} - a[0], by = int64_t{b[1]} - a[1], bz = int64_t{b[2]} - a[2];
  const int64_t cx = int64_t{c[0]} - a[0], cy = int64_t{c[1]} - a[1], cz = int64_t{c[2]} - a[2];
  const int64_t dx = int64_t{d[0]} - a[0], dy = int64_t{d[1]} - a[1], dz = int64_t{d[2]} - a[2];
  const __int128 det = bx * (__int128{cy} * dz - __int128{cz} * dy) - by * (__int128{cx} * dz - __int128{cz} * dx) +
                       bz * (__int128{cx} * dy - __int128{cy} * dx);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

}  // namespace mrsv
