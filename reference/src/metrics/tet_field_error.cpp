// The scalar field of one tet mesh against another's at random positions in
// the first one's volume (the PSNR of the paper's experiment 7.2).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "metrics/splitmix64.h"
#include "metrics/surface_distance.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

const ScalarField* findField(const TetMesh& mesh, const std::string& name) {
  for (const ScalarField& f : mesh.fields)
    if (f.name == name) return &f;
  return nullptr;
}

double tetVolume(const TetMesh& mesh, const std::array<uint32_t, 4>& t) {
  const Point3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]],
               &d = mesh.positions[t[3]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

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
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const double d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1);
  const double d20 = dot(d, e0), d21 = dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  double v = den > 0.0 ? (d11 * d20 - d01 * d21) / den : 0.0;
  double w = den > 0.0 ? (d00 * d21 - d01 * d20) / den : 0.0;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1.0 - v - w, v, w};
}

// Neumaier's compensated sum: 10^6 squared errors of similar size.
struct CompensatedSum {
  double sum = 0.0, carry = 0.0;
  void add(double x) {
    const double t = sum + x;
    carry += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + carry; }
};

}  // namespace

bool measureTetFieldError(const TetMesh& a, const TetMesh& b, const TetFieldErrorOptions& options,
                          TetFieldError* result, std::string* error) {
  *result = TetFieldError{};
  if (a.fields.empty()) {
    *error = "A has no scalar field";
    return false;
  }
  const std::string name = options.field.empty() ? a.fields.front().name : options.field;
  const ScalarField* fa = findField(a, name);
  const ScalarField* fb = findField(b, name);
  if (!fa || !fb) {
    *error = std::string(fa ? "B" : "A") + " has no scalar field '" + name + "'";
    return false;
  }
  result->field = name;

  // Prefix sums of A's tet volumes; inverted and flat tets get no samples.
  std::vector<double> cumulative(a.tets.size());
  double total = 0.0;
  for (size_t t = 0; t < a.tets.size(); ++t) {
    total += std::max(tetVolume(a, a.tets[t]), 0.0);
    cumulative[t] = total;
  }
  if (!(total > 0.0)) {
    *error = "A has no positive volume";
    return false;
  }
  const auto [lo, hi] = std::minmax_element(fa->values.begin(), fa->values.end());
  result->range = fa->values.empty() ? 0.0 : *hi - *lo;

  const TetLocator locator_a(a);
  const TetLocator locator(b);
  // B's boundary and its closest-point tree, built on the first sample
  // outside B (none when B covers A's domain).
  std::vector<uint32_t> boundary_vertex;
  TriangleMesh boundary;
  std::unique_ptr<SurfaceDistanceTree> boundary_tree;

  SplitMix64 rng{options.seed};
  CompensatedSum sum_abs, sum_sq;
  for (uint64_t i = 0; i < options.sample_count; ++i) {
    // A tet with probability proportional to its volume: the first whose
    // running total exceeds a uniform fraction of the total.
    const double target = rng.unit() * total;
    const size_t t = std::min<size_t>(
        static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), target) -
                            cumulative.begin()),
        a.tets.size() - 1);
    // Uniform in the tet: the spacings of three sorted uniforms are
    // uniformly distributed barycentric coordinates.
    double u[3] = {rng.unit(), rng.unit(), rng.unit()};
    if (u[0] > u[1]) std::swap(u[0], u[1]);
    if (u[1] > u[2]) std::swap(u[1], u[2]);
    if (u[0] > u[1]) std::swap(u[0], u[1]);
    const double w[4] = {u[0], u[1] - u[0], u[2] - u[1], 1.0 - u[2]};
    const auto& tet = a.tets[t];
    Point3 p{0.0, 0.0, 0.0};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) p[d] += w[k] * a.positions[tet[k]][d];
    // A's value as B's is found (not from w), so that equal meshes give
    // equal values; p can only be missed through rounding at A's boundary.
    double va = 0.0, vb;
    if (!locator_a.interpolate(fa->values, p, &va, static_cast<int64_t>(t)))
      for (int k = 0; k < 4; ++k) va += w[k] * fa->values[tet[k]];
    if (!locator.interpolate(fb->values, p, &vb)) {
      if (!boundary_tree) {
        boundary = tetBoundary(b, &boundary_vertex);
        std::string why;
        if (!checkSurfaceMesh(boundary, &why)) {
          *error = "B's boundary: " + why;
          return false;
        }
        boundary_tree = std::make_unique<SurfaceDistanceTree>(boundary);
      }
      uint32_t face;
      const Point3 q = boundary_tree->closestPoint(p, &face);
      const auto& tri = boundary.triangles[face];
      const auto bary = triangleBary(q, boundary.positions[tri[0]], boundary.positions[tri[1]],
                                     boundary.positions[tri[2]]);
      vb = 0.0;
      for (int k = 0; k < 3; ++k) vb += bary[k] * fb->values[boundary_vertex[tri[k]]];
      ++result->outside_b;
      const double dist =
          std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                    (p[2] - q[2]) * (p[2] - q[2]));
      result->outside_b_max_distance = std::max(result->outside_b_max_distance, dist);
    }
    const double e = std::fabs(vb - va);
    result->max_abs = std::max(result->max_abs, e);
    sum_abs.add(e);
    sum_sq.add(e * e);
  }
  result->samples = options.sample_count;
  if (result->samples > 0) {
    const auto n = static_cast<double>(result->samples);
    result->mean_abs = sum_abs.value() / n;
    result->rms = std::sqrt(sum_sq.value() / n);
  }
  if (!(result->range > 0.0))
    result->psnr_db = std::numeric_limits<double>::quiet_NaN();
  else if (result->rms == 0.0)
    result->psnr_db = std::numeric_limits<double>::infinity();
  else
    result->psnr_db = 20.0 * std::log10(result->range / result->rms);
  return true;
}

}  // namespace mrsv
