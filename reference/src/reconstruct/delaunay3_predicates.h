// Exact 3-D predicates on grid points, with the symbolic perturbation that
// makes the Delaunay tetrahedralization of any point set unique.
// spec: 10.2 (orientation, in-sphere, perturbation), 10.3 (the hull).
//
// Coordinates are grid indices in [0, 2^15) (spec 10.1 bounds the sides):
// - orient3d: differences below 2^15, products of three below 2^45, the sum
//   of six below 2^48: 64-bit exact.
// - insphere: with differences below 2^15 the squared lengths stay below
//   2^32, the 3 x 3 minors below 2^48 and the four products below 2^80:
//   128-bit exact. With coordinates below 2^11 the same terms stay below
//   2^60 and their sum below 2^62, so grids of sides up to 2048 take 64 bits.
// No floating point, no filter: every implementation gets the same signs.
#pragma once

#include <array>
#include <cstdint>

namespace mrsv::reconstruct {

using GridPoint = std::array<int32_t, 3>;

// det[b - a, c - a, d - a], exactly (coordinates below 2^15).
inline int64_t orient3dValue(const GridPoint& a, const GridPoint& b, const GridPoint& c, const GridPoint& d) {
  const int64_t bx = int64_t{b[0]} - a[0], by = int64_t{b[1]} - a[1], bz = int64_t{b[2]} - a[2];
  const int64_t cx = int64_t{c[0]} - a[0], cy = int64_t{c[1]} - a[1], cz = int64_t{c[2]} - a[2];
  const int64_t dx = int64_t{d[0]} - a[0], dy = int64_t{d[1]} - a[1], dz = int64_t{d[2]} - a[2];
  return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
}

inline int signOf(int64_t v) { return (v > 0) - (v < 0); }

// The lexicographic order (x, then y, then z) of the perturbation.
inline bool lexLess(const GridPoint& p, const GridPoint& q) {
  if (p[0] != q[0]) return p[0] < q[0];
  if (p[1] != q[1]) return p[1] < q[1];
  return p[2] < q[2];
}

// The sign of the in-sphere determinant of e against the positively oriented
// (a, b, c, d): +1 when e lies strictly inside their sphere, 0 on it, -1
// outside. `Wide` is int64_t when every coordinate is below 2^11, else __int128.
template <typename Wide>
int insphere(const GridPoint& a, const GridPoint& b, const GridPoint& c, const GridPoint& d, const GridPoint& e) {
  const int64_t ax = int64_t{a[0]} - e[0], ay = int64_t{a[1]} - e[1], az = int64_t{a[2]} - e[2];
  const int64_t bx = int64_t{b[0]} - e[0], by = int64_t{b[1]} - e[1], bz = int64_t{b[2]} - e[2];
  const int64_t cx = int64_t{c[0]} - e[0], cy = int64_t{c[1]} - e[1], cz = int64_t{c[2]} - e[2];
  const int64_t dx = int64_t{d[0]} - e[0], dy = int64_t{d[1]} - e[1], dz = int64_t{d[2]} - e[2];
  // 2 x 2 minors of the (x, y) columns, shared by the four 3 x 3 minors.
  const int64_t ab = ax * by - bx * ay, ac = ax * cy - cx * ay, ad = ax * dy - dx * ay;
  const int64_t bc = bx * cy - cx * by, bd = bx * dy - dx * by, cd = cx * dy - dx * cy;
  const int64_t abc = az * bc - bz * ac + cz * ab;
  const int64_t bcd = bz * cd - cz * bd + dz * bc;
  const int64_t cda = az * cd - cz * ad + dz * ac;
  const int64_t dab = az * bd - bz * ad + dz * ab;
  const int64_t alift = ax * ax + ay * ay + az * az, blift = bx * bx + by * by + bz * bz;
  const int64_t clift = cx * cx + cy * cy + cz * cz, dlift = dx * dx + dy * dy + dz * dz;
  // det of the rows (p - e, |p - e|^2) for p = a, b, c, d, expanded along the
  // lifted column; negated so that "inside" is positive for positive tets.
  const Wide det = (Wide{dlift} * abc - Wide{clift} * dab) + (Wide{blift} * cda - Wide{alift} * bcd);
  return det < 0 ? 1 : (det > 0 ? -1 : 0);
}

// Whether e conflicts with the positive tet t[0..3] (spec 10.2): inside its
// sphere, the cospherical case decided by the perturbation of Devillers and
// Teillaud: of the five points, from the lexicographically largest down, the
// first that is e says "outside"; the first that is a corner t[k] whose
// replacement by e leaves a tet of non-zero orientation says "inside" when
// that orientation is positive. Two steps always decide (four distinct
// points of a non-flat tet and a fifth distinct point).
template <typename Wide>
bool insphereConflict(const GridPoint* const t[4], const GridPoint& e) {
  const int s = insphere<Wide>(*t[0], *t[1], *t[2], *t[3], e);
  if (s != 0) return s > 0;
  const GridPoint* pts[5] = {t[0], t[1], t[2], t[3], &e};
  // Decreasing lexicographic order, by insertion (five elements).
  for (int i = 1; i < 5; ++i)
    for (int j = i; j > 0 && lexLess(*pts[j - 1], *pts[j]); --j) std::swap(pts[j - 1], pts[j]);
  for (int i = 0; i < 5; ++i) {
    if (pts[i] == &e) return false;
    const GridPoint* r[4] = {t[0], t[1], t[2], t[3]};
    for (int k = 0; k < 4; ++k)
      if (r[k] == pts[i]) r[k] = &e;
    const int64_t o = orient3dValue(*r[0], *r[1], *r[2], *r[3]);
    if (o != 0) return o > 0;
  }
  return false;  // not reached for a non-flat tet
}

// The axis a hull face is perpendicular to: the grid box's faces are the
// hull once its corners are in, so a face's three corners share one
// coordinate. -1 when they share none (a face of the box's partial hull while
// the corners go in, never coplanar with a grid point: spec 10.3).
inline int sharedAxis(const GridPoint& a, const GridPoint& b, const GridPoint& c) {
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k]) return k;
  return -1;
}

// orient2d of three points projected along `axis` (dropping that coordinate):
// an orthogonal projection, so circles stay circles.
inline int64_t orient2dDropping(int axis, const GridPoint& a, const GridPoint& b, const GridPoint& c) {
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  return (int64_t{b[u]} - a[u]) * (int64_t{c[v]} - a[v]) - (int64_t{b[v]} - a[v]) * (int64_t{c[u]} - a[u]);
}

// The in-circle sign of d against (a, b, c) projected along `axis`: +1 inside
// when (a, b, c) is counter-clockwise in the projection, negated otherwise.
// Differences below 2^15: lifts below 2^31, terms below 2^63 (128-bit sum).
inline int incircleDropping(int axis, const GridPoint& a, const GridPoint& b, const GridPoint& c,
                            const GridPoint& d) {
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  const int64_t adx = int64_t{a[u]} - d[u], ady = int64_t{a[v]} - d[v];
  const int64_t bdx = int64_t{b[u]} - d[u], bdy = int64_t{b[v]} - d[v];
  const int64_t cdx = int64_t{c[u]} - d[u], cdy = int64_t{c[v]} - d[v];
  const __int128 det = __int128{adx * adx + ady * ady} * (bdx * cdy - bdy * cdx) +
                       __int128{bdx * bdx + bdy * bdy} * (cdx * ady - cdy * adx) +
                       __int128{cdx * cdx + cdy * cdy} * (adx * bdy - ady * bdx);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// Whether d, in the plane of the hull face (f[0], f[1], f[2]) perpendicular
// to `axis`, lies inside the face's circle (spec 10.3): the in-circle test in
// that plane, the cocircular case decided by the same perturbation in 2-D
// (from the lexicographically largest of the four points down: d says
// "outside", a corner whose replacement by d leaves a non-collinear triangle
// says "inside" when that triangle turns the same way as the face).
inline bool coplanarCircleConflict(int axis, const GridPoint* const f[3], const GridPoint& d) {
  const int64_t turn = orient2dDropping(axis, *f[0], *f[1], *f[2]);
  const int s = incircleDropping(axis, *f[0], *f[1], *f[2], d);
  if (s != 0) return (turn > 0) == (s > 0);
  const GridPoint* pts[4] = {f[0], f[1], f[2], &d};
  for (int i = 1; i < 4; ++i)
    for (int j = i; j > 0 && lexLess(*pts[j - 1], *pts[j]); --j) std::swap(pts[j - 1], pts[j]);
  for (int i = 0; i < 4; ++i) {
    if (pts[i] == &d) return false;
    const GridPoint* r[3] = {f[0], f[1], f[2]};
    for (int k = 0; k < 3; ++k)
      if (r[k] == pts[i]) r[k] = &d;
    const int64_t o = orient2dDropping(axis, *r[0], *r[1], *r[2]);
    if (o != 0) return (o > 0) == (turn > 0);
  }
  return false;  // not reached for a non-degenerate face
}

}  // namespace mrsv::reconstruct
