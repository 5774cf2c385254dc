// Distance from a point to a triangle, shared by the simplifier's deviation
// guard and the PM encoder's choice of grid points.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "simplify/vec3.h"

namespace mrsv::simplify {

inline double segmentDistance2(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = sub(b, a);
  const Vec3 ap = sub(p, a);
  const double l = dot(ab, ab);
  double t = l > 0.0 ? dot(ap, ab) / l : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  const Vec3 d = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return dot(d, d);
}

// A triangle with what the distance test needs precomputed.
struct Triangle {
  Vec3 a, ab, ac;
  double d00, d01, d11, det;
};

inline Triangle makeTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Triangle t;
  t.a = a;
  t.ab = sub(b, a);
  t.ac = sub(c, a);
  t.d00 = dot(t.ab, t.ab);
  t.d01 = dot(t.ab, t.ac);
  t.d11 = dot(t.ac, t.ac);
  t.det = t.d00 * t.d11 - t.d01 * t.d01;
  return t;
}

inline double area(const Triangle& t) { return 0.5 * std::sqrt(std::fmax(0.0, t.det)); }

// Squared distance from p to triangle t: to the plane when p projects inside,
// else to the nearest of the three edges (where the closest point then lies).
inline double distance2(const Vec3& p, const Triangle& t) {
  const Vec3 ap = sub(p, t.a);
  if (t.det > 0.0) {
    const double d20 = dot(ap, t.ab);
    const double d21 = dot(ap, t.ac);
    const double v = (t.d11 * d20 - t.d01 * d21) / t.det;
    const double w = (t.d00 * d21 - t.d01 * d20) / t.det;
    if (v >= 0.0 && w >= 0.0 && v + w <= 1.0) {
      const Vec3 d = {ap[0] - v * t.ab[0] - w * t.ac[0], ap[1] - v * t.ab[1] - w * t.ac[1],
                      ap[2] - v * t.ab[2] - w * t.ac[2]};
      return dot(d, d);
    }
  }
  const Vec3 b = {t.a[0] + t.ab[0], t.a[1] + t.ab[1], t.a[2] + t.ab[2]};
  const Vec3 c = {t.a[0] + t.ac[0], t.a[1] + t.ac[1], t.a[2] + t.ac[2]};
  return std::min({segmentDistance2(p, t.a, b), segmentDistance2(p, b, c), segmentDistance2(p, c, t.a)});
}

// The squared distance from p to the nearest triangle of the fan, stopping as
// soon as it is at most `enough` (the caller needs no less).
inline double fanDistance2(const Vec3& p, const std::vector<Triangle>& fan, double enough) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < fan.size() && best > enough; ++i) {
    const double d2 = distance2(p, fan[i]);
    if (d2 < best) best = d2;
  }
  return best;
}

}  // namespace mrsv::simplify
