// spec: 9 quadtree vertex removal: the trees of the max-error (9.4) and
// wavelet (9.2) criteria, the mesh of a tree (9.3), the tile border rule (9.5)
// and the triangle-count search (9.6).
#include "mrsv/quadtree_mesh.h"

#include <algorithm>
#include <array>
#include <limits>

#include "reconstruct/quadtree_border.h"
#include "reconstruct/quadtree_error.h"
#include "reconstruct/quadtree_removal.h"
#include "reconstruct/quadtree_tree.h"

namespace mrsv {
namespace {

using quadtree::Tree;
using Triangle = std::array<std::array<uint32_t, 2>, 3>;

struct CellRef {
  int level;
  uint32_t i, j;
};

// Table 9-2 by rising diagonal and mask, looked up once: the rounds and the
// mesh ask it for every leaf.
struct CandidateTables {
  const quadtree::CellCandidates* at[2][16];
  CandidateTables() {
    for (int rising = 0; rising < 2; ++rising)
      for (int mask = 0; mask < 16; ++mask) at[rising][mask] = &quadtree::cellCandidates(mask, rising != 0);
  }
};
const CandidateTables kCandidates;

const quadtree::CellCandidates& candidatesOf(int mask, uint32_t i, uint32_t j) {
  return *kCandidates.at[quadtree::risingDiagonal(i, j) ? 1 : 0][mask];
}

// The grid points of leaf (l, i, j)'s polygon (table 9-1), by the offsets of
// kPointOffset: 0, a half side or a side. A level-0 cell has no midpoints, so
// its half side is never asked for.
struct CellGrid {
  uint32_t x[3], y[3];
  CellGrid(const Tree& tree, int l, uint32_t i, uint32_t j) {
    const uint32_t x0 = tree.originX() + (i << l), y0 = tree.originY() + (j << l);
    const uint32_t side = uint32_t{1} << l, half = side >> 1;
    x[0] = x0, x[1] = x0 + half, x[2] = x0 + side;
    y[0] = y0, y[1] = y0 + half, y[2] = y0 + side;
  }
  void point(uint8_t p, uint32_t out[2]) const {
    out[0] = x[quadtree::kPointOffset[p][0]];
    out[1] = y[quadtree::kPointOffset[p][1]];
  }
};

// The grid points of leaf (l, i, j)'s triangles for midpoint mask `mask` and
// candidate `choice` of table 9-2 (0: the table 9-1 entry).
template <class Emit>
void forEachCellTriangle(const Tree& tree, int l, uint32_t i, uint32_t j, int mask, int choice, Emit&& emit) {
  const quadtree::CellCandidates& c = candidatesOf(mask, i, j);
  const quadtree::CellCandidates::Candidate& cand = c.candidate[choice];
  const CellGrid grid(tree, l, i, j);
  for (int k = 0; k < cand.count; ++k) {
    uint32_t p[3][2];
    for (int v = 0; v < 3; ++v) grid.point(c.triangle[cand.triangle[k]][v], p[v]);
    emit(p);
  }
}

// spec 9.4: the first candidate of table 9-2 whose triangles are all within
// E, or -1. Each distinct triangle is tested at most once.
int firstCandidateWithin(const Tree& tree, const quadtree::ErrorTest& test, int l, uint32_t i, uint32_t j,
                         int mask) {
  const quadtree::CellCandidates& c = candidatesOf(mask, i, j);
  int8_t within[128];  // -1 unknown, 0 no, 1 yes
  std::fill_n(within, c.triangle.size(), int8_t{-1});
  const CellGrid grid(tree, l, i, j);
  for (size_t n = 0; n < c.candidate.size(); ++n) {
    const quadtree::CellCandidates::Candidate& cand = c.candidate[n];
    bool ok = true;
    for (int k = 0; k < cand.count && ok; ++k) {
      int8_t& w = within[cand.triangle[k]];
      if (w < 0) {
        uint32_t p[3][2];
        for (int v = 0; v < 3; ++v) grid.point(c.triangle[cand.triangle[k]][v], p[v]);
        w = test.triangleWithin(p) ? 1 : 0;
      }
      ok = w == 1;
    }
    if (ok) return static_cast<int>(n);
  }
  return -1;
}

// spec 9.4: refinement rounds. Every leaf is tested with its current midpoint
// mask; all that fail are split together (with the balance they force), and
// the rounds go on until no leaf fails. A leaf is tested again only when new
// or when its mask changed, which gives the same rounds as testing them all.
// `choice` gets each leaf's candidate (table 9-2) for its final mask.
uint32_t maxErrorTree(const quadtree::ErrorTest& test, Tree* tree, std::vector<std::vector<uint8_t>>* choice) {
  const int top = tree->top();
  std::vector<std::vector<uint8_t>> passed(top + 1), queued(top + 1);  // passed: mask + 1
  choice->assign(top + 1, {});
  for (int l = 0; l <= top; ++l) {
    passed[l].assign(size_t{tree->cellsX(l)} * tree->cellsY(l), 0);
    queued[l].assign(passed[l].size(), 0);
    (*choice)[l].assign(passed[l].size(), 0);
  }
  std::vector<CellRef> work{{top, 0, 0}}, next, failed;
  auto touch = [&](int l, uint32_t i, uint32_t j) {
    uint8_t& q = queued[l][size_t{j} * tree->cellsX(l) + i];
    if (!q) q = 1, next.push_back({l, i, j});
  };
  uint32_t rounds = 0;
  for (;;) {
    failed.clear();
    for (const CellRef& c : work) {
      const size_t k = size_t{c.j} * tree->cellsX(c.level) + c.i;
      queued[c.level][k] = 0;
      if (tree->state(c.level, c.i, c.j) != quadtree::kLeaf) continue;
      const int mask = tree->midpointMask(c.level, c.i, c.j);
      if (passed[c.level][k] == mask + 1) continue;
      int pick = -1;
      if (tree->inside(c.level, c.i, c.j)) pick = c.level == 0 ? 0 : firstCandidateWithin(*tree, test, c.level, c.i, c.j, mask);
      if (pick >= 0) {
        passed[c.level][k] = static_cast<uint8_t>(mask + 1);
        (*choice)[c.level][k] = static_cast<uint8_t>(pick);
      } else {
        failed.push_back(c);
      }
    }
    if (failed.empty()) return rounds;
    ++rounds;
    next.clear();
    for (const CellRef& c : failed) tree->split(c.level, c.i, c.j, touch);
    work.swap(next);
  }
}

// spec 9.2: the paper's bottom-up removal. Cell c of level m becomes a leaf
// (its centre vertex is removed) when its four children could, the squares of
// the level-m detail signal at its centre and its four edge midpoints sum to
// at most epsilon, and the level m-1 cells across its sides could too.
void waveletTree(const QuadtreeDetails& details, const ErrorBound& epsilon, Tree* tree) {
  const int top = tree->top(), levels = std::min(top, details.levels());
  std::vector<std::vector<uint8_t>> leafable(top + 1);
  leafable[0].assign(size_t{tree->cellsX(0)} * tree->cellsY(0), 1);
  // sum <= num / den in the stream's fixed point: sum * den <= num * 4^frac_bits.
  const __int128 limit = static_cast<__int128>(epsilon.num) << (2 * details.frac_bits);
  for (int m = 1; m <= top; ++m) {
    const uint32_t nx = tree->cellsX(m), ny = tree->cellsY(m);
    const uint32_t cx = tree->cellsX(m - 1), cy = tree->cellsY(m - 1);
    leafable[m].assign(size_t{nx} * ny, 0);
    if (m > levels) continue;
    const std::vector<int64_t>& d = details.detail[m - 1];
    const uint64_t w = details.width(m);
    auto below = [&](int64_t i, int64_t j) {  // a level m-1 cell could be a leaf (true off the grid)
      if (i < 0 || j < 0 || i >= cx || j >= cy) return true;
      return leafable[m - 1][size_t(j) * cx + size_t(i)] != 0;
    };
    for (uint32_t j = 0; j < ny; ++j)
      for (uint32_t i = 0; i < nx; ++i) {
        if (!tree->inside(m, i, j)) continue;
        const int64_t a = 2 * int64_t{i}, b = 2 * int64_t{j};
        if (!below(a, b) || !below(a + 1, b) || !below(a, b + 1) || !below(a + 1, b + 1)) continue;
        if (!below(a, b - 1) || !below(a + 1, b - 1) || !below(a + 2, b) || !below(a + 2, b + 1) ||
            !below(a, b + 2) || !below(a + 1, b + 2) || !below(a - 1, b) || !below(a - 1, b + 1))
          continue;
        __int128 sum = 0;
        const int64_t at[5][2] = {{a + 1, b + 1}, {a + 1, b}, {a + 2, b + 1}, {a + 1, b + 2}, {a, b + 1}};
        for (const auto& p : at) {
          const __int128 v = d[uint64_t(p[1]) * w + uint64_t(p[0])];
          sum += v * v;
        }
        if (sum * epsilon.den <= limit) leafable[m][size_t{j} * nx + i] = 1;
      }
  }
  // Top down: a cell is a leaf when it could be and its parent could not.
  for (int l = top; l > 0; --l)
    for (uint32_t j = 0; j < tree->cellsY(l); ++j)
      for (uint32_t i = 0; i < tree->cellsX(l); ++i)
        if (tree->state(l, i, j) == quadtree::kLeaf && !leafable[l][size_t{j} * tree->cellsX(l) + i])
          tree->split(l, i, j, [](int, uint32_t, uint32_t) {});
}

class MeshBuilder {
 public:
  MeshBuilder(const SampleField& field, GridMesh* out) : field_(field), out_(out) {
    out->dims = 2;
    out->size[0] = field.size[0], out->size[1] = field.size[1], out->size[2] = 1;
    out->points.clear(), out->values.clear(), out->cells.clear();
    index_.assign(field.values.size(), kNone);
  }
  uint32_t vertex(uint32_t x, uint32_t y) {
    uint32_t& v = index_[field_.index(x, y)];
    if (v == kNone) {
      v = static_cast<uint32_t>(out_->points.size());
      out_->points.push_back({x, y, 0});
      out_->values.push_back(field_.at(x, y));
    }
    return v;
  }
  bool isVertex(uint32_t x, uint32_t y) const { return index_[field_.index(x, y)] != kNone; }
  void triangle(const uint32_t p[3][2]) {
    out_->cells.push_back({vertex(p[0][0], p[0][1]), vertex(p[1][0], p[1][1]), vertex(p[2][0], p[2][1]), 0});
  }

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  const SampleField& field_;
  GridMesh* out_;
  std::vector<uint32_t> index_;
};

// spec 9.3: every leaf's triangles from table 9-2: candidate 0 (the look-up
// table), or each leaf's candidate chosen by the max-error test (9.4).
void meshTree(const Tree& tree, const std::vector<std::vector<uint8_t>>* choice, MeshBuilder* mesh) {
  for (int l = tree.top(); l >= 0; --l)
    for (uint32_t j = 0; j < tree.cellsY(l); ++j)
      for (uint32_t i = 0; i < tree.cellsX(l); ++i)
        if (tree.state(l, i, j) == quadtree::kLeaf)
          forEachCellTriangle(tree, l, i, j, tree.midpointMask(l, i, j),
                              choice ? (*choice)[l][size_t{j} * tree.cellsX(l) + i] : 0,
                              [&](const uint32_t p[3][2]) { mesh->triangle(p); });
}

// spec 9.5: the ring of outermost samples, each side cut by its own samples
// and zipped to the inner quadtree's boundary vertices.
void meshRing(const SampleField& field, const quadtree::ErrorTest& test, MeshBuilder* mesh) {
  const uint32_t w = field.size[0], h = field.size[1];
  std::vector<Triangle> triangles;
  for (int side = 0; side < 4; ++side) {
    const bool horizontal = side == quadtree::kBottom || side == quadtree::kTop;
    const uint32_t length = horizontal ? w - 1 : h - 1;
    // The side's line and the inner boundary line one sample in.
    const uint32_t line = side == quadtree::kBottom ? 0 : side == quadtree::kTop ? h - 1
                          : side == quadtree::kLeft ? 0 : w - 1;
    const uint32_t in = side == quadtree::kBottom || side == quadtree::kLeft ? line + 1 : line - 1;
    auto point = [&](uint32_t t, uint32_t across) {
      return horizontal ? std::array<uint32_t, 2>{t, across} : std::array<uint32_t, 2>{across, t};
    };
    const uint64_t first = horizontal ? field.index(0, line) : field.index(line, 0);
    const uint64_t step = horizontal ? 1 : w;
    std::vector<std::array<uint32_t, 2>> outer, inner;
    for (uint32_t t : quadtree::sideCuts(test, first, step, length)) outer.push_back(point(t, line));
    for (uint32_t t = 1; t < length; ++t) {
      const auto p = point(t, in);
      if (mesh->isVertex(p[0], p[1])) inner.push_back(p);
    }
    quadtree::zipStrip(outer, inner, horizontal ? 0 : 1, &triangles);
  }
  for (const Triangle& t : triangles) {
    const uint32_t p[3][2] = {{t[0][0], t[0][1]}, {t[1][0], t[1][1]}, {t[2][0], t[2][1]}};
    mesh->triangle(p);
  }
}

bool meshWith(const SampleField& field, const QuadtreeDetails* details, QuadtreeCriterion criterion,
              const ErrorBound& threshold, bool tile_borders, bool remove_vertices, GridMesh* out,
              QuadtreeReport* report) {
  const uint32_t w = field.size[0], h = field.size[1];
  Tree tree;
  MeshBuilder mesh(field, out);
  if (criterion == QuadtreeCriterion::kWavelet) {
    tree.init(0, 0, w - 1, h - 1);
    waveletTree(*details, threshold, &tree);
    meshTree(tree, nullptr, &mesh);
    return true;
  }
  const quadtree::ErrorTest test(field, threshold);
  if (tile_borders) tree.init(1, 1, w - 3, h - 3);
  else tree.init(0, 0, w - 1, h - 1);
  std::vector<std::vector<uint8_t>> choice;
  report->rounds = maxErrorTree(test, &tree, &choice);
  meshTree(tree, &choice, &mesh);
  if (tile_borders) meshRing(field, test, &mesh);
  report->vertices_removed = 0;
  report->removal_passes = 0;
  if (remove_vertices) {
    quadtree::RemovalReport removal;
    quadtree::removeVertices(test, out, quadtree::kAfterQuadtree, &removal);  // spec 9.7 (D86, D89)
    report->vertices_removed = removal.removed;
    report->removal_passes = removal.passes;
  }
  return true;
}

}  // namespace

bool quadtreeMesh(const SampleField& field, const QuadtreeDetails* details,
                  const QuadtreeOptions& options, GridMesh* out, std::string* error,
                  QuadtreeReport* report) {
  *out = GridMesh{};
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (field.dims() != 2 || field.size[0] < 2 || field.size[1] < 2 ||
      field.values.size() != uint64_t{field.size[0]} * field.size[1])
    return fail("the quadtree meshes 2-D grids of at least 2 x 2 samples");
  const bool wavelet = options.criterion == QuadtreeCriterion::kWavelet;
  if (wavelet) {
    if (!details) return fail("the wavelet criterion needs the stream's detail signals");
    if (details->size[0] != field.size[0] || details->size[1] != field.size[1])
      return fail("the detail signals are of another grid size");
    if (options.tile_borders) return fail("the tile border rule needs the max-error criterion");
    if (options.remove_vertices) return fail("the vertex-removal pass needs the max-error criterion");
  }
  if (options.tile_borders && (field.size[0] < 4 || field.size[1] < 4))
    return fail("the tile border rule needs a grid of at least 4 x 4 samples");
  if (options.max_triangles == 0 && (!options.threshold.set() || options.threshold.den <= 0))
    return fail(wavelet ? "no epsilon given" : "no maximum error given");
  QuadtreeReport local;
  QuadtreeReport* rep = report ? report : &local;
  if (options.max_triangles == 0) {
    rep->threshold = options.threshold;
    meshWith(field, details, options.criterion, options.threshold, options.tile_borders, options.remove_vertices,
             out, rep);
    return true;
  }
  // spec 9.6: the smallest k in [0, k_max] with at most max_triangles found by
  // bisection (lo = 0, hi = k_max; mid = floor((lo + hi) / 2)); the threshold
  // is k / 8 sample units (max error) or k in the stream's fixed point squared
  // (wavelet). k_max: 8 x the samples' range, or the largest sum of squares.
  int64_t k_max = 0;
  int64_t den = 8;
  if (wavelet) {
    den = int64_t{1} << (2 * details->frac_bits);
    __int128 largest = 0;
    for (const auto& level : details->detail)
      for (int64_t v : level) largest = std::max(largest, static_cast<__int128>(v) * v);
    largest *= 5;
    k_max = largest > INT64_MAX ? INT64_MAX : static_cast<int64_t>(largest);
  } else {
    const auto [lo, hi] = std::minmax_element(field.values.begin(), field.values.end());
    k_max = 8 * (int64_t{*hi} - *lo);
  }
  auto build = [&](int64_t k) {
    const ErrorBound t{k, den};
    meshWith(field, details, options.criterion, t, options.tile_borders, options.remove_vertices, out, rep);
    rep->threshold = t;
    return out->cells.size() <= options.max_triangles;
  };
  int64_t lo = 0, hi = k_max;
  while (lo < hi) {
    const int64_t mid = lo + (hi - lo) / 2;
    if (build(mid)) hi = mid;
    else lo = mid + 1;
  }
  build(lo);
  return true;
}

}  // namespace mrsv
