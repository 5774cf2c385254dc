// The boundary triangles' grid (boundary_index.h).
#include "tetsimplify/boundary_index.h"

#include <algorithm>
#include <cmath>

#include "tetsimplify/exact_predicates.h"

namespace mrsv::tetsimplify {

namespace {

constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

std::array<uint32_t, 3> faceVertices(const TetComplex& complex, uint32_t face) {
  const auto& v = complex.tet(face >> 2);
  const int f = face & 3;
  return {v[kFace[f][0]], v[kFace[f][1]], v[kFace[f][2]]};
}

void bounds(const TetComplex& complex, const std::array<uint32_t, 3>& tri, std::array<int32_t, 3>* lo,
            std::array<int32_t, 3>* hi) {
  *lo = *hi = complex.position(tri[0]);
  for (int i = 1; i < 3; ++i) {
    const IPoint& p = complex.position(tri[i]);
    for (int k = 0; k < 3; ++k) {
      (*lo)[k] = std::min((*lo)[k], p[k]);
      (*hi)[k] = std::max((*hi)[k], p[k]);
    }
  }
}

}  // namespace

void BoundaryIndex::build(const TetComplex& complex) {
  std::vector<uint32_t> faces;
  std::array<int32_t, 3> lo = {INT32_MAX, INT32_MAX, INT32_MAX}, hi = {0, 0, 0};
  double extent_sum = 0.0;
  for (uint32_t t = 0; t < complex.numTetSlots(); ++t) {
    if (!complex.tetAlive(t) || complex.boundaryMask(t) == 0) continue;
    for (uint32_t f = 0; f < 4; ++f) {
      if (!(complex.boundaryMask(t) >> f & 1)) continue;
      faces.push_back(4 * t + f);
      std::array<int32_t, 3> a, b;
      bounds(complex, faceVertices(complex, 4 * t + f), &a, &b);
      int32_t extent = 0;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], a[k]);
        hi[k] = std::max(hi[k], b[k]);
        extent = std::max(extent, b[k] - a[k]);
      }
      extent_sum += extent;
    }
  }
  cells_.clear();
  entries_ = 0;
  seen_.assign(4 * size_t(complex.numTetSlots()), 0);
  query_ = 0;
  if (faces.empty()) {
    dims_ = {0, 0, 0};
    entries_at_build_ = 0;
    return;
  }
  // Cells about twice a triangle's extent: most triangles fall in one to
  // eight cells; at most about four cells per triangle overall.
  double cell = std::max(1.0, 2.0 * extent_sum / double(faces.size()));
  auto count = [&](double c) {
    double n = 1.0;
    for (int k = 0; k < 3; ++k) n *= std::floor(double(hi[k] - lo[k]) / c) + 1.0;
    return n;
  };
  while (count(cell) > 4.0 * double(faces.size()) + 64.0) cell *= 1.25;
  cell_ = static_cast<int64_t>(std::ceil(cell));
  for (int k = 0; k < 3; ++k) {
    origin_[k] = lo[k];
    dims_[k] = static_cast<int32_t>((int64_t(hi[k]) - lo[k]) / cell_ + 1);
  }
  cells_.resize(size_t(dims_[0]) * dims_[1] * dims_[2]);
  for (uint32_t face : faces) add(complex, face);
  entries_at_build_ = entries_;
}

template <typename F>
void BoundaryIndex::forEachCell(const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi, F&& f) {
  int32_t a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = static_cast<int32_t>(std::clamp<int64_t>((lo[k] - origin_[k]) / cell_, 0, dims_[k] - 1));
    b[k] = static_cast<int32_t>(std::clamp<int64_t>((hi[k] - origin_[k]) / cell_, 0, dims_[k] - 1));
  }
  for (int32_t z = a[2]; z <= b[2]; ++z) {
    for (int32_t y = a[1]; y <= b[1]; ++y) {
      for (int32_t x = a[0]; x <= b[0]; ++x) f(cells_[(size_t(z) * dims_[1] + y) * dims_[0] + x]);
    }
  }
}

void BoundaryIndex::add(const TetComplex& complex, uint32_t face) {
  std::array<int32_t, 3> lo, hi;
  bounds(complex, faceVertices(complex, face), &lo, &hi);
  forEachCell(lo, hi, [&](std::vector<uint32_t>& cell) {
    cell.push_back(face);
    ++entries_;
  });
}

void BoundaryIndex::addFacesAround(TetComplex& complex, uint32_t v) {
  if (cells_.empty()) return;
  if (entries_ > 3 * entries_at_build_ + 1024) {
    build(complex);
    return;
  }
  complex.forEachTet(v, [&](uint32_t t, uint32_t corner) {
    const uint8_t mask = complex.boundaryMask(t);
    for (uint32_t f = 0; f < 4; ++f) {
      if (f != corner && (mask >> f & 1)) add(complex, 4 * t + f);
    }
  });
}

bool BoundaryIndex::clashes(const TetComplex& complex, const std::array<uint32_t, 3>& tri, uint32_t ignored) {
  if (cells_.empty()) return false;
  if (++query_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    query_ = 1;
  }
  std::array<int32_t, 3> lo, hi;
  bounds(complex, tri, &lo, &hi);
  bool clash = false;
  forEachCell(lo, hi, [&](std::vector<uint32_t>& cell) {
    for (uint32_t face : cell) {
      if (clash) return;
      if (seen_[face] == query_) continue;
      seen_[face] = query_;
      const uint32_t t = face >> 2;
      if (!complex.tetAlive(t) || !(complex.boundaryMask(t) >> (face & 3) & 1)) continue;
      const std::array<uint32_t, 3> other = faceVertices(complex, face);
      if (other[0] == ignored || other[1] == ignored || other[2] == ignored) continue;
      std::array<int32_t, 3> a, b;
      bounds(complex, other, &a, &b);
      if (a[0] > hi[0] || a[1] > hi[1] || a[2] > hi[2] || b[0] < lo[0] || b[1] < lo[1] || b[2] < lo[2]) continue;
      if (trianglesClash(tri, other, complex.positions().data())) clash = true;
    }
  });
  return clash;
}

}  // namespace mrsv::tetsimplify
