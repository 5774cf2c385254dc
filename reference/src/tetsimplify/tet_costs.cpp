// Collapse costs (tet_costs.h).
#include "tetsimplify/tet_costs.h"

#include <cmath>

namespace mrsv::tetsimplify {

using simplify::cross;
using simplify::dot;
using simplify::length;
using simplify::sub;

namespace {

// The outward face opposite each corner of a positively oriented tet.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

double volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6.0;
}

// Sum over the six edges of (length - mean length)^2.
double equilateralEnergy(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double l[6] = {length(sub(a, b)), length(sub(a, c)), length(sub(a, d)),
                       length(sub(b, c)), length(sub(b, d)), length(sub(c, d))};
  const double m = (l[0] + l[1] + l[2] + l[3] + l[4] + l[5]) / 6.0;
  double e = 0.0;
  for (double x : l) e += (x - m) * (x - m);
  return e;
}

}  // namespace

void Quadric5::addSquare(const std::array<double, 5>& w, double weight) {
  int k = 0;
  for (int i = 0; i < 5; ++i) {
    for (int j = i; j < 5; ++j) m[k++] += weight * w[i] * w[j];
  }
}

double Quadric5::evaluate(const Vec3& p, double s) const {
  const double x = p[0], y = p[1], z = p[2];
  // Row by row of the upper triangle: m[0..4] row 0, m[5..8] row 1, m[9..11]
  // row 2, m[12..13] row 3, m[14] row 4; off-diagonal terms count twice.
  return x * (m[0] * x + 2.0 * (m[1] * y + m[2] * z + m[3] * s + m[4])) +
         y * (m[5] * y + 2.0 * (m[6] * z + m[7] * s + m[8])) + z * (m[9] * z + 2.0 * (m[10] * s + m[11])) +
         s * (m[12] * s + 2.0 * m[13]) + m[14];
}

void initialQuadrics(const TetComplex& complex, const std::vector<Vec3>& positions,
                     const std::vector<double>& scalars, double boundary_weight, std::vector<Quadric5>* quadrics) {
  quadrics->assign(positions.size(), Quadric5{});
  for (uint32_t t = 0; t < complex.numTetSlots(); ++t) {
    if (!complex.tetAlive(t)) continue;
    const auto& v = complex.tet(t);
    const Vec3 &p0 = positions[v[0]], &p1 = positions[v[1]], &p2 = positions[v[2]], &p3 = positions[v[3]];
    const Vec3 e1 = sub(p1, p0), e2 = sub(p2, p0), e3 = sub(p3, p0);
    const double det = dot(e1, cross(e2, e3));
    if (det > 0.0) {
      // The gradient of the linear interpolant: solve [e1 e2 e3]^T g = ds.
      const double d1 = scalars[v[1]] - scalars[v[0]], d2 = scalars[v[2]] - scalars[v[0]],
                   d3 = scalars[v[3]] - scalars[v[0]];
      const Vec3 c23 = cross(e2, e3), c31 = cross(e3, e1), c12 = cross(e1, e2);
      Vec3 g;
      for (int i = 0; i < 3; ++i) g[i] = (d1 * c23[i] + d2 * c31[i] + d3 * c12[i]) / det;
      const double c = scalars[v[0]] - dot(g, p0);
      Quadric5 q;
      q.addSquare({-g[0], -g[1], -g[2], 1.0, -c}, det / 6.0);
      for (int i = 0; i < 4; ++i) (*quadrics)[v[i]].add(q);
    }
    const uint8_t mask = complex.boundaryMask(t);
    if (mask == 0 || boundary_weight <= 0.0) continue;
    for (int f = 0; f < 4; ++f) {
      if (!(mask >> f & 1)) continue;
      const Vec3 &a = positions[v[kFace[f][0]]], &b = positions[v[kFace[f][1]]], &c = positions[v[kFace[f][2]]];
      const Vec3 n2 = cross(sub(b, a), sub(c, a));
      const double len = length(n2);
      if (len <= 0.0) continue;
      const Vec3 n = {n2[0] / len, n2[1] / len, n2[2] / len};
      Quadric5 q;
      q.addSquare({n[0], n[1], n[2], 0.0, -dot(n, a)}, 0.5 * len * boundary_weight);
      for (int i = 0; i < 3; ++i) (*quadrics)[v[kFace[f][i]]].add(q);
    }
  }
}

double paperCost(TetComplex& complex, const std::vector<Vec3>& positions, const std::vector<double>& scalars,
                 const std::vector<Vec3>& normals, uint32_t vs, uint32_t vt, const PaperWeights& weights) {
  const Vec3& ps = positions[vs];
  const Vec3 edge = sub(ps, positions[vt]);
  const double len2 = dot(edge, edge);
  double before = 0.0, after = 0.0, equi = 0.0;
  complex.forEachTet(vt, [&](uint32_t t, uint32_t corner) {
    const auto& v = complex.tet(t);
    const Vec3 &a = positions[v[0]], &b = positions[v[1]], &c = positions[v[2]], &d = positions[v[3]];
    before += volume(a, b, c, d);
    if (v[0] == vs || v[1] == vs || v[2] == vs || v[3] == vs) return;  // vanishes
    Vec3 q[4] = {a, b, c, d};
    q[corner] = ps;
    after += volume(q[0], q[1], q[2], q[3]);
    if (weights.equilateral != 0.0) {
      equi += equilateralEnergy(q[0], q[1], q[2], q[3]) - equilateralEnergy(a, b, c, d);
    }
  });
  double cost = weights.gradient * std::fabs(scalars[vs] - scalars[vt]) +
                weights.volume * std::fabs(before - after) * weights.inverse_volume_unit +
                weights.equilateral * equi + weights.edge_length * std::sqrt(len2);
  if (complex.onBoundary(vs) && complex.onBoundary(vt)) {
    cost += weights.normal * (1.0 - dot(normals[vs], normals[vt])) * len2;
  }
  return cost;
}

Vec3 boundaryNormal(TetComplex& complex, const std::vector<Vec3>& positions, uint32_t v) {
  Vec3 n = {0.0, 0.0, 0.0};
  if (!complex.onBoundary(v)) return n;
  complex.forEachTet(v, [&](uint32_t t, uint32_t corner) {
    const uint8_t mask = complex.boundaryMask(t);
    if (mask == 0) return;
    const auto& w = complex.tet(t);
    for (uint32_t f = 0; f < 4; ++f) {
      if (f == corner || !(mask >> f & 1)) continue;
      const Vec3 &a = positions[w[kFace[f][0]]], &b = positions[w[kFace[f][1]]], &c = positions[w[kFace[f][2]]];
      const Vec3 m = cross(sub(b, a), sub(c, a));
      for (int i = 0; i < 3; ++i) n[i] += m[i];
    }
  });
  const double len = length(n);
  if (len > 0.0) {
    for (double& x : n) x /= len;
  }
  return n;
}

}  // namespace mrsv::tetsimplify
