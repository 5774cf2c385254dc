// Point location in a tet mesh: a uniform grid of tet bounding boxes, a
// floating-point barycentric test with a per-tet error bound, and exact
// orientation predicates when that bound cannot decide.
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "metrics/tet_predicates.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

// The barycentric frame of one tet: lambda_1..3 = inv * (p - origin),
// lambda_0 = 1 - their sum. `margin` bounds the rounding error of the
// computed lambdas for points near the tet (see frameOf).
struct Frame {
  double inv[9];
  double origin[3];
  double margin;
};

// The frame of (a, b, c, d), or false when its matrix cannot be inverted in
// doubles (a flat tet; such tets are left out of the grid).
bool frameOf(const Point3& a, const Point3& b, const Point3& c, const Point3& d, Frame* f) {
  // Columns b - a, c - a, d - a.
  const double m[9] = {b[0] - a[0], c[0] - a[0], d[0] - a[0],  //
                       b[1] - a[1], c[1] - a[1], d[1] - a[1],  //
                       b[2] - a[2], c[2] - a[2], d[2] - a[2]};
  const double c00 = m[4] * m[8] - m[5] * m[7];
  const double c01 = m[5] * m[6] - m[3] * m[8];
  const double c02 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return false;
  const double r = 1.0 / det;
  f->inv[0] = c00 * r;
  f->inv[1] = (m[2] * m[7] - m[1] * m[8]) * r;
  f->inv[2] = (m[1] * m[5] - m[2] * m[4]) * r;
  f->inv[3] = c01 * r;
  f->inv[4] = (m[0] * m[8] - m[2] * m[6]) * r;
  f->inv[5] = (m[2] * m[3] - m[0] * m[5]) * r;
  f->inv[6] = c02 * r;
  f->inv[7] = (m[1] * m[6] - m[0] * m[7]) * r;
  f->inv[8] = (m[0] * m[4] - m[1] * m[3]) * r;
  for (int i = 0; i < 3; ++i) f->origin[i] = a[i];
  // Infinity norms of the matrix and of its inverse; their product is the
  // condition number that bounds the relative error of the inverse.
  double norm_m = 0.0, norm_inv = 0.0;
  for (int i = 0; i < 3; ++i) {
    norm_m =
        std::max(norm_m, std::fabs(m[3 * i]) + std::fabs(m[3 * i + 1]) + std::fabs(m[3 * i + 2]));
    norm_inv = std::max(norm_inv, std::fabs(f->inv[3 * i]) + std::fabs(f->inv[3 * i + 1]) +
                                      std::fabs(f->inv[3 * i + 2]));
  }
  const double cond = norm_m * norm_inv;
  // A point within the tet's extent of `origin` has |p - origin| <= norm_m
  // per axis; the lambdas then carry the inverse's relative error (a few
  // units of rounding times cond) and the rounding of p - origin and of the
  // dot products (a few units times norm_inv * norm_m = cond). 64 units of
  // rounding per term leave a wide safety factor; a point whose lambdas all
  // exceed the margin is inside for certain, anything closer is decided exactly.
  f->margin = 64.0 * DBL_EPSILON * (cond + 4.0) * (1.0 + cond);
  return std::isfinite(f->margin) && f->margin < 0.25;
}

}  // namespace

struct TetLocator::Impl {
  const TetMesh* mesh = nullptr;
  std::vector<Frame> frames;        // per tet
  std::vector<int8_t> orientation;  // per tet: exact sign; 0 = never answered
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  double inv_cell[3] = {0, 0, 0};  // cells per unit length, per axis
  int64_t dims[3] = {1, 1, 1};
  std::vector<uint32_t> cell_start;  // CSR over cells; size cells + 1
  std::vector<uint32_t> cell_tets;   // ascending tet indices per cell

  int64_t cellCoord(double x, int axis) const {
    const auto i = static_cast<int64_t>(std::floor((x - lo[axis]) * inv_cell[axis]));
    return std::clamp<int64_t>(i, 0, dims[axis] - 1);
  }

  // Whether p is in the closed tet t, exactly: p replacing each corner in
  // turn gives the tet's own orientation or zero.
  bool containsExactly(uint32_t t, const Point3& p) const {
    const auto& tet = mesh->tets[t];
    const auto& x = mesh->positions;
    const int s = orientation[t];
    for (int i = 0; i < 4; ++i) {
      Point3 q[4] = {x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]};
      q[i] = p;
      if (exactOrientation(q[0], q[1], q[2], q[3]) == -s) return false;
    }
    return true;
  }
};

TetLocator::TetLocator(const TetMesh& mesh) : impl_(new Impl) {
  Impl& m = *impl_;
  m.mesh = &mesh;
  const size_t n = mesh.tets.size();
  m.frames.resize(n);
  m.orientation.assign(n, 0);
  for (size_t t = 0; t < n; ++t) {
    const auto& tet = mesh.tets[t];
    const Point3 &a = mesh.positions[tet[0]], &b = mesh.positions[tet[1]],
                 &c = mesh.positions[tet[2]], &d = mesh.positions[tet[3]];
    if (frameOf(a, b, c, d, &m.frames[t]))
      m.orientation[t] = static_cast<int8_t>(exactOrientation(a, b, c, d));
  }
  // The grid spans the bounding box of the vertices with about one cell per
  // tet, cubic cells (as near as whole counts allow).
  for (int i = 0; i < 3; ++i) {
    m.lo[i] = n ? HUGE_VAL : 0.0;
    m.hi[i] = n ? -HUGE_VAL : 0.0;
  }
  for (const auto& tet : mesh.tets)
    for (uint32_t v : tet)
      for (int i = 0; i < 3; ++i) {
        m.lo[i] = std::min(m.lo[i], mesh.positions[v][i]);
        m.hi[i] = std::max(m.hi[i], mesh.positions[v][i]);
      }
  double extent[3], volume = 1.0, largest = 0.0;
  for (int i = 0; i < 3; ++i) largest = std::max(largest, m.hi[i] - m.lo[i]);
  if (!(largest > 0.0)) largest = 1.0;
  for (int i = 0; i < 3; ++i) {
    // A flat box still gets cells of positive size.
    extent[i] = std::max(m.hi[i] - m.lo[i], largest * 1e-6);
    volume *= extent[i];
  }
  const double cell = std::cbrt(volume / static_cast<double>(std::max<size_t>(n, 1)));
  for (int i = 0; i < 3; ++i) {
    m.dims[i] = std::clamp<int64_t>(static_cast<int64_t>(std::ceil(extent[i] / cell)), 1, 1 << 20);
    m.inv_cell[i] = static_cast<double>(m.dims[i]) / extent[i];
  }
  const auto cells = static_cast<size_t>(m.dims[0] * m.dims[1] * m.dims[2]);
  // Two passes over the tets' cell ranges: count, then fill in tet order, so
  // each cell lists its tets ascending.
  m.cell_start.assign(cells + 1, 0);
  auto forCells = [&](size_t t, auto visit) {
    const auto& tet = mesh.tets[t];
    int64_t from[3], to[3];
    for (int i = 0; i < 3; ++i) {
      double x0 = mesh.positions[tet[0]][i], x1 = x0;
      for (int k = 1; k < 4; ++k) {
        x0 = std::min(x0, mesh.positions[tet[k]][i]);
        x1 = std::max(x1, mesh.positions[tet[k]][i]);
      }
      from[i] = m.cellCoord(x0, i);
      to[i] = m.cellCoord(x1, i);
    }
    for (int64_t z = from[2]; z <= to[2]; ++z)
      for (int64_t y = from[1]; y <= to[1]; ++y)
        for (int64_t x = from[0]; x <= to[0]; ++x)
          visit(static_cast<size_t>((z * m.dims[1] + y) * m.dims[0] + x));
  };
  for (size_t t = 0; t < n; ++t)
    if (m.orientation[t] != 0) forCells(t, [&](size_t c) { ++m.cell_start[c + 1]; });
  for (size_t c = 0; c < cells; ++c) m.cell_start[c + 1] += m.cell_start[c];
  m.cell_tets.resize(m.cell_start[cells]);
  std::vector<uint32_t> fill(m.cell_start.begin(), m.cell_start.end() - 1);
  for (size_t t = 0; t < n; ++t)
    if (m.orientation[t] != 0)
      forCells(t, [&](size_t c) { m.cell_tets[fill[c]++] = static_cast<uint32_t>(t); });
}

TetLocator::~TetLocator() = default;
TetLocator::TetLocator(TetLocator&&) noexcept = default;
TetLocator& TetLocator::operator=(TetLocator&&) noexcept = default;

int64_t TetLocator::locate(const Point3& p, std::array<double, 4>* bary, int64_t hint) const {
  const Impl& m = *impl_;
  for (int i = 0; i < 3; ++i)
    if (!(p[i] >= m.lo[i] && p[i] <= m.hi[i])) return -1;  // also NaN
  const size_t c = static_cast<size_t>(
      (m.cellCoord(p[2], 2) * m.dims[1] + m.cellCoord(p[1], 1)) * m.dims[0] + m.cellCoord(p[0], 0));
  // Tets the floating-point test cannot decide, in ascending order; a few at
  // most (a point near a face, edge or vertex).
  uint32_t close[64];
  size_t close_count = 0;
  double l[4];
  auto lambdas = [&](uint32_t t) {
    const Frame& f = m.frames[t];
    const double d0 = p[0] - f.origin[0], d1 = p[1] - f.origin[1], d2 = p[2] - f.origin[2];
    l[1] = f.inv[0] * d0 + f.inv[1] * d1 + f.inv[2] * d2;
    l[2] = f.inv[3] * d0 + f.inv[4] * d1 + f.inv[5] * d2;
    l[3] = f.inv[6] * d0 + f.inv[7] * d1 + f.inv[8] * d2;
    l[0] = 1.0 - l[1] - l[2] - l[3];
    return std::min(std::min(l[0], l[1]), std::min(l[2], l[3]));
  };
  auto answer = [&](uint32_t t) {
    if (bary) {
      // Clamped into the tet: a point decided exactly may have tiny
      // negative coordinates from rounding.
      double sum = 0.0;
      for (int i = 0; i < 4; ++i) sum += (l[i] = std::max(l[i], 0.0));
      for (int i = 0; i < 4; ++i) (*bary)[i] = sum > 0.0 ? l[i] / sum : 0.25;
    }
    return static_cast<int64_t>(t);
  };
  if (hint >= 0 && static_cast<size_t>(hint) < m.frames.size() && m.orientation[hint] != 0 &&
      lambdas(static_cast<uint32_t>(hint)) > m.frames[hint].margin)
    return answer(static_cast<uint32_t>(hint));
  for (uint32_t k = m.cell_start[c]; k < m.cell_start[c + 1]; ++k) {
    const uint32_t t = m.cell_tets[k];
    const double lowest = lambdas(t);
    // Inside beyond any rounding: in a valid mesh no other tet holds p.
    if (lowest > m.frames[t].margin) return answer(t);
    if (lowest >= -m.frames[t].margin) {
      if (close_count < sizeof(close) / sizeof(close[0])) {
        close[close_count++] = t;
      } else {
        // More near misses than fit (a vertex of very high degree): decide
        // the ones kept (lower indices) now, then start over with this one.
        for (size_t j = 0; j < close_count; ++j)
          if (m.containsExactly(close[j], p)) {
            lambdas(close[j]);
            return answer(close[j]);
          }
        close_count = 0;
        close[close_count++] = t;
      }
    }
  }
  for (size_t j = 0; j < close_count; ++j)
    if (m.containsExactly(close[j], p)) {
      lambdas(close[j]);
      return answer(close[j]);
    }
  return -1;
}

bool TetLocator::interpolate(const std::vector<double>& values, const Point3& p, double* value,
                             int64_t hint) const {
  std::array<double, 4> b;
  const int64_t t = locate(p, &b, hint);
  if (t < 0) return false;
  const auto& tet = impl_->mesh->tets[static_cast<size_t>(t)];
  *value =
      b[0] * values[tet[0]] + b[1] * values[tet[1]] + b[2] * values[tet[2]] + b[3] * values[tet[3]];
  return true;
}

}  // namespace mrsv
