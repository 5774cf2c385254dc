// The scalar field of one tet mesh against another's at random positions in
// the first one's volume (the PSNR of the paper's experiment 7.2).
#include <algorithm>
#include <cmath>
#include <limits>

#include "metrics/compensated_sum.h"
#include "metrics/splitmix64.h"
#include "metrics/tet_geometry.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

const ScalarField* findField(const TetMesh& mesh, const std::string& name) {
  for (const ScalarField& f : mesh.fields)
    if (f.name == name) return &f;
  return nullptr;
}

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
    const auto& tet = a.tets[t];
    total += std::max(signedTetVolume(a.positions[tet[0]], a.positions[tet[1]], a.positions[tet[2]],
                                      a.positions[tet[3]]),
                      0.0);
    cumulative[t] = total;
  }
  if (!(total > 0.0)) {
    *error = "A has no positive volume";
    return false;
  }
  const auto [lo, hi] = std::minmax_element(fa->values.begin(), fa->values.end());
  result->range = fa->values.empty() ? 0.0 : *hi - *lo;

  const TetLocator locator_a(a);
  const TetFieldProbe probe_b(b, fb->values);

  // The samples come in the order of A's tets, so that consecutive ones are
  // near each other in a mesh whose tets are stored coherently (a grid, a
  // mesher's output) and the point location runs from cache: the sorted
  // fractions of the total volume are the normalised running sums of N + 1
  // exponential variates (uniform order statistics), generated twice from
  // one stream, first for their total.
  const uint64_t n = options.sample_count;
  auto exponential = [](SplitMix64* g) { return -std::log1p(-g->unit()); };
  double spacing_total = 0.0;
  {
    SplitMix64 g = splitMixStream(options.seed, 1, 0);
    for (uint64_t i = 0; i <= n; ++i) spacing_total += exponential(&g);
  }
  SplitMix64 spacing = splitMixStream(options.seed, 1, 0);
  SplitMix64 rng = splitMixStream(options.seed, 2, 0);
  double running = 0.0;
  size_t t = 0;
  CompensatedSum sum_abs, sum_sq;
  for (uint64_t i = 0; i < n; ++i) {
    // The tet whose share of the running volume holds the next fraction:
    // each tet is chosen with probability proportional to its volume.
    running += exponential(&spacing);
    const double target = running / spacing_total * total;
    while (t + 1 < a.tets.size() && !(target < cumulative[t])) ++t;
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
    TetFieldProbe::Sample sb;
    if (!probe_b.sample(p, &sb)) {
      *error = "a sample is outside B, and B's boundary has no face of nonzero area";
      return false;
    }
    vb = sb.value;
    if (!sb.inside) {
      ++result->outside_b;
      result->outside_b_max_distance = std::max(result->outside_b_max_distance, sb.distance);
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
