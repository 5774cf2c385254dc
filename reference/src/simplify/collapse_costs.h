// What a collapse costs: the Garland-Heckbert quadric error and the paper's
// energies (section 6.1, with the section 7.1 weights), and where the kept
// vertex goes with Placement::kFree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "simplify/collapse_checks.h"
#include "simplify/edge_topology.h"

namespace mrsv::simplify {

// A symmetric 4x4 matrix Q, the error of point p being [p 1] Q [p 1]^T.
// Stored as its upper triangle: a00 a01 a02 a03 a11 a12 a13 a22 a23 a33.
struct Quadric {
  std::array<double, 10> q{};

  void add(const Quadric& o) {
    for (int i = 0; i < 10; ++i) q[i] += o.q[i];
  }
  // Adds weight * (n . p + d)^2 (with |n| = 1, weight times the squared
  // distance to the plane n . p + d = 0), in place: this is the innermost
  // loop of the quadric updates, and a temporary Quadric was built in memory.
  void addPlane(const Vec3& n, double d, double weight) {
    const double a = n[0], b = n[1], c = n[2];
    q[0] += weight * a * a;
    q[1] += weight * a * b;
    q[2] += weight * a * c;
    q[3] += weight * a * d;
    q[4] += weight * b * b;
    q[5] += weight * b * c;
    q[6] += weight * b * d;
    q[7] += weight * c * c;
    q[8] += weight * c * d;
    q[9] += weight * d * d;
  }
  double evaluate(const Vec3& p) const {
    const double x = p[0], y = p[1], z = p[2];
    return x * (q[0] * x + 2.0 * (q[1] * y + q[2] * z + q[3])) +
           y * (q[4] * y + 2.0 * (q[5] * z + q[6])) + z * (q[7] * z + 2.0 * q[8]) + q[9];
  }
  // The point of least error on the plane g . p = offset (the volume
  // constraint), when the 3x3 part is well conditioned (det >=
  // kConditionLimit * (trace / 3)^3, i.e. the planes pin all three
  // directions down); false otherwise (flat or cylindrical neighbourhoods).
  bool constrainedMinimizer(const Vec3& g, double offset, Vec3* out) const;
  // The point of least error on the segment [a, b] (the fallback when the
  // minimiser is unusable: along a cylinder, say, it still finds the best
  // point of the edge, not just the best of its ends and middle).
  Vec3 segmentMinimizer(const Vec3& a, const Vec3& b) const;
};

// The signed volume between a fan of triangles and the cone from a point p
// over the fan's rim is (g . p - offset) / 6, with g the sum of the
// triangles' (unnormalised, twice-area) normals and offset the sum of
// normal . corner: linear in p, so fans add up term by term.
struct VolumeTerm {
  Vec3 g{0.0, 0.0, 0.0};
  double offset = 0.0;
  void add(const VolumeTerm& o) {
    g = {g[0] + o.g[0], g[1] + o.g[1], g[2] + o.g[2]};
    offset += o.offset;
  }
  void subtract(const VolumeTerm& o) {
    g = {g[0] - o.g[0], g[1] - o.g[1], g[2] - o.g[2]};
    offset -= o.offset;
  }
};

// What the costs need of one triangle (a, b, c): n = (b - a) x (c - a) (twice
// the area along the normal), n . a, and 1 / (2 |n|) (0 for a degenerate
// triangle). Its area-weighted plane quadric, area * distance^2, is
// (n . p - offset)^2 / (2 |n|), and its volume term is (n, offset).
struct TrianglePlane {
  Vec3 n{0.0, 0.0, 0.0};
  double offset = 0.0;
  double quadric_scale = 0.0;
};
TrianglePlane trianglePlane(const Vec3& a, const Vec3& b, const Vec3& c);

// The memoryless quadric of live vertex v: the area-weighted plane quadrics of
// the triangles of its fan as they are now (planes, by triangle number), plus
// for each boundary edge of the fan the plane through it perpendicular to its
// triangle, weighted by boundary_weight * length^2 (which keeps the boundary
// where it is); and the volume term of the fan.
void vertexQuadric(const EdgeTopology& topo, const std::vector<Vec3>& positions,
                   const std::vector<TrianglePlane>& planes, uint32_t v, double boundary_weight,
                   Quadric* quadric, VolumeTerm* volume);

// Area-weighted unit normal of live vertex v (zero if its fan has no area).
Vec3 vertexNormal(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t v);

struct PaperWeights {
  double normal = 50.0;
  double edge_length = 1.0;
  double equilateral = 5.0;
  // Lengths are measured in units of the input's mean edge length, so the
  // section 7.1 weights mean the same on every mesh whatever its scale.
  double inverse_length_unit = 1.0;
};

// The paper's energy of collapsing `removed` into `kept` placed at
// new_position (spec 6.9, decisions D14, D15):
//   normal * (1 - n_removed . n_kept) * l^2 + edge_length * l
//   + equilateral * sum over changed triangles of (E(after) - E(before)),
// E(T) = sum over the edges of T of (l_e - m_T)^2, m_T the mean edge length.
double paperEnergy(const EdgeTopology& topo, const std::vector<Vec3>& positions,
                   const std::vector<Vec3>& normals, uint32_t removed, uint32_t kept,
                   const Vec3& new_position, bool kept_moves, const PaperWeights& weights);

}  // namespace mrsv::simplify
