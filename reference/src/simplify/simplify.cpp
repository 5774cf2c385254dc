// The simplifier's driver: a priority queue of candidate collapses, grouped
// into batches of independent collapses (spec 6.9).
//
// Every edge has one queue entry for its cheaper allowed direction. Entries
// are never updated in place: a collapse bumps the version of the vertices
// whose cost inputs changed and pushes fresh entries; an entry whose versions
// no longer match is skipped when popped (lazy deletion). Consistency is
// checked when an entry is popped, since it depends on the neighbourhood as it
// is then; an entry that fails tries the other direction once and is
// otherwise dropped until a collapse next to it pushes the edge again, or the
// queue runs dry and is rebuilt from all edges.
//
// A batch pops candidates in cost order. Accepting a collapse locks both
// endpoints and all their neighbours; a popped candidate touching a locked
// vertex waits for the next batch. Unlocked vertices keep their
// neighbourhood through the batch, so the accepted collapses satisfy the
// independence rule of SimplifyResult by construction.
#include "simplify/simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "simplify/collapse_checks.h"
#include "simplify/collapse_costs.h"
#include "simplify/edge_topology.h"

namespace mrsv {

namespace {

using simplify::EdgeTopology;
using simplify::kNone;
using simplify::Quadric;
using simplify::Vec3;

// Perpendicular boundary planes weigh this much per squared edge length
// (triangle planes weigh their area, about 0.43 per squared edge length), so
// a boundary that bends costs far more than an interior that bends.
constexpr double kBoundaryWeight = 100.0;
// How often (in collapses) the clock and the progress callback are consulted.
constexpr uint32_t kCheckInterval = 1024;

struct Candidate {
  double cost;
  uint32_t h;        // a half-edge of the edge when the entry was made
  uint32_t removed;
  uint32_t kept;
  uint32_t version;  // version[removed] + version[kept] then; versions only grow
  bool second_choice;
};

// Min-heap order with a total tie-break, so the result never depends on the
// heap's internals.
struct LaterCandidate {
  bool operator()(const Candidate& a, const Candidate& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    if (a.h != b.h) return a.h > b.h;
    return a.removed > b.removed;
  }
};

class Simplifier {
 public:
  Simplifier(const SimplifyOptions& options) : options_(options) {}

  bool init(const TriangleMesh& mesh, std::string* error);
  void run(SimplifyResult* result);

 private:
  bool evaluate(uint32_t removed, uint32_t kept, uint32_t h, double* cost, Vec3* position) const;
  void pushEdge(uint32_t h, std::vector<Candidate>* out);
  void pushEdgesAround(uint32_t v, std::vector<Candidate>* out);
  void pushHeap(const Candidate& c) {
    heap_.push_back(c);
    std::push_heap(heap_.begin(), heap_.end(), LaterCandidate());
  }
  bool fresh(const Candidate& c) const {
    return topo_.alive(c.removed) && topo_.alive(c.kept) &&
           version_[c.removed] + version_[c.kept] == c.version;
  }
  uint32_t currentHalfEdge(const Candidate& c) const;
  void rebuildHeap();
  void lockNeighbourhood(uint32_t v, uint32_t batch);

  const SimplifyOptions& options_;
  EdgeTopology topo_;
  std::vector<Vec3> positions_;
  std::vector<Quadric> quadrics_;
  std::vector<Vec3> normals_;  // CollapseCost::kPaper only
  std::vector<uint32_t> version_;
  std::vector<uint32_t> locked_in_batch_;  // batch number + 1 that locked the vertex
  std::vector<Candidate> heap_;
  std::vector<Candidate> deferred_;
  std::vector<uint32_t> scratch_;
  simplify::VertexMarks marks_;
  simplify::GeometryLimits limits_;
  simplify::PaperWeights paper_;
  double cost_floor_ = 0.0;
  uint64_t live_vertices_ = 0;
};

bool Simplifier::init(const TriangleMesh& mesh, std::string* error) {
  if (!topo_.build(mesh, error)) return false;
  positions_ = mesh.positions;
  for (const Vec3& p : positions_) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      *error = "a vertex position is not finite";
      return false;
    }
  }
  const uint32_t nv = topo_.numVertices();
  version_.assign(nv, 0);
  locked_in_batch_.assign(nv, 0);
  marks_.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) live_vertices_ += topo_.alive(v);

  double length_sum = 0.0;
  uint64_t edges = 0;
  for (uint32_t h = 0; h < 3 * topo_.numTriangles(); ++h) {
    const uint32_t o = topo_.opposite(h);
    if (o != kNone && o < h) continue;
    const Vec3& a = positions_[topo_.vertexOf(h)];
    const Vec3& b = positions_[topo_.target(h)];
    length_sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
    ++edges;
  }
  const double unit = edges > 0 && length_sum > 0.0 ? length_sum / static_cast<double>(edges) : 1.0;
  paper_.normal = options_.weight_normal;
  paper_.edge_length = options_.weight_edge_length;
  paper_.equilateral = options_.weight_equilateral;
  paper_.inverse_length_unit = 1.0 / unit;

  buildQuadrics(topo_, positions_, kBoundaryWeight, &quadrics_);
  if (options_.cost == CollapseCost::kPaper) {
    normals_.assign(nv, Vec3{0.0, 0.0, 0.0});
    for (uint32_t v = 0; v < nv; ++v) {
      if (topo_.alive(v)) normals_[v] = simplify::vertexNormal(topo_, positions_, v);
    }
    // The energies are in units of the mean edge length: 1e-9 of one unit is
    // "no cost" for the batch rule.
    cost_floor_ = 1e-9;
  } else {
    // Quadric errors are area times squared distance: unit^4.
    cost_floor_ = 1e-12 * unit * unit * unit * unit;
  }
  return true;
}

bool Simplifier::evaluate(uint32_t removed, uint32_t kept, uint32_t h, double* cost,
                          Vec3* position) const {
  const Vec3& pk = positions_[kept];
  bool kept_moves = false;
  if (options_.placement == Placement::kEndpoint) {
    *position = pk;
  } else {
    Quadric q = quadrics_[removed];
    q.add(quadrics_[kept]);
    const Vec3& pr = positions_[removed];
    if (topo_.edgeOnBoundary(h)) {
      // A boundary vertex only ever takes the place of another one, so that
      // the boundary vertices stay exactly on the input's boundary (a point
      // between them would be on a chord of it).
      *position = q.evaluate(pr) < q.evaluate(pk) ? pr : pk;
    } else if (topo_.onBoundary(kept)) {
      *position = pk;  // a boundary vertex only moves along a boundary edge
    } else {
      const Vec3 mid = {0.5 * (pr[0] + pk[0]), 0.5 * (pr[1] + pk[1]), 0.5 * (pr[2] + pk[2])};
      Vec3 x;
      // The optimum is used only near the edge (within one edge length of its
      // midpoint); a far optimum comes from nearly parallel planes.
      const double len2 = (pr[0] - pk[0]) * (pr[0] - pk[0]) + (pr[1] - pk[1]) * (pr[1] - pk[1]) +
                          (pr[2] - pk[2]) * (pr[2] - pk[2]);
      if (q.minimizer(&x) && (x[0] - mid[0]) * (x[0] - mid[0]) + (x[1] - mid[1]) * (x[1] - mid[1]) +
                                     (x[2] - mid[2]) * (x[2] - mid[2]) <=
                                 len2) {
        *position = x;
      } else {
        const double ek = q.evaluate(pk), er = q.evaluate(pr), em = q.evaluate(mid);
        *position = ek <= er && ek <= em ? pk : (er <= em ? pr : mid);
      }
    }
    kept_moves = *position != pk;
  }
  if (options_.cost == CollapseCost::kQuadric) {
    *cost = quadrics_[removed].evaluate(*position) + quadrics_[kept].evaluate(*position);
  } else {
    *cost = simplify::paperEnergy(topo_, positions_, normals_, removed, kept, *position, kept_moves,
                                  paper_);
  }
  return kept_moves;
}

void Simplifier::pushEdge(uint32_t h, std::vector<Candidate>* out) {
  const uint32_t a = topo_.vertexOf(h);
  const uint32_t b = topo_.target(h);
  Vec3 position;
  Candidate best{};
  bool have = false;
  for (int dir = 0; dir < 2; ++dir) {
    const uint32_t removed = dir == 0 ? a : b;
    const uint32_t kept = dir == 0 ? b : a;
    if (!simplify::boundaryRuleAllows(topo_, removed, h)) continue;
    double cost;
    evaluate(removed, kept, h, &cost, &position);
    if (!have || cost < best.cost) {
      best = {cost, h, removed, kept, version_[removed] + version_[kept], false};
      have = true;
    }
  }
  if (have) out->push_back(best);
}

void Simplifier::pushEdgesAround(uint32_t v, std::vector<Candidate>* out) {
  uint32_t last = kNone;
  topo_.forEachOutgoing(v, [&](uint32_t h) {
    pushEdge(h, out);
    last = h;
  });
  // The last edge of a boundary fan is reached only by its incoming half-edge.
  const uint32_t incoming = EdgeTopology::prev(last);
  if (topo_.edgeOnBoundary(incoming)) pushEdge(incoming, out);
}

uint32_t Simplifier::currentHalfEdge(const Candidate& c) const {
  const uint32_t h = c.h;
  const uint32_t u = topo_.vertexOf(h);
  if (u != kNone) {
    const uint32_t w = topo_.target(h);
    if ((u == c.removed && w == c.kept) || (u == c.kept && w == c.removed)) return h;
  }
  const uint32_t g = topo_.findHalfEdge(c.removed, c.kept);
  return g != kNone ? g : topo_.findHalfEdge(c.kept, c.removed);
}

void Simplifier::rebuildHeap() {
  heap_.clear();
  for (uint32_t h = 0; h < 3 * topo_.numTriangles(); ++h) {
    if (topo_.vertexOf(h) == kNone) continue;
    const uint32_t o = topo_.opposite(h);
    if (o != kNone && o < h) continue;
    pushEdge(h, &heap_);
  }
  std::make_heap(heap_.begin(), heap_.end(), LaterCandidate());
}

void Simplifier::lockNeighbourhood(uint32_t v, uint32_t batch) {
  locked_in_batch_[v] = batch;
  topo_.forEachNeighbour(v, [&](uint32_t w) { locked_in_batch_[w] = batch; });
}

void Simplifier::run(SimplifyResult* result) {
  result->batches.clear();
  const uint64_t start_triangles = topo_.liveTriangles();
  const uint64_t target = options_.target_triangles;
  const double ratio = std::max(1.0, options_.batch_cost_ratio);
  const double max_fraction = std::clamp(options_.batch_max_fraction, 0.0, 1.0);
  const auto start_time = std::chrono::steady_clock::now();
  const bool paper = options_.cost == CollapseCost::kPaper;

  auto report = [&](bool final) {
    if (!options_.progress) return;
    if (final) {
      options_.progress(1.0);
      return;
    }
    const double goal = static_cast<double>(start_triangles) - static_cast<double>(target);
    const double done = static_cast<double>(start_triangles - topo_.liveTriangles());
    options_.progress(goal > 0.0 ? std::min(1.0, done / goal) : 1.0);
  };

  rebuildHeap();
  bool rebuilt_without_progress = false;
  bool stop = topo_.liveTriangles() <= target;
  uint64_t collapses = 0;
  uint32_t batch_number = 0;
  std::vector<HalfEdgeCollapse> batch;
  while (!stop) {
    ++batch_number;
    batch.clear();
    deferred_.clear();
    const uint64_t cap = std::max<uint64_t>(
        1, static_cast<uint64_t>(max_fraction * static_cast<double>(live_vertices_)));
    double limit = std::numeric_limits<double>::infinity();
    while (!heap_.empty() && !stop) {
      std::pop_heap(heap_.begin(), heap_.end(), LaterCandidate());
      const Candidate c = heap_.back();
      heap_.pop_back();
      if (!fresh(c)) continue;
      if (locked_in_batch_[c.removed] == batch_number || locked_in_batch_[c.kept] == batch_number) {
        deferred_.push_back(c);
        continue;
      }
      if (c.cost > limit) {
        pushHeap(c);
        break;
      }
      const uint32_t h = currentHalfEdge(c);
      Vec3 position;
      double cost;
      const bool kept_moves = evaluate(c.removed, c.kept, h, &cost, &position);
      if (!simplify::linkConditionHolds(topo_, c.removed, c.kept, h, &marks_) ||
          !simplify::geometryAllows(topo_, positions_, c.removed, c.kept, position, kept_moves,
                                    limits_)) {
        if (!c.second_choice && simplify::boundaryRuleAllows(topo_, c.kept, h)) {
          Candidate other{0.0, h, c.kept, c.removed, c.version, true};
          evaluate(other.removed, other.kept, h, &other.cost, &position);
          pushHeap(other);
        }
        continue;
      }
      if (batch.empty()) {
        // The batch takes collapses up to `ratio` times its first one's cost
        // (with costs near zero counted as cost_floor_, and negative costs of
        // the paper's energies measured by their magnitude).
        limit = c.cost + (ratio - 1.0) * std::max(std::fabs(c.cost), cost_floor_);
      }

      // The neighbourhoods as they are before the collapse: afterwards the
      // kept vertex's neighbours are their union, so locking them afterwards
      // would be the same set.
      lockNeighbourhood(c.removed, batch_number);
      lockNeighbourhood(c.kept, batch_number);
      topo_.collapse(c.removed, c.kept, h);
      positions_[c.kept] = position;
      quadrics_[c.kept].add(quadrics_[c.removed]);
      ++version_[c.removed];
      ++version_[c.kept];
      --live_vertices_;
      batch.push_back({c.removed, c.kept, position});
      ++collapses;

      if (paper) {
        // Normals change on the kept vertex and all its neighbours, and with
        // them the costs of every edge around those.
        scratch_.clear();
        scratch_.push_back(c.kept);
        topo_.forEachNeighbour(c.kept, [&](uint32_t w) { scratch_.push_back(w); });
        for (uint32_t v : scratch_) {
          normals_[v] = simplify::vertexNormal(topo_, positions_, v);
          ++version_[v];
        }
        for (uint32_t v : scratch_) pushEdgesAround(v, &deferred_);
      } else {
        pushEdgesAround(c.kept, &deferred_);
      }

      if (topo_.liveTriangles() <= target) stop = true;
      if (batch.size() >= cap) break;
      if (collapses % kCheckInterval == 0) {
        report(false);
        if (options_.time_budget_seconds > 0.0) {
          const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start_time;
          if (spent.count() >= options_.time_budget_seconds) stop = true;
        }
      }
    }
    for (const Candidate& c : deferred_) {
      if (fresh(c)) pushHeap(c);
    }
    if (!batch.empty()) {
      result->batches.push_back(batch);
      rebuilt_without_progress = false;
      continue;
    }
    // Nothing was collapsible: entries dropped as inconsistent may have
    // become consistent since, so look at every edge once more before giving up.
    if (stop || rebuilt_without_progress) break;
    rebuildHeap();
    rebuilt_without_progress = true;
  }
  result->final_triangles = topo_.liveTriangles();
  result->final_vertices = live_vertices_;
  report(true);
}

}  // namespace

bool simplifyMesh(const TriangleMesh& mesh, const SimplifyOptions& options,
                  SimplifyResult* result, std::string* error) {
  Simplifier simplifier(options);
  if (!simplifier.init(mesh, error)) return false;
  simplifier.run(result);
  return true;
}

}  // namespace mrsv
