// Collapse costs of the tet simplifier: the paper's terms (6.1) and a quadric
// of the linear scalar field (spec decision D44). Both work in normalised
// units: positions in mean edge lengths from the bounding box's corner, the
// scalar (the first field) in its range from its minimum.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "simplify/vec3.h"
#include "tetsimplify/tet_complex.h"

namespace mrsv::tetsimplify {

using simplify::Vec3;

// A symmetric 5x5 quadric over (x, y, z, s, 1), upper triangle row by row.
struct Quadric5 {
  std::array<double, 15> m{};

  // Adds weight * (w . (x, y, z, s, 1))^2.
  void addSquare(const std::array<double, 5>& w, double weight);
  void add(const Quadric5& o) {
    for (int i = 0; i < 15; ++i) m[i] += o.m[i];
  }
  double evaluate(const Vec3& p, double s) const;
};

// Per tet: its volume and the quadric of its linear scalar field, (s - g.x -
// c)^2 weighted by the volume, so a vertex's quadric sums the squared error
// its value would make against the input's field over the input's tets.
// Per boundary face: its plane, (n.x - d)^2 weighted by its area and
// `boundary_weight`, which keeps the domain's shape.
void initialQuadrics(const TetComplex& complex, const std::vector<Vec3>& positions,
                     const std::vector<double>& scalars, double boundary_weight, std::vector<Quadric5>* quadrics);

struct PaperWeights {
  double gradient = 1.0, volume = 1.0, equilateral = 0.1, edge_length = 0.1, normal = 1.0;
  double inverse_volume_unit = 1.0;  // 1 / the mean tet volume (in normalised units)
};

// The paper's cost (6.1, equation 8) of collapsing vt into vs: |s_a - s_b|,
// the volume change over the tets of vt, the change of their equilateral
// energy (after minus before: a collapse that makes tets less regular costs),
// the edge length, and on boundary edges (1 - n_a . n_b) |l|^2 (the paper
// writes n_a . n_b, which would make flat boundaries the dearest).
double paperCost(TetComplex& complex, const std::vector<Vec3>& positions, const std::vector<double>& scalars,
                 const std::vector<Vec3>& normals, uint32_t vs, uint32_t vt, const PaperWeights& weights);

// Area-weighted unit normal of v's boundary faces (zero for interior vertices).
Vec3 boundaryNormal(TetComplex& complex, const std::vector<Vec3>& positions, uint32_t v);

}  // namespace mrsv::tetsimplify
