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
      if (across == kNone || poly_.size() > max_link_) return false;
      c = next(across);
    } while (c != c0);
    const size_t n = poly_.size();
    if (n < 3) return false;  // not a closed fan: a caller's mesh that is not a triangulation
    // The polygon starts at its smallest point in (y, x) order.
    size_t first = 0;
    for (size_t i = 1; i < n; ++i) {
      const auto &p = point(poly_[i]), &q = point(poly_[first]);
      if (p[1] < q[1] || (p[1] == q[1] && p[0] < q[0])) first = i;
    }
    std::rotate(poly_.begin(), poly_.begin() + static_cast<std::ptrdiff_t>(first), poly_.end());
    std::rotate(star_.begin(), star_.begin() + static_cast<std::ptrdiff_t>(first), star_.end());
    for (size_t i = 0; i < n; ++i) {
      x_[i] = point(poly_[i])[0];
      y_[i] = point(poly_[i])[1];
    }
    vx_ = point(v)[0], vy_ = point(v)[1];
    if (n <= kMaxCoverCheck && !coverable()) return false;
    if (!clipEars()) return false;
    replaceStar(v);
    return true;
  }

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
  // Does polygon triangle (a, b, c), counter-clockwise, hold v's point (its
  // sides included)?
  bool holdsV(size_t a, size_t b, size_t c) const {
    auto side = [&](size_t p, size_t q) { return (x_[q] - x_[p]) * (vy_ - y_[p]) - (y_[q] - y_[p]) * (vx_ - x_[p]); };
    return side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0;
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
    const size_t n = poly_.size();
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 1; b < n; ++b)
        for (size_t c = b + 1; c < n; ++c) {
          if (orient(a, b, c) <= 0 || !holdsV(a, b, c)) continue;
          uint32_t p[3][2];
          corners(a, b, c, p);
          if (test_.pointWithin(p, static_cast<uint32_t>(vx_), static_cast<uint32_t>(vy_))) return true;
        }
    return false;
  }
  // Polygon triangle (a, b, c) within E (spec 9.4's test), each triangle
  // tested once per star. v's own sample, the likeliest to fail, goes first.
  bool within(size_t a, size_t b, size_t c) {
    // The key of the triangle whatever its first corner (positions < 64).
    const size_t lo = std::min({a, b, c});
    const uint32_t key = lo == a ? (a << 12 | b << 6 | c) : lo == b ? (b << 12 | c << 6 | a) : (c << 12 | a << 6 | b);
    for (const uint32_t seen : tested_)
      if ((seen >> 1) == key) return seen & 1;
    uint32_t p[3][2];
    corners(a, b, c, p);
    const bool ok = (!holdsV(a, b, c) || test_.pointWithin(p, static_cast<uint32_t>(vx_), static_cast<uint32_t>(vy_))) &&
                    test_.triangleWithin(p);
    tested_.push_back(key << 1 | (ok ? 1u : 0u));
    return ok;
  }
  // Step 3: the ears of the polygon, each time the first one in polygon order
  // that is convex, holds no other polygon point (on its sides neither) and is
  // within E. False when none is. ring_ holds polygon positions.
  bool clipEars() {
    const size_t n = poly_.size();
    ring_.resize(n);
    for (size_t i = 0; i < n; ++i) ring_[i] = static_cast<uint8_t>(i);
    made_.clear();
    tested_.clear();
    while (ring_.size() > 3) {
      const size_t m = ring_.size();
      size_t ear = m;
      for (size_t i = 0; i < m && ear == m; ++i) {
        // The neighbours around the ring without a division (m is not a constant).
        const size_t a = ring_[i == 0 ? m - 1 : i - 1], b = ring_[i], c = ring_[i + 1 == m ? 0 : i + 1];
        if (orient(a, b, c) <= 0) continue;
        bool empty = true;
        for (size_t j = 0; j < m && empty; ++j) {
          const size_t q = ring_[j];
          if (q != a && q != b && q != c && orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0)
            empty = false;
        }
        if (empty && within(a, b, c)) ear = i;
      }
      if (ear == m) return false;
      made_.push_back({poly_[ring_[ear == 0 ? m - 1 : ear - 1]], poly_[ring_[ear]], poly_[ring_[ear + 1 == m ? 0 : ear + 1]]});
      ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    if (orient(ring_[0], ring_[1], ring_[2]) <= 0 || !within(ring_[0], ring_[1], ring_[2])) return false;
    made_.push_back({poly_[ring_[0]], poly_[ring_[1]], poly_[ring_[2]]});
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
        if (poly_[px + 1 == n ? 0 : px + 1] == y) {  // a polygon edge: the triangle outside
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
  size_t max_link_;
  std::vector<uint32_t> vertex_, opposite_, corner_of_;
  std::vector<uint32_t> poly_, star_, outer_;
  std::vector<uint8_t> ring_;
  int64_t x_[kMaxLink + 1], y_[kMaxLink + 1], vx_ = 0, vy_ = 0;  // the polygon's points and v's
  std::vector<std::array<uint32_t, 3>> made_;
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
    for (uint32_t v : order) {
      if (!remover.present(v) || !changed[v]) continue;
      changed[v] = 0;
      if (rules.bent_stay && bent(test, mesh->points[v][0], mesh->points[v][1])) continue;
      if (!remover.tryRemove(v)) continue;
      ++removed_in_pass;
      for (uint32_t u : remover.link()) changed[u] = 1;
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
