// spec: 9.3 the restricted quadtree and its look-up table.
#include "reconstruct/quadtree_tree.h"

#include <algorithm>

namespace mrsv::quadtree {

void Tree::init(uint32_t ox, uint32_t oy, uint32_t lx, uint32_t ly) {
  ox_ = ox, oy_ = oy, lx_ = lx, ly_ = ly;
  top_ = 0;
  while ((uint64_t{1} << top_) < lx || (uint64_t{1} << top_) < ly) ++top_;
  nx_.assign(top_ + 1, 0);
  ny_.assign(top_ + 1, 0);
  state_.assign(top_ + 1, {});
  for (int l = 0; l <= top_; ++l) {
    // The cells that start inside the rectangle: ceil(length / 2^l), at least 1.
    nx_[l] = static_cast<uint32_t>(((uint64_t{lx} + (uint64_t{1} << l) - 1) >> l));
    ny_[l] = static_cast<uint32_t>(((uint64_t{ly} + (uint64_t{1} << l) - 1) >> l));
    if (nx_[l] == 0) nx_[l] = 1;
    if (ny_[l] == 0) ny_[l] = 1;
    state_[l].assign(size_t{nx_[l]} * ny_[l], kAbsent);
  }
  state_[top_][0] = kLeaf;
}

namespace {

// Table 9-1, built once: mask 0 is two triangles on the diagonal; any other
// mask is a fan from its first midpoint in the order B, R, T, L over the
// polygon's present points (a fan from a midpoint never has three collinear
// points: the only points collinear with it are its own edge's corners, which
// are its polygon neighbours).
struct Table {
  CellTriangles entry[2][16];
  Table() {
    for (int rising = 0; rising < 2; ++rising)
      for (int mask = 0; mask < 16; ++mask) {
        CellTriangles& t = entry[rising][mask];
        t = {};
        if (mask == 0) {
          t.count = 2;
          const uint8_t a[2][3] = {{0, 2, 6}, {2, 4, 6}}, b[2][3] = {{0, 2, 4}, {0, 4, 6}};
          for (int k = 0; k < 2; ++k)
            for (int v = 0; v < 3; ++v) t.point[k][v] = rising ? b[k][v] : a[k][v];
          continue;
        }
        int apex = 0;
        while (!(mask >> apex & 1)) ++apex;
        const int start = 2 * apex + 1;
        uint8_t polygon[8];
        int n = 0;
        for (int k = 0; k < 8; ++k) {
          const int p = (start + k) & 7;
          if ((p & 1) == 0 || (mask >> (p >> 1) & 1)) polygon[n++] = static_cast<uint8_t>(p);
        }
        t.count = n - 2;
        for (int k = 1; k + 1 < n; ++k) {
          t.point[k - 1][0] = polygon[0];
          t.point[k - 1][1] = polygon[k];
          t.point[k - 1][2] = polygon[k + 1];
        }
      }
  }
};

}  // namespace

const CellTriangles& cellTriangles(int mask, bool rising) {
  static const Table table;
  return table.entry[rising ? 1 : 0][mask & 15];
}

namespace {

using Tri = std::array<uint8_t, 3>;

// Every triangulation of the chain of polygon points poly[a..b] closed by the
// edge (a, b), with no flat triangle: for k = a+1..b-1, the triangle
// (a, k, b) with each triangulation of (a, k) and then of (k, b).
std::vector<std::vector<Tri>> chainTriangulations(const std::vector<uint8_t>& poly, size_t a, size_t b) {
  if (b - a < 2) return {{}};
  std::vector<std::vector<Tri>> out;
  for (size_t k = a + 1; k < b; ++k) {
    const uint8_t* p = kPointOffset[poly[a]];
    const uint8_t* q = kPointOffset[poly[k]];
    const uint8_t* r = kPointOffset[poly[b]];
    if ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]) == 0) continue;  // flat
    const auto left = chainTriangulations(poly, a, k), right = chainTriangulations(poly, k, b);
    for (const auto& l : left)
      for (const auto& r2 : right) {
        std::vector<Tri> t{{poly[a], poly[k], poly[b]}};
        t.insert(t.end(), l.begin(), l.end());
        t.insert(t.end(), r2.begin(), r2.end());
        out.push_back(std::move(t));
      }
  }
  return out;
}

struct Candidates {
  CellCandidates entry[2][16];
  Candidates() {
    for (int rising = 0; rising < 2; ++rising)
      for (int mask = 0; mask < 16; ++mask) {
        CellCandidates& c = entry[rising][mask];
        auto add = [&](const std::vector<Tri>& triangles) {
          CellCandidates::Candidate cand{};
          cand.count = static_cast<uint8_t>(triangles.size());
          for (size_t k = 0; k < triangles.size(); ++k) {
            size_t id = 0;
            while (id < c.triangle.size() && c.triangle[id] != triangles[k]) ++id;
            if (id == c.triangle.size()) c.triangle.push_back(triangles[k]);
            cand.triangle[k] = static_cast<uint8_t>(id);
          }
          c.candidate.push_back(cand);
        };
        // Triangles as (smallest polygon position first) so that equal sets compare equal.
        std::vector<uint8_t> poly;
        for (uint8_t p = 0; p < 8; ++p)
          if ((p & 1) == 0 || (mask >> (p >> 1) & 1)) poly.push_back(p);
        auto canonical = [&](std::vector<Tri> t) {
          for (Tri& x : t) {
            auto pos = [&](uint8_t v) { return std::find(poly.begin(), poly.end(), v) - poly.begin(); };
            while (pos(x[0]) > pos(x[1]) || pos(x[0]) > pos(x[2])) x = {x[1], x[2], x[0]};
          }
          std::sort(t.begin(), t.end());
          return t;
        };
        const CellTriangles& table = cellTriangles(mask, rising != 0);
        std::vector<Tri> first;
        for (int k = 0; k < table.count; ++k) first.push_back({table.point[k][0], table.point[k][1], table.point[k][2]});
        first = canonical(first);
        add(first);
        for (const auto& t : chainTriangulations(poly, 0, poly.size() - 1)) {
          const std::vector<Tri> sorted = canonical(t);
          if (sorted != first) add(t);
        }
        std::vector<Tri> fan;
        for (size_t k = 0; k < poly.size(); ++k) fan.push_back({kCentre, poly[k], poly[(k + 1) % poly.size()]});
        add(fan);
      }
  }
};

}  // namespace

const CellCandidates& cellCandidates(int mask, bool rising) {
  static const Candidates candidates;
  return candidates.entry[rising ? 1 : 0][mask & 15];
}

}  // namespace mrsv::quadtree
