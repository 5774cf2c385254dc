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
constexpr uint32_t kPaired = kNone - 1;  // an edge whose two corners have met
// spec 8.8: a star larger than this is left alone. It bounds the ear search,
// cubic in the link's size. (The quadtree's pass, 9.7, stops at 6: D89.)
constexpr size_t kMaxLink = kAfterInsertion.max_link;
// Links up to this size are first checked for a triangle that could hold the
// removed vertex's sample (Remover::coverable); larger ones go straight to
// the ears (the check is cubic in the size).
constexpr size_t kMaxCoverCheck = 12;

// spec 9.7: grid point (x, y), inside the grid, bends by more than E along
// both axes: its sample is further than E from the sum of its neighbours'
// minus itself, |2 s(x, y) - s(x-1, y) - s(x+1, y)| > E, and so across y.
// Such a point is a peak, a pit or a saddle of the grid at the scale of one
// sample, which the ears cannot cut off at that E on most terrains (D89);
// it is not tried.
bool bent(const ErrorTest& test, uint32_t x, uint32_t y) {
  const SampleField& f = test.field();
  const int64_t s2 = 2 * int64_t{f.at(x, y)};
  const int64_t along_x = s2 - f.at(x - 1, y) - f.at(x + 1, y), along_y = s2 - f.at(x, y - 1) - f.at(x, y + 1);
  const __int128 least = std::min(along_x < 0 ? -along_x : along_x, along_y < 0 ? -along_y : along_y);
  return least * test.bound().den > test.bound().num;
}

uint32_t next(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
uint32_t prev(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

// The mesh as a corner table (triangle t owns corners 3t..3t+2, counter-
// clockwise; opposite_[c] is the corner across the edge c faces, kNone on the
// grid's border), changed in place by each removal. The vertices keep the
// mesh's numbers and the triangles its order (a quadtree's, leaf by leaf:
// close triangles close in memory), so that setting up costs a copy and one
// look-up per edge.
class Remover {
 public:
  Remover(const ErrorTest& test, GridMesh* mesh, size_t max_link)
      : test_(test), mesh_(mesh), max_link_(std::min(max_link, kMaxLink)) {
    const size_t t_count = mesh->cells.size();
    vertex_.resize(3 * t_count);
    for (size_t t = 0; t < t_count; ++t)
      for (int k = 0; k < 3; ++k) vertex_[3 * t + k] = mesh->cells[t][k];
    opposite_.assign(vertex_.size(), kNone);
    // An edge between grid points is known by its midpoint, (x0 + x1, y0 + y1)
    // on the half-grid: two edges of a triangulation with one midpoint would
    // cross there. The first corner facing an edge waits at its midpoint for
    // the second. For a sparse mesh on a large grid (more half-grid points
    // than 16 per triangle) the half-edges are grouped by their start instead.
    const uint64_t hw = 2 * uint64_t{mesh->size[0]} - 1, hh = 2 * uint64_t{mesh->size[1]} - 1;
    if (hw * hh <= 16 * uint64_t{t_count} + 64) matchByMidpoint(hw * hh, hw);
    else matchByStart();
    corner_of_.assign(mesh->points.size(), kNone);
    for (uint32_t c = 0; c < vertex_.size(); ++c) corner_of_[vertex_[c]] = c;
  }

  bool present(uint32_t v) const { return corner_of_[v] != kNone; }
  void prefetchCorner(uint32_t v) const {
    __builtin_prefetch(&corner_of_[v]);
    __builtin_prefetch(&mesh_->points[v]);
  }
  void prefetchStar(uint32_t v) const {
    const uint32_t c = corner_of_[v];
    if (c == kNone) return;
    __builtin_prefetch(&vertex_[c]);
    __builtin_prefetch(&opposite_[c]);
  }

  // spec 9.7 steps 2 to 4 for interior vertex v: true when it left the mesh.
  bool tryRemove(uint32_t v) {
    // v's link, counter-clockwise: triangle (v, a, b) gives the edge a -> b.
    uint32_t link[kMaxLink + 1], star[kMaxLink + 1];
    size_t n = 0;
    const uint32_t c0 = corner_of_[v];
    uint32_t c = c0;
    do {
      const uint32_t to_b = next(c);
      link[n] = vertex_[to_b];
      star[n++] = c;
      const uint32_t across = opposite_[to_b];  // the triangle across v -> b
      if (across == kNone || n > max_link_) return false;
      c = next(across);
    } while (c != c0);
    if (n < 3) return false;  // not a closed fan: a caller's mesh that is not a triangulation
    // The polygon starts at its smallest point in (y, x) order.
    const auto& pts = mesh_->points;
    size_t first = 0;
    for (size_t i = 1; i < n; ++i) {
      const auto &p = pts[link[i]], &q = pts[link[first]];
      if (p[1] < q[1] || (p[1] == q[1] && p[0] < q[0])) first = i;
    }
    const SampleField& field = test_.field();
    n_ = n;
    for (size_t i = 0, k = first; i < n; ++i, k = k + 1 == n ? 0 : k + 1) {
      poly_[i] = link[k];
      star_[i] = star[k];
      const auto& p = pts[link[k]];
      x_[i] = p[0], y_[i] = p[1];
      s_[i] = field.at(p[0], p[1]);
    }
    vx_ = pts[v][0], vy_ = pts[v][1];
    vs_ = field.at(pts[v][0], pts[v][1]);
    if (n <= kMaxCoverCheck && !coverable()) return false;
    if (!clipEars()) return false;
    replaceStar(v);
    return true;
  }
  // v's link polygon after a successful tryRemove.
  const uint32_t* link() const { return poly_; }
  size_t linkSize() const { return n_; }

  // The mesh without the removed vertices and the dead triangles.
  // In place: the arrays only shrink, and corner_of_, no longer needed,
  // becomes the vertices' new numbers.
  void compact() {
    GridMesh& m = *mesh_;
    uint32_t kept = 0;
    for (uint32_t v = 0; v < m.points.size(); ++v) {
      if (!present(v)) continue;
      corner_of_[v] = kept;
      m.points[kept] = m.points[v];
      m.values[kept++] = m.values[v];
    }
    m.points.resize(kept);
    m.values.resize(kept);
    size_t t_kept = 0;
    for (uint32_t t = 0; 3 * t < vertex_.size(); ++t)
      if (vertex_[3 * t] != kNone)
        m.cells[t_kept++] = {corner_of_[vertex_[3 * t]], corner_of_[vertex_[3 * t + 1]], corner_of_[vertex_[3 * t + 2]], 0};
    m.cells.resize(t_kept);
  }

 private:
  const std::array<uint32_t, 3>& point(uint32_t v) const { return mesh_->points[v]; }

  void matchByMidpoint(uint64_t size, uint64_t hw) {
    std::vector<uint32_t> waiting(size, kNone);
    const auto& pts = mesh_->points;
    for (uint32_t t = 0; 3 * t < vertex_.size(); ++t) {
      const uint32_t* v = &vertex_[3 * t];
      const auto &p0 = pts[v[0]], &p1 = pts[v[1]], &p2 = pts[v[2]];
      // corner 3t + k faces the edge between the other two
      const uint64_t key[3] = {p1[0] + p2[0] + (p1[1] + p2[1]) * hw, p2[0] + p0[0] + (p2[1] + p0[1]) * hw,
                               p0[0] + p1[0] + (p0[1] + p1[1]) * hw};
      for (uint32_t k = 0; k < 3; ++k) {
        uint32_t& w = waiting[key[k]];
        if (w == kNone) {
          w = 3 * t + k;
        } else if (w != kPaired) {  // a third corner on one edge (not a triangulation) stays unpaired
          opposite_[3 * t + k] = w;
          opposite_[w] = 3 * t + k;
          w = kPaired;
        }
      }
    }
  }
  // The corner facing a -> b meets the one facing b -> a. The half-edges that
  // go up in number (a < b) are grouped by their start (a counting sort),
  // each stored with its end; every half-edge going down finds its twin
  // among those leaving its end.
  void matchByStart() {
    std::vector<uint32_t> start(mesh_->points.size() + 2, 0);
    for (uint32_t c = 0; c < vertex_.size(); ++c)
      if (vertex_[next(c)] < vertex_[prev(c)]) ++start[vertex_[next(c)] + 2];
    for (size_t v = 2; v < start.size(); ++v) start[v] += start[v - 1];
    std::vector<std::pair<uint32_t, uint32_t>> up(start.back());  // (end, corner)
    for (uint32_t c = 0; c < vertex_.size(); ++c)
      if (vertex_[next(c)] < vertex_[prev(c)]) up[start[vertex_[next(c)] + 1]++] = {vertex_[prev(c)], c};
    // Now start[a] .. start[a + 1] are the half-edges going up from a.
    for (uint32_t c = 0; c < vertex_.size(); ++c) {
      const uint32_t a = vertex_[next(c)], b = vertex_[prev(c)];
      if (a < b) continue;
      for (uint32_t k = start[b]; k < start[b + 1]; ++k)
        if (up[k].first == a) {
          opposite_[c] = up[k].second;
          opposite_[up[k].second] = c;
          break;
        }
    }
  }

  int64_t orient(size_t a, size_t b, size_t c) const {
    return (x_[b] - x_[a]) * (y_[c] - y_[a]) - (y_[b] - y_[a]) * (x_[c] - x_[a]);
  }
  // orient(a, b, v): v's side of polygon edge a -> b.
  int64_t sideOfV(size_t a, size_t b) const { return (x_[b] - x_[a]) * (vy_ - y_[a]) - (y_[b] - y_[a]) * (vx_ - x_[a]); }
  // Counter-clockwise polygon triangle (a, b, c), d = orient(a, b, c) > 0: 1
  // when it holds v's point (its sides included) and v's sample is within E
  // of it, 0 when it holds the point and the sample is not, -1 when it does
  // not hold the point. The edge functions at v are its sides' orientations.
  int vSampleIn(size_t a, size_t b, size_t c, int64_t d) const {
    const int64_t w0 = sideOfV(b, c), w1 = sideOfV(c, a), w2 = sideOfV(a, b);
    if (w0 < 0 || w1 < 0 || w2 < 0) return -1;
    return test_.sampleWithin(d, w1, w2, s_[a], s_[b], s_[c], vs_) ? 1 : 0;
  }
  void corners(size_t a, size_t b, size_t c, uint32_t p[3][2]) const {
    const size_t k[3] = {a, b, c};
    for (int j = 0; j < 3; ++j) p[j][0] = static_cast<uint32_t>(x_[k[j]]), p[j][1] = static_cast<uint32_t>(y_[k[j]]);
  }
  // A necessary condition for the removal, cheap beside the ears: the
  // triangles the ears make cover v's point, so one of them, a counter-
  // clockwise triangle of polygon points holding it, has v's sample within E.
  // A vertex without any such triangle stays (as the ears would decide, after
  // scanning most of its star).
  bool coverable() const {
    const size_t n = n_;
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 1; b < n; ++b)
        for (size_t c = b + 1; c < n; ++c) {
          const int64_t d = orient(a, b, c);
          if (d > 0 && vSampleIn(a, b, c, d) == 1) return true;
        }
    return false;
  }
  // Polygon triangle (a, b, c), counter-clockwise, within E (spec 9.4's
  // test), each triangle tested once per star. v's own sample, the likeliest
  // to fail, goes first.
  bool within(size_t a, size_t b, size_t c, int64_t d) {
    // The key of the triangle whatever its first corner (positions < 64).
    const size_t lo = std::min({a, b, c});
    const uint32_t key = lo == a ? (a << 12 | b << 6 | c) : lo == b ? (b << 12 | c << 6 | a) : (c << 12 | a << 6 | b);
    for (const uint32_t seen : tested_)
      if ((seen >> 1) == key) return seen & 1;
    bool ok = vSampleIn(a, b, c, d) != 0;
    if (ok) {
      uint32_t p[3][2];
      corners(a, b, c, p);
      ok = test_.triangleWithin(p);
    }
    tested_.push_back(key << 1 | (ok ? 1u : 0u));
    return ok;
  }
  // Step 3: the ears of the polygon, each time the first one in polygon order
  // that is convex, holds no other polygon point (on its sides neither) and is
  // within E. False when none is. ring_ holds polygon positions, made_ the
  // ears' positions.
  bool clipEars() {
    const size_t n = n_;
    size_t m = n;
    for (size_t i = 0; i < n; ++i) ring_[i] = static_cast<uint8_t>(i);
    made_count_ = 0;
    tested_.clear();
    while (m > 3) {
      size_t ear = m;
      for (size_t i = 0; i < m && ear == m; ++i) {
        // The neighbours around the ring without a division (m is not a constant).
        const size_t a = ring_[i == 0 ? m - 1 : i - 1], b = ring_[i], c = ring_[i + 1 == m ? 0 : i + 1];
        const int64_t d = orient(a, b, c);
        if (d <= 0) continue;
        bool empty = true;
        for (size_t j = 0; j < m && empty; ++j) {
          const size_t q = ring_[j];
          // The diagonal c -> a first: most points lie beyond it.
          if (q != a && q != b && q != c && orient(c, a, q) >= 0 && orient(a, b, q) >= 0 && orient(b, c, q) >= 0)
            empty = false;
        }
        if (empty && within(a, b, c, d)) ear = i;
      }
      if (ear == m) return false;
      made_[made_count_++] = {ring_[ear == 0 ? m - 1 : ear - 1], ring_[ear], ring_[ear + 1 == m ? 0 : ear + 1]};
      for (size_t i = ear; i + 1 < m; ++i) ring_[i] = ring_[i + 1];
      --m;
    }
    const int64_t d = orient(ring_[0], ring_[1], ring_[2]);
    if (d <= 0 || !within(ring_[0], ring_[1], ring_[2], d)) return false;
    made_[made_count_++] = {ring_[0], ring_[1], ring_[2]};
    return true;
  }
  // The made triangles take the first n - 2 of the star's slots; the last two
  // die. A made triangle's side between polygon positions i and i + 1 faces
  // the triangle outside that polygon edge; its other sides are diagonals,
  // each shared with one other made triangle.
  void replaceStar(uint32_t v) {
    const size_t n = n_;
    uint32_t outer[kMaxLink + 1];  // the corner across polygon edge i -> i + 1
    for (size_t i = 0; i < n; ++i) outer[i] = opposite_[star_[i]];
    for (size_t k = made_count_; k < n; ++k) {
      const uint32_t t = star_[k] / 3;
      for (int j = 0; j < 3; ++j) vertex_[3 * t + j] = kNone, opposite_[3 * t + j] = kNone;
    }
    // Diagonals waiting for their twin: (from << 8 | to) of the corner's edge.
    uint32_t waiting_key[2 * kMaxLink], waiting_corner[2 * kMaxLink];
    size_t waiting = 0;
    for (size_t k = 0; k < made_count_; ++k) {
      const uint32_t t = star_[k] / 3;
      const auto& pos = made_[k];
      for (uint32_t j = 0; j < 3; ++j) {
        const uint32_t c = 3 * t + j;
        vertex_[c] = poly_[pos[j]];
        corner_of_[vertex_[c]] = c;
      }
      for (uint32_t j = 0; j < 3; ++j) {
        const uint32_t c = 3 * t + j;
        const uint32_t from = pos[j == 2 ? 0 : j + 1], to = pos[j == 0 ? 2 : j - 1];  // the edge c faces
        if (to == (from + 1 == n ? 0 : from + 1)) {  // a polygon edge: the triangle outside
          opposite_[c] = outer[from];
          if (outer[from] != kNone) opposite_[outer[from]] = c;
          continue;
        }
        const uint32_t twin = to << 8 | from;
        size_t w = 0;
        while (w < waiting && waiting_key[w] != twin) ++w;
        if (w < waiting) {
          opposite_[c] = waiting_corner[w];
          opposite_[waiting_corner[w]] = c;
          waiting_key[w] = waiting_key[--waiting], waiting_corner[w] = waiting_corner[waiting];
        } else {
          waiting_key[waiting] = from << 8 | to, waiting_corner[waiting++] = c;
        }
      }
    }
    corner_of_[v] = kNone;
  }

  const ErrorTest& test_;
  GridMesh* mesh_;
  size_t max_link_;
  std::vector<uint32_t> vertex_, opposite_, corner_of_;
  // The try's polygon (n_ points from the smallest in (y, x) order), the star's
  // corners at v (star_[i]: the triangle of polygon edge i -> i + 1), the
  // points' coordinates and samples, and v's.
  size_t n_ = 0;
  uint32_t poly_[kMaxLink + 1], star_[kMaxLink + 1];
  int64_t x_[kMaxLink + 1], y_[kMaxLink + 1], s_[kMaxLink + 1], vx_ = 0, vy_ = 0, vs_ = 0;
  uint8_t ring_[kMaxLink + 1];
  std::array<uint8_t, 3> made_[kMaxLink];  // the ears, as polygon positions
  size_t made_count_ = 0;
  std::vector<uint32_t> tested_;  // triangle key << 1 | within
};

}  // namespace

void removeVertices(const ErrorTest& test, GridMesh* mesh, const RemovalRules& rules, RemovalReport* report) {
  *report = RemovalReport{};
  const uint32_t w = mesh->size[0], h = mesh->size[1];
  Remover remover(test, mesh, rules.max_link);
  // Step 1: the interior vertices, finest first (the lowest set bit of x | y),
  // then by y, then by x: a sweep of the grid, grouped by fineness (a stable
  // counting sort).
  std::vector<uint32_t> order;
  {
    auto inner = [&](uint32_t v) {
      const auto& p = mesh->points[v];
      return p[0] > 0 && p[1] > 0 && p[0] + 1 < w && p[1] + 1 < h;
    };
    auto key = [&](uint32_t v) { return uint64_t{mesh->points[v][1]} * w + mesh->points[v][0]; };
    std::vector<uint32_t> at;  // the inner vertices in (y, x) order, kNone where none
    if (mesh->points.size() * uint64_t{16} < uint64_t{w} * h) {
      // Few points for the grid (the border cleanup's sub-mesh, 8.8): sorted,
      // not swept, so that memory follows the mesh rather than the grid.
      for (uint32_t v = 0; v < mesh->points.size(); ++v)
        if (inner(v)) at.push_back(v);
      std::sort(at.begin(), at.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    } else {
      at.assign(uint64_t{w} * h, kNone);
      for (uint32_t v = 0; v < mesh->points.size(); ++v)
        if (inner(v)) at[key(v)] = v;
    }
    std::vector<uint32_t> count(34, 0);
    auto fineness = [&](uint32_t v) {
      return static_cast<uint32_t>(__builtin_ctz(mesh->points[v][0] | mesh->points[v][1]));
    };
    for (uint32_t v : at)
      if (v != kNone) ++count[fineness(v) + 1];
    for (size_t f = 1; f < count.size(); ++f) count[f] += count[f - 1];
    order.resize(count.back());
    for (uint32_t v : at)
      if (v != kNone) order[count[fineness(v)]++] = v;
    if (rules.candidates == RemovalCandidates::kBorderZone) {
      // spec 8.8: the inner vertices of a triangle with a border vertex
      // (mesh->cells is still the mesh on entry).
      std::vector<uint8_t> zone(mesh->points.size(), 0);
      for (const auto& cell : mesh->cells)
        if (!inner(cell[0]) || !inner(cell[1]) || !inner(cell[2]))
          for (int k = 0; k < 3; ++k) zone[cell[k]] = 1;
      order.erase(std::remove_if(order.begin(), order.end(), [&](uint32_t v) { return !zone[v]; }), order.end());
    }
  }
  // Step 5: passes until one removes nothing (or max_passes). A vertex whose
  // star has not changed since it last stayed would stay again: it is not
  // tried.
  std::vector<uint8_t> changed(mesh->points.size(), 1);
  uint64_t removed_in_pass = 0;
  do {
    ++report->passes;
    removed_in_pass = 0;
    for (size_t k = 0; k < order.size(); ++k) {
      // The stars ahead, in two steps: a vertex's corner, then its triangle
      // (the sweep's loads are scattered over the corner table).
      if (k + 16 < order.size()) remover.prefetchCorner(order[k + 16]);
      if (k + 8 < order.size()) remover.prefetchStar(order[k + 8]);
      const uint32_t v = order[k];
      if (!remover.present(v) || !changed[v]) continue;
      changed[v] = 0;
      if (rules.bent_stay && bent(test, mesh->points[v][0], mesh->points[v][1])) continue;
      if (!remover.tryRemove(v)) continue;
      ++removed_in_pass;
      for (size_t i = 0; i < remover.linkSize(); ++i) changed[remover.link()[i]] = 1;
    }
    report->removed += removed_in_pass;
  } while (removed_in_pass > 0 && report->passes != rules.max_passes);
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
  quadtree::removeVertices(test, mesh, quadtree::kAfterInsertion, &report);
  if (removed) *removed = report.removed;
  return true;
}

}  // namespace mrsv
