// spec: 9.7 the vertex-removal pass.
#include "reconstruct/quadtree_removal.h"

#include "mrsv/quadtree_mesh.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace mrsv::quadtree {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;
// spec 9.7: a star larger than this is left alone. It bounds the ear search,
// cubic in the link's size.
constexpr size_t kMaxLink = 64;

uint32_t next(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
uint32_t prev(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

// The mesh as a corner table (triangle t owns corners 3t..3t+2, counter-
// clockwise; opposite_[c] is the corner across the edge c faces, kNone on the
// grid's border), changed in place by each removal.
class Remover {
 public:
  Remover(const ErrorTest& test, GridMesh* mesh) : test_(test), mesh_(mesh) {
    const size_t t_count = mesh->cells.size();
    vertex_.resize(3 * t_count);
    for (size_t t = 0; t < t_count; ++t)
      for (int k = 0; k < 3; ++k) vertex_[3 * t + k] = mesh->cells[t][k];
    // Opposites: the corner facing a -> b meets the one facing b -> a, found
    // among the half-edges leaving b (grouped by their start, a counting sort).
    const size_t v_count = mesh->points.size();
    std::vector<uint32_t> start(v_count + 1, 0), leaving(vertex_.size());
    for (uint32_t c = 0; c < vertex_.size(); ++c) ++start[vertex_[next(c)] + 1];
    for (size_t v = 0; v < v_count; ++v) start[v + 1] += start[v];
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t c = 0; c < vertex_.size(); ++c) leaving[fill[vertex_[next(c)]]++] = c;
    opposite_.assign(vertex_.size(), kNone);
    for (uint32_t c = 0; c < vertex_.size(); ++c) {
      const uint32_t a = vertex_[next(c)], b = vertex_[prev(c)];
      for (uint32_t k = start[b]; k < start[b + 1]; ++k)
        if (vertex_[prev(leaving[k])] == a) opposite_[c] = leaving[k];
    }
    corner_of_.assign(mesh->points.size(), kNone);
    for (uint32_t c = 0; c < vertex_.size(); ++c) corner_of_[vertex_[c]] = c;
  }

  bool present(uint32_t v) const { return corner_of_[v] != kNone; }
  const std::vector<uint32_t>& link() const { return poly_; }

  // spec 9.7 steps 2 to 4 for interior vertex v: true when it left the mesh.
  bool tryRemove(uint32_t v) {
    // v's link, counter-clockwise: triangle (v, a, b) gives the edge a -> b.
    poly_.clear();
    star_.clear();
    const uint32_t c0 = corner_of_[v];
    uint32_t c = c0;
    do {
      poly_.push_back(vertex_[next(c)]);
      star_.push_back(c);
      const uint32_t across = opposite_[next(c)];  // the triangle across v -> b
      if (across == kNone || poly_.size() > kMaxLink) return false;
      c = next(across);
    } while (c != c0);
    const size_t n = poly_.size();
    if (n < 3) return false;  // not a closed fan: a caller's mesh that is not a triangulation
    // The polygon starts at its smallest point in (y, x) order.
    size_t first = 0;
    for (size_t i = 1; i < n; ++i)
      if (before(poly_[i], poly_[first])) first = i;
    std::rotate(poly_.begin(), poly_.begin() + static_cast<std::ptrdiff_t>(first), poly_.end());
    std::rotate(star_.begin(), star_.begin() + static_cast<std::ptrdiff_t>(first), star_.end());
    if (!clipEars()) return false;
    replaceStar(v);
    return true;
  }

  // The mesh without the removed vertices and the dead triangles.
  void compact() {
    GridMesh out;
    out.dims = 2;
    std::copy(mesh_->size, mesh_->size + 3, out.size);
    std::vector<uint32_t> index(mesh_->points.size(), kNone);
    for (uint32_t v = 0; v < mesh_->points.size(); ++v) {
      if (!present(v)) continue;
      index[v] = static_cast<uint32_t>(out.points.size());
      out.points.push_back(mesh_->points[v]);
      out.values.push_back(mesh_->values[v]);
    }
    for (uint32_t t = 0; 3 * t < vertex_.size(); ++t)
      if (vertex_[3 * t] != kNone)
        out.cells.push_back({index[vertex_[3 * t]], index[vertex_[3 * t + 1]], index[vertex_[3 * t + 2]], 0});
    *mesh_ = std::move(out);
  }

 private:
  const std::array<uint32_t, 3>& point(uint32_t v) const { return mesh_->points[v]; }
  bool before(uint32_t a, uint32_t b) const {
    return point(a)[1] != point(b)[1] ? point(a)[1] < point(b)[1] : point(a)[0] < point(b)[0];
  }
  int64_t orient(uint32_t a, uint32_t b, uint32_t c) const {
    const auto &p = point(a), &q = point(b), &r = point(c);
    return (int64_t{q[0]} - p[0]) * (int64_t{r[1]} - p[1]) - (int64_t{q[1]} - p[1]) * (int64_t{r[0]} - p[0]);
  }
  // Triangle (a, b, c) within E (spec 9.4's test), each triple tested once per star.
  bool within(uint32_t a, uint32_t b, uint32_t c) {
    const std::array<uint32_t, 3> t = {a, b, c};
    for (const auto& [seen, ok] : tested_)
      if (seen == t) return ok;
    const uint32_t p[3][2] = {{point(a)[0], point(a)[1]}, {point(b)[0], point(b)[1]}, {point(c)[0], point(c)[1]}};
    const bool ok = test_.triangleWithin(p);
    tested_.push_back({t, ok});
    return ok;
  }
  // Step 3: the ears of the polygon, each time the first one in polygon order
  // that is convex, holds no other polygon point (on its sides neither) and is
  // within E. False when none is.
  bool clipEars() {
    ring_ = poly_;
    made_.clear();
    tested_.clear();
    while (ring_.size() > 3) {
      const size_t m = ring_.size();
      size_t ear = m;
      for (size_t i = 0; i < m && ear == m; ++i) {
        const uint32_t a = ring_[(i + m - 1) % m], b = ring_[i], c = ring_[(i + 1) % m];
        if (orient(a, b, c) <= 0) continue;
        bool empty = true;
        for (size_t j = 0; j < m && empty; ++j) {
          const uint32_t q = ring_[j];
          if (q != a && q != b && q != c && orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0)
            empty = false;
        }
        if (empty && within(a, b, c)) ear = i;
      }
      if (ear == m) return false;
      made_.push_back({ring_[(ear + m - 1) % m], ring_[ear], ring_[(ear + 1) % m]});
      ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    if (orient(ring_[0], ring_[1], ring_[2]) <= 0 || !within(ring_[0], ring_[1], ring_[2])) return false;
    made_.push_back({ring_[0], ring_[1], ring_[2]});
    return true;
  }
  // The made triangles take the first n - 2 of the star's slots; the last two die.
  void replaceStar(uint32_t v) {
    const size_t n = poly_.size();
    std::vector<uint32_t>& outer = outer_;  // the corner across polygon edge i -> i + 1
    outer.resize(n);
    for (size_t i = 0; i < n; ++i) outer[i] = opposite_[star_[i]];
    auto position = [&](uint32_t u) {
      return static_cast<size_t>(std::find(poly_.begin(), poly_.end(), u) - poly_.begin());
    };
    for (size_t k = 0; k < n; ++k) {
      const uint32_t t = star_[k] / 3;
      for (int j = 0; j < 3; ++j) {
        vertex_[3 * t + j] = k < made_.size() ? made_[k][j] : kNone;
        opposite_[3 * t + j] = kNone;
      }
    }
    for (size_t k = 0; k < made_.size(); ++k) {
      const uint32_t t = star_[k] / 3;
      for (uint32_t j = 0; j < 3; ++j) {
        const uint32_t c = 3 * t + j;
        corner_of_[vertex_[c]] = c;
        if (opposite_[c] != kNone) continue;
        const uint32_t x = vertex_[next(c)], y = vertex_[prev(c)];
        const size_t px = position(x);
        if (poly_[(px + 1) % n] == y) {  // a polygon edge: the triangle outside
          opposite_[c] = outer[px];
          if (outer[px] != kNone) opposite_[outer[px]] = c;
          continue;
        }
        for (size_t k2 = k + 1; k2 < made_.size() && opposite_[c] == kNone; ++k2) {  // a diagonal
          const uint32_t t2 = star_[k2] / 3;
          for (uint32_t j2 = 0; j2 < 3; ++j2) {
            const uint32_t c2 = 3 * t2 + j2;
            if (vertex_[next(c2)] == y && vertex_[prev(c2)] == x) {
              opposite_[c] = c2;
              opposite_[c2] = c;
            }
          }
        }
      }
    }
    corner_of_[v] = kNone;
  }

  const ErrorTest& test_;
  GridMesh* mesh_;
  std::vector<uint32_t> vertex_, opposite_, corner_of_;
  std::vector<uint32_t> poly_, star_, ring_, outer_;
  std::vector<std::array<uint32_t, 3>> made_;
  std::vector<std::pair<std::array<uint32_t, 3>, bool>> tested_;
};

}  // namespace

void removeVertices(const ErrorTest& test, GridMesh* mesh, RemovalReport* report) {
  *report = RemovalReport{};
  const uint32_t w = mesh->size[0], h = mesh->size[1];
  // Step 1: the interior vertices, finest first (the lowest set bit of x | y),
  // then by y, then by x.
  auto fineness = [&](uint32_t v) {
    return __builtin_ctz(mesh->points[v][0] | mesh->points[v][1]);
  };
  std::vector<uint32_t> order;
  for (uint32_t v = 0; v < mesh->points.size(); ++v) {
    const auto& p = mesh->points[v];
    if (p[0] > 0 && p[1] > 0 && p[0] + 1 < w && p[1] + 1 < h) order.push_back(v);
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const auto &pa = mesh->points[a], &pb = mesh->points[b];
    const int fa = fineness(a), fb = fineness(b);
    if (fa != fb) return fa < fb;
    return pa[1] != pb[1] ? pa[1] < pb[1] : pa[0] < pb[0];
  });
  Remover remover(test, mesh);
  // Step 5: passes until one removes nothing. A vertex whose star has not
  // changed since it last stayed would stay again: it is not tried.
  std::vector<uint8_t> changed(mesh->points.size(), 1);
  uint64_t removed_in_pass = 0;
  do {
    ++report->passes;
    removed_in_pass = 0;
    for (uint32_t v : order) {
      if (!remover.present(v) || !changed[v]) continue;
      changed[v] = 0;
      if (!remover.tryRemove(v)) continue;
      ++removed_in_pass;
      for (uint32_t u : remover.link()) changed[u] = 1;
    }
    report->removed += removed_in_pass;
  } while (removed_in_pass > 0);
  remover.compact();
}

}  // namespace mrsv::quadtree

namespace mrsv {

bool removeInnerVertices(const SampleField& field, const ErrorBound& bound, GridMesh* mesh, uint64_t* removed,
                         std::string* error) {
  if (field.dims() != 2 || mesh->dims != 2 || mesh->size[0] != field.size[0] || mesh->size[1] != field.size[1] ||
      field.size[0] < 2 || field.size[1] < 2) {
    if (error) *error = "the vertex-removal pass takes a 2-D mesh of the field's grid";
    return false;
  }
  if (!bound.set() || bound.den <= 0) {
    if (error) *error = "the vertex-removal pass needs a maximum error";
    return false;
  }
  const quadtree::ErrorTest test(field, bound);
  quadtree::RemovalReport report;
  quadtree::removeVertices(test, mesh, &report);
  if (removed) *removed = report.removed;
  return true;
}

}  // namespace mrsv
