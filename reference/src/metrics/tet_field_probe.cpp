// A tet mesh's field at any point: inside by interpolation in its tet,
// outside at the nearest boundary point.
#include <algorithm>
#include <cmath>

#include "metrics/surface_distance.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

// Barycentric coordinates of q, a point of triangle (a, b, c) (the closest
// point the AABB tree found), clamped into the triangle against rounding.
std::array<double, 3> triangleBary(const Point3& q, const Point3& a, const Point3& b,
                                   const Point3& c) {
  double e0[3], e1[3], d[3];
  for (int i = 0; i < 3; ++i) {
    e0[i] = b[i] - a[i];
    e1[i] = c[i] - a[i];
    d[i] = q[i] - a[i];
  }
  auto dot = [](const double* x, const double* y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  const double d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1);
  const double d20 = dot(d, e0), d21 = dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  double v = den > 0.0 ? (d11 * d20 - d01 * d21) / den : 0.0;
  double w = den > 0.0 ? (d00 * d21 - d01 * d20) / den : 0.0;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1.0 - v - w, v, w};
}

}  // namespace

struct TetFieldProbe::Impl {
  const std::vector<double>* values;
  TetLocator locator;
  std::vector<uint32_t> boundary_vertex;  // boundary vertex -> mesh vertex
  TriangleMesh boundary;
  std::unique_ptr<SurfaceDistanceTree> tree;  // null: no usable boundary
  Impl(const TetMesh& mesh, const std::vector<double>& v) : values(&v), locator(mesh) {}
};

TetFieldProbe::TetFieldProbe(const TetMesh& mesh, const std::vector<double>& values)
    : impl_(new Impl(mesh, values)) {
  // Built up front (a few milliseconds for 10^4 faces), so that sampling
  // only reads and may run on several threads.
  impl_->boundary = tetBoundary(mesh, &impl_->boundary_vertex);
  std::string why;
  if (checkSurfaceMesh(impl_->boundary, &why))
    impl_->tree = std::make_unique<SurfaceDistanceTree>(impl_->boundary);
}

TetFieldProbe::~TetFieldProbe() = default;
TetFieldProbe::TetFieldProbe(TetFieldProbe&&) noexcept = default;
TetFieldProbe& TetFieldProbe::operator=(TetFieldProbe&&) noexcept = default;

const TetLocator& TetFieldProbe::locator() const { return impl_->locator; }

bool TetFieldProbe::sample(const Point3& p, Sample* out, int64_t hint) const {
  const Impl& m = *impl_;
  *out = Sample{};
  if (m.locator.interpolate(*m.values, p, &out->value, hint)) {
    out->inside = true;
    return true;
  }
  if (!m.tree) return false;
  uint32_t face;
  const Point3 q = m.tree->closestPoint(p, &face);
  const auto& tri = m.boundary.triangles[face];
  const auto bary = triangleBary(q, m.boundary.positions[tri[0]], m.boundary.positions[tri[1]],
                                 m.boundary.positions[tri[2]]);
  for (int k = 0; k < 3; ++k) out->value += bary[k] * (*m.values)[m.boundary_vertex[tri[k]]];
  out->distance = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                            (p[2] - q[2]) * (p[2] - q[2]));
  return true;
}

}  // namespace mrsv
