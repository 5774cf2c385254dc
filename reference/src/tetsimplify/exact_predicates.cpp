// Exact triangle-intersection predicates (exact_predicates.h). Two triangles
// that are not coplanar meet in a segment whose ends lie on edges of one or
// the other, so edge-against-triangle tests decide every case; coplanar
// configurations fall back to the same tests in the plane of largest
// projection.
#include "tetsimplify/exact_predicates.h"

#include <cstdlib>

namespace mrsv::tetsimplify {

namespace {

using P2 = std::array<int64_t, 2>;

// The axis along which the plane of abc has its largest normal component:
// dropping it projects the plane one to one.
int dropAxis(const IPoint& a, const IPoint& b, const IPoint& c) {
  const int64_t ux = int64_t(b[0]) - a[0], uy = int64_t(b[1]) - a[1], uz = int64_t(b[2]) - a[2];
  const int64_t vx = int64_t(c[0]) - a[0], vy = int64_t(c[1]) - a[1], vz = int64_t(c[2]) - a[2];
  Int128 n[3] = {Int128(uy) * vz - Int128(uz) * vy, Int128(uz) * vx - Int128(ux) * vz,
                 Int128(ux) * vy - Int128(uy) * vx};
  for (Int128& x : n) x = x < 0 ? -x : x;
  return n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
}

P2 project(const IPoint& p, int drop) {
  return drop == 0 ? P2{p[1], p[2]} : (drop == 1 ? P2{p[2], p[0]} : P2{p[0], p[1]});
}

int orient2d(const P2& a, const P2& b, const P2& c) {
  return sign(Int128(b[0] - a[0]) * (c[1] - a[1]) - Int128(b[1] - a[1]) * (c[0] - a[0]));
}

// c on the closed segment ab, given that the three are collinear.
bool between(const P2& a, const P2& b, const P2& c) {
  return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
         c[1] <= std::max(a[1], b[1]);
}

bool segmentsMeet2d(const P2& p, const P2& q, const P2& a, const P2& b) {
  const int o1 = orient2d(p, q, a), o2 = orient2d(p, q, b), o3 = orient2d(a, b, p), o4 = orient2d(a, b, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && between(p, q, a)) || (o2 == 0 && between(p, q, b)) || (o3 == 0 && between(a, b, p)) ||
         (o4 == 0 && between(a, b, q));
}

bool pointInTriangle2d(const P2& p, const P2& a, const P2& b, const P2& c) {
  const int o = orient2d(a, b, c);
  return orient2d(a, b, p) * o >= 0 && orient2d(b, c, p) * o >= 0 && orient2d(c, a, p) * o >= 0;
}

// Segment pq against triangle abc, all in one plane.
bool coplanarSegmentMeetsTriangle(const IPoint& p, const IPoint& q, const IPoint& a, const IPoint& b,
                                  const IPoint& c) {
  const int drop = dropAxis(a, b, c);
  const P2 p2 = project(p, drop), q2 = project(q, drop), a2 = project(a, drop), b2 = project(b, drop),
           c2 = project(c, drop);
  return pointInTriangle2d(p2, a2, b2, c2) || pointInTriangle2d(q2, a2, b2, c2) ||
         segmentsMeet2d(p2, q2, a2, b2) || segmentsMeet2d(p2, q2, b2, c2) || segmentsMeet2d(p2, q2, c2, a2);
}

// Whether the edge from v to x leaves v inside the triangle (v, y, z): x in
// the plane of the triangle and x - v within the triangle's angle at v.
bool edgeRunsInto(const IPoint& v, const IPoint& x, const IPoint& y, const IPoint& z) {
  if (orient3d(v, y, z, x) != 0) return false;
  const int drop = dropAxis(v, y, z);
  const P2 v2 = project(v, drop), x2 = project(x, drop), y2 = project(y, drop), z2 = project(z, drop);
  const int o = orient2d(v2, y2, z2);
  return orient2d(v2, y2, x2) * o >= 0 && orient2d(v2, x2, z2) * o >= 0;
}

}  // namespace

bool segmentMeetsTriangle(const IPoint& p, const IPoint& q, const IPoint& a, const IPoint& b, const IPoint& c) {
  const int s1 = sign(orient3d(a, b, c, p)), s2 = sign(orient3d(a, b, c, q));
  if (s1 * s2 > 0) return false;
  if (s1 == 0 && s2 == 0) return coplanarSegmentMeetsTriangle(p, q, a, b, c);
  // The line pq crosses the plane once; the crossing is in the triangle when
  // pq turns the same way around all three edges (zero: on an edge).
  const int o1 = sign(orient3d(p, q, a, b)), o2 = sign(orient3d(p, q, b, c)), o3 = sign(orient3d(p, q, c, a));
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

bool trianglesClash(const std::array<uint32_t, 3>& s, const std::array<uint32_t, 3>& t, const IPoint* pos) {
  int shared = 0;
  int si[3], ti[3];  // positions in s and t of the shared vertices, then the others
  bool s_used[3] = {false, false, false}, t_used[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!t_used[j] && s[i] == t[j]) {
        si[shared] = i;
        ti[shared] = j;
        s_used[i] = t_used[j] = true;
        ++shared;
        break;
      }
    }
  }
  int ns = shared, nt = shared;
  for (int i = 0; i < 3; ++i) {
    if (!s_used[i]) si[ns++] = i;
    if (!t_used[i]) ti[nt++] = i;
  }
  const IPoint &s0 = pos[s[si[0]]], &s1 = pos[s[si[1]]], &s2 = pos[s[si[2]]];
  const IPoint &t0 = pos[t[ti[0]]], &t1 = pos[t[ti[1]]], &t2 = pos[t[ti[2]]];
  switch (shared) {
    case 0:
      return segmentMeetsTriangle(s0, s1, t0, t1, t2) || segmentMeetsTriangle(s1, s2, t0, t1, t2) ||
             segmentMeetsTriangle(s2, s0, t0, t1, t2) || segmentMeetsTriangle(t0, t1, s0, s1, s2) ||
             segmentMeetsTriangle(t1, t2, s0, s1, s2) || segmentMeetsTriangle(t2, t0, s0, s1, s2);
    case 1:
      // s0 == t0: they meet elsewhere when a far edge crosses the other
      // triangle or an edge at the common vertex runs into the other one.
      return segmentMeetsTriangle(s1, s2, t0, t1, t2) || segmentMeetsTriangle(t1, t2, s0, s1, s2) ||
             edgeRunsInto(s0, s1, t1, t2) || edgeRunsInto(s0, s2, t1, t2) || edgeRunsInto(t0, t1, s1, s2) ||
             edgeRunsInto(t0, t2, s1, s2);
    case 2: {
      // Common edge s0 s1: only a fold (coplanar, same side) is a clash.
      if (orient3d(s0, s1, s2, t2) != 0) return false;
      const int drop = dropAxis(s0, s1, s2);
      const P2 a = project(s0, drop), b = project(s1, drop);
      return orient2d(a, b, project(s2, drop)) * orient2d(a, b, project(t2, drop)) >= 0;
    }
    default:
      return true;  // the same triangle twice
  }
}

}  // namespace mrsv::tetsimplify
