// The simplifier's driver: candidate collapses in cost order, grouped into
// batches of independent collapses (spec 6.9).
//
// Every edge keeps one candidate, the cheaper of its two directions that the
// boundary rules allow and that has not failed the consistency checks, with
// its cost. Costs are memoryless (Lindstrom and Turk): a vertex's quadric
// describes its fan as it is now, not the part of the input it stands for.
// A collapse therefore changes the quadrics of the kept vertex and of all its
// neighbours, and the costs of every edge around those. All of these
// vertices are locked for the rest of the batch, so none of those edges can
// be taken before it ends. The quadrics are recomputed right after the
// collapse, while its neighbourhood is still in the cache, and so are the
// candidates around the kept vertex, whose shape changed (and again, should a
// later collapse of the batch change the other end of one of them). The
// other candidates around the neighbours, of which only one end's quadric
// changed, are marked outdated by the vertices' change counters and
// recomputed only when a batch is about to take them: few ever are, and
// recomputing them all would triple the work. (With the paper's energies,
// which depend on more than the two ends, all of this waits for the end of
// the batch, and every candidate around a changed vertex is recomputed.) A
// direction that fails the checks is not tried again until a collapse
// changes the neighbourhood of one of the edge's endpoints, which is when
// its outcome can change.
//
// A batch is one pass in cost order: every candidate up to batch_cost_ratio
// times the cheapest one, or up to the batch_min_fraction quantile of the
// candidates' costs if that is higher (their coarse_ counterparts once few
// vertices are left), is sorted, then taken in order unless
// an endpoint is locked. Accepting a collapse locks both endpoints and all
// their neighbours. Unlocked vertices keep their neighbourhood through the
// batch, so the accepted collapses satisfy the independence rule of
// SimplifyResult by construction, and candidates that touch a locked vertex
// simply wait for the next batch. With quadric costs, a collapse about to be
// taken is charged the deviation guard too (deviation_guard.h), and waits for
// a later batch if that makes it dearer than the limit. Sorting per batch,
// rather than keeping a global heap, is what makes it fast: a heap pays
// O(log n) cache misses for every stale, locked or recomputed entry, and
// batches have plenty of those.
#include "simplify/simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "simplify/collapse_checks.h"
#include "simplify/collapse_costs.h"
#include "simplify/deviation_guard.h"
#include "simplify/edge_topology.h"

namespace mrsv {

namespace {

using simplify::EdgeTopology;
using simplify::kNone;
using simplify::Quadric;
using simplify::Vec3;

// Perpendicular boundary planes weigh this much per squared edge length
// (triangle planes weigh their area, about 0.43 per squared edge length), so
// a boundary that bends costs about twice what an interior that bends does.
// (100, as before D35, kept the boundary so firmly that at 1 % of the bunny's
// faces a fifth of its vertices were on the holes' rims, Lindstrom-Turk's
// result a tenth, and the RMS error was 12 % larger.)
constexpr double kBoundaryWeight = 1.0;
// How often (in collapses) the clock and the progress callback are consulted.
constexpr uint32_t kCheckInterval = 1024;
// The batch rule's quantile is estimated from every kSampleStride-th edge.
constexpr size_t kSampleStride = 8;
// Direction of an edge's candidate: which end of its canonical half-edge goes.
constexpr uint8_t kOriginGoes = 0;
constexpr uint8_t kTargetGoes = 1;
constexpr uint8_t kNoDirection = 2;

struct Entry {
  double cost;
  uint32_t h;  // the edge's canonical half-edge
};

// What the simplifier keeps per canonical half-edge: its candidate (cost and
// direction), which directions failed the checks (bit d for direction d),
// after how many collapses the candidate (or the failure) was computed, and
// whether the edge is in the list of live edges, and whether the half-edge
// is the canonical one of a live edge (so the scan of the list need not look
// at the topology). One struct rather than one array per field: refreshing
// or scanning an edge then costs one cache miss, not six, and on large
// meshes those misses were most of the time.
struct EdgeState {
  double cost = 0.0;
  uint32_t evaluated_at = 0;
  uint8_t direction = kNoDirection;
  uint8_t failed = 0;
  uint8_t listed = 0;
  uint8_t live = 0;
};

// Per vertex: the batch that last locked it, the number of collapses made
// when its neighbourhood last changed, the last batch in which it was a kept
// vertex, and (the paper's energies) the last batch whose refresh recomputed
// its normal; read together when a batch locks or refreshes.
struct VertexState {
  uint32_t locked_in_batch = 0;
  uint32_t changed_at = 0;
  uint32_t kept_in_batch = 0;
  uint32_t refreshed_in = 0;
};

// A vertex's quadric and volume term, which every cost reads together.
struct VertexTerms {
  Quadric quadric;
  simplify::VolumeTerm volume;
};

// A total order, so the result never depends on the sort's internals. (A
// lambda, not a function: std::sort then inlines it.)
constexpr auto cheaper = [](const Entry& a, const Entry& b) {
  return a.cost < b.cost || (a.cost == b.cost && a.h < b.h);
};

class Simplifier {
 public:
  explicit Simplifier(const SimplifyOptions& options) : options_(options) {}

  bool init(const TriangleMesh& mesh, std::string* error);
  void run(SimplifyResult* result);

 private:
  // The canonical half-edge of h's edge: the lower index of the pair.
  uint32_t canonical(uint32_t h) const {
    const uint32_t o = topo_.opposite(h);
    return o != kNone && o < h ? o : h;
  }
  // Whether both directions of edge h give the same collapse: the same
  // position, cost and resulting mesh (only the vertex that keeps its number
  // differs). True for the quadric cost with free placement when neither end
  // is on the boundary; such an edge is evaluated once.
  bool symmetric(uint32_t h) const {
    return quadric_free_ && !topo_.onBoundary(topo_.vertexOf(h)) && !topo_.onBoundary(topo_.target(h));
  }
  // Where the kept vertex goes; true if that is not where it is.
  bool place(uint32_t removed, uint32_t kept, uint32_t h, Vec3* position) const;
  double cost(uint32_t removed, uint32_t kept, const Vec3& position, bool moves) const;
  // Picks the cheaper direction of canonical half-edge h among those allowed
  // and not yet failed.
  void chooseDirection(uint32_t h);
  void refreshEdge(uint32_t h) {
    edge_[h].failed = 0;
    edge_[h].evaluated_at = collapses_;
    chooseDirection(h);
  }
  void refreshEdgesAround(uint32_t v);
  void updatePlane(uint32_t t) {
    planes_[t] = simplify::trianglePlane(positions_[topo_.vertexOf(3 * t)], positions_[topo_.vertexOf(3 * t + 1)],
                                         positions_[topo_.vertexOf(3 * t + 2)]);
  }
  // Whether a collapse changed the neighbourhood of an end of edge h since
  // its candidate was computed.
  bool outdated(uint32_t h) const {
    return std::max(vertex_[topo_.vertexOf(h)].changed_at, vertex_[topo_.target(h)].changed_at) > edge_[h].evaluated_at;
  }
  // Calls f(c) for the canonical half-edge c of every edge of live vertex v.
  template <typename F>
  void forEachEdgeAround(uint32_t v, F&& f) const;
  // Quadric costs, right after a collapse: new quadrics for the kept vertex
  // and its neighbours, then new candidates for the edges around the kept
  // vertex and for those that this collapse outdated around the kept
  // vertices of earlier collapses of the batch.
  void refreshAfterCollapse(uint32_t kept);
  // After a batch, the paper's energies only: new quadrics and normals for
  // the vertices the batch's collapses changed, then new candidates for the
  // edges around all of them.
  void refreshAfterBatch();
  // Tries the current candidate of edge h; on failure marks the direction and
  // returns false.
  bool consistent(uint32_t h, uint32_t removed, uint32_t kept, Vec3* position);
  void lockNeighbourhood(uint32_t v);
  // Collapses edge h, `removed` into `kept`, and keeps EdgeState::live
  // current.
  void collapse(uint32_t h, uint32_t removed, uint32_t kept);

  const SimplifyOptions& options_;
  // Whether kept vertices move yet (free placement only, once at most
  // free_placement_below of the input's vertices are left).
  bool moving_ = false;
  EdgeTopology topo_;
  std::vector<Vec3> positions_;
  // Per vertex: its memoryless quadric and its fan's volume term, side by
  // side because every cost reads both of both endpoints.
  std::vector<VertexTerms> terms_;
  // Per triangle: its plane, kept current as vertices move.
  std::vector<simplify::TrianglePlane> planes_;
  std::vector<Vec3> normals_;  // CollapseCost::kPaper only
  simplify::DeviationGuard guard_;  // used when guarded_
  bool guarded_ = false;
  // Per canonical half-edge (EdgeState).
  std::vector<EdgeState> edge_;
  // Per vertex (VertexState).
  std::vector<VertexState> vertex_;
  // The paper's energies: the vertices whose fan a collapse of this batch
  // changed, with repeats, and the kept vertices among them. Quadric costs:
  // the vertices that this collapse locked when an earlier collapse of the
  // batch had locked them already (refreshAfterCollapse()).
  std::vector<uint32_t> changed_;
  std::vector<uint32_t> kept_in_batch_;
  std::vector<uint32_t> relocked_;
  // Per half-edge, the last batch that refreshed it (the paper's energies
  // only: see refreshEdgesAround()).
  std::vector<uint32_t> edge_refreshed_in_;
  // The canonical half-edges of the live edges, with EdgeState::listed
  // marking them. An edge whose canonical half-edge changes is one around a
  // kept vertex, and gets its new one appended; the list drops stale entries
  // every batch.
  std::vector<uint32_t> edges_;
  std::vector<Entry> candidates_;
  std::vector<Entry> pool_;
  std::vector<double> sample_;
  std::vector<uint32_t> scratch_;
  simplify::VertexMarks marks_;
  simplify::GeometryLimits limits_;
  simplify::PaperWeights paper_;
  double cost_floor_ = 0.0;
  bool quadric_free_ = false;
  uint64_t live_vertices_ = 0;
  uint32_t batch_number_ = 0;
  uint32_t collapses_ = 0;
};

bool Simplifier::init(const TriangleMesh& mesh, std::string* error) {
  if (!topo_.build(mesh, error)) return false;
  // As run() would find at once.
  moving_ = options_.placement == Placement::kFree && options_.free_placement_below >= 1.0;
  positions_ = mesh.positions;
  for (const Vec3& p : positions_) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      *error = "a vertex position is not finite";
      return false;
    }
  }
  const uint32_t nv = topo_.numVertices();
  const size_t nh = 3 * static_cast<size_t>(topo_.numTriangles());
  vertex_.assign(nv, VertexState{});
  marks_.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) live_vertices_ += topo_.alive(v);

  double length_sum = 0.0;
  uint64_t edges = 0;
  for (uint32_t h = 0; h < nh; ++h) {
    if (canonical(h) != h) continue;
    const Vec3& a = positions_[topo_.vertexOf(h)];
    const Vec3& b = positions_[topo_.target(h)];
    length_sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
    ++edges;
  }
  const double unit = edges > 0 && length_sum > 0.0 ? length_sum / static_cast<double>(edges) : 1.0;
  quadric_free_ = options_.cost == CollapseCost::kQuadric && options_.placement == Placement::kFree;
  // The guard's cost is in the quadric's units (area times squared distance);
  // the paper's energies have their own.
  guarded_ = options_.cost == CollapseCost::kQuadric && options_.deviation_weight > 0.0;
  if (guarded_) guard_.init(mesh, options_.deviation_weight);
  paper_.normal = options_.weight_normal;
  paper_.edge_length = options_.weight_edge_length;
  paper_.equilateral = options_.weight_equilateral;
  paper_.inverse_length_unit = 1.0 / unit;

  planes_.assign(topo_.numTriangles(), simplify::TrianglePlane{});
  for (uint32_t t = 0; t < topo_.numTriangles(); ++t) {
    if (topo_.triangleAlive(t)) updatePlane(t);
  }
  terms_.assign(nv, VertexTerms{});
  for (uint32_t v = 0; v < nv; ++v) {
    if (topo_.alive(v)) {
      simplify::vertexQuadric(topo_, positions_, planes_, v, kBoundaryWeight, &terms_[v].quadric, &terms_[v].volume);
    }
  }
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

  edge_.assign(nh, EdgeState{});
  if (options_.cost == CollapseCost::kPaper) edge_refreshed_in_.assign(nh, 0);

  for (uint32_t h = 0; h < nh; ++h) {
    if (canonical(h) == h) {
      edges_.push_back(h);
      edge_[h].listed = 1;
      edge_[h].live = 1;
      chooseDirection(h);
    }
  }
  return true;
}

bool Simplifier::place(uint32_t removed, uint32_t kept, uint32_t h, Vec3* position) const {
  const Vec3& pk = positions_[kept];
  if (!moving_) {
    *position = pk;
    return false;
  }
  Quadric q = terms_[removed].quadric;
  q.add(terms_[kept].quadric);
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
    // The optimum is used only near the edge (within one edge length of its
    // midpoint); a far optimum comes from nearly parallel planes.
    const double len2 = (pr[0] - pk[0]) * (pr[0] - pk[0]) + (pr[1] - pk[1]) * (pr[1] - pk[1]) +
                        (pr[2] - pk[2]) * (pr[2] - pk[2]);
    // Lindstrom and Turk's volume preservation: the new fan encloses as much
    // as the two old ones, so the simplified surface does not drift inwards
    // on convex parts (or outwards on concave ones) as plain quadric optima
    // do. The fans share the edge's triangles, which count once.
    simplify::VolumeTerm volume = terms_[removed].volume;
    volume.add(terms_[kept].volume);
    auto subtractTriangle = [&](uint32_t t) { volume.subtract({planes_[t].n, planes_[t].offset}); };
    subtractTriangle(EdgeTopology::triangleOf(h));
    const uint32_t twin = topo_.opposite(h);
    if (twin != kNone) subtractTriangle(EdgeTopology::triangleOf(twin));
    Vec3 x;
    if (q.constrainedMinimizer(volume.g, volume.offset, &x) && (x[0] - mid[0]) * (x[0] - mid[0]) + (x[1] - mid[1]) * (x[1] - mid[1]) +
                                   (x[2] - mid[2]) * (x[2] - mid[2]) <=
                               len2) {
      *position = x;
    } else {
      *position = q.segmentMinimizer(pk, pr);
    }
  }
  return *position != pk;
}

double Simplifier::cost(uint32_t removed, uint32_t kept, const Vec3& position, bool moves) const {
  if (options_.cost == CollapseCost::kQuadric) {
    return terms_[removed].quadric.evaluate(position) + terms_[kept].quadric.evaluate(position);
  }
  return simplify::paperEnergy(topo_, positions_, normals_, removed, kept, position, moves, paper_);
}

void Simplifier::chooseDirection(uint32_t h) {
  const uint32_t a = topo_.vertexOf(h);
  const uint32_t b = topo_.target(h);
  edge_[h].direction = kNoDirection;
  if (symmetric(h)) {
    if (edge_[h].failed != 0) return;  // both directions fail alike
    Vec3 position;
    place(a, b, h, &position);
    edge_[h].cost = cost(a, b, position, true);
    // Keeping the end nearer the new position makes the coded move smaller.
    const Vec3& pa = positions_[a];
    const Vec3& pb = positions_[b];
    const double to_a = (position[0] - pa[0]) * (position[0] - pa[0]) +
                        (position[1] - pa[1]) * (position[1] - pa[1]) +
                        (position[2] - pa[2]) * (position[2] - pa[2]);
    const double to_b = (position[0] - pb[0]) * (position[0] - pb[0]) +
                        (position[1] - pb[1]) * (position[1] - pb[1]) +
                        (position[2] - pb[2]) * (position[2] - pb[2]);
    edge_[h].direction = to_b <= to_a ? kOriginGoes : kTargetGoes;
    return;
  }
  for (uint8_t d : {kOriginGoes, kTargetGoes}) {
    if (edge_[h].failed & (1u << d)) continue;
    const uint32_t removed = d == kOriginGoes ? a : b;
    const uint32_t kept = d == kOriginGoes ? b : a;
    if (!simplify::boundaryRuleAllows(topo_, removed, h)) continue;
    Vec3 position;
    const bool moves = place(removed, kept, h, &position);
    const double c = cost(removed, kept, position, moves);
    if (edge_[h].direction == kNoDirection || c < edge_[h].cost) {
      edge_[h].direction = d;
      edge_[h].cost = c;
    }
  }
}

template <typename F>
void Simplifier::forEachEdgeAround(uint32_t v, F&& f) const {
  uint32_t last = kNone;
  topo_.forEachOutgoing(v, [&](uint32_t h) {
    f(canonical(h));
    last = h;
  });
  // The last edge of a boundary fan is reached only by its incoming half-edge.
  const uint32_t incoming = EdgeTopology::prev(last);
  if (topo_.edgeOnBoundary(incoming)) f(incoming);
}

void Simplifier::refreshEdgesAround(uint32_t v) {
  // With the paper's energies the edges around every changed vertex are
  // refreshed, and neighbours share edges, so each is refreshed once per
  // batch. With quadrics only the kept vertices' edges are, and kept vertices
  // of one batch are never adjacent (they are locked with their
  // neighbourhoods), so no edge comes twice and the check is skipped.
  const bool paper = options_.cost == CollapseCost::kPaper;
  forEachEdgeAround(v, [&](uint32_t c) {
    if (paper) {
      if (edge_refreshed_in_[c] == batch_number_) return;
      edge_refreshed_in_[c] = batch_number_;
    }
    refreshEdge(c);
    if (!edge_[c].listed) {
      edge_[c].listed = 1;
      edges_.push_back(c);
    }
  });
}

bool Simplifier::consistent(uint32_t h, uint32_t removed, uint32_t kept, Vec3* position) {
  const bool moves = place(removed, kept, h, position);
  if (simplify::linkConditionHolds(topo_, removed, kept, h, &marks_) &&
      simplify::geometryAllows(topo_, positions_, removed, kept, *position, moves, limits_)) {
    return true;
  }
  edge_[h].failed |= static_cast<uint8_t>(symmetric(h) ? 3u : 1u << edge_[h].direction);
  edge_[h].evaluated_at = collapses_;
  chooseDirection(h);
  return false;
}

void Simplifier::collapse(uint32_t h, uint32_t removed, uint32_t kept) {
  const uint32_t twin = topo_.opposite(h);
  topo_.collapse(removed, kept, h);
  // The edge's one or two triangles die with their half-edges. The other
  // edges of those triangles merge pairwise into edges of `kept`, whose
  // half-edges are paired anew; nothing else changes its pairing. So every
  // half-edge that stopped (or started) being the canonical one of a live
  // edge is either dead or on an edge around `kept`.
  for (uint32_t g : {h, twin}) {
    if (g == kNone) continue;
    const uint32_t first = 3 * EdgeTopology::triangleOf(g);
    for (uint32_t i = 0; i < 3; ++i) edge_[first + i].live = 0;
  }
  forEachEdgeAround(kept, [&](uint32_t c) {
    edge_[c].live = 1;
    const uint32_t o = topo_.opposite(c);
    if (o != kNone) edge_[o].live = 0;
  });
}

void Simplifier::lockNeighbourhood(uint32_t v) {
  auto lock = [&](uint32_t w) {
    VertexState& state = vertex_[w];
    // Locked by an earlier collapse of this batch (not by the other end of
    // this one): that collapse's candidates may now be outdated.
    if (state.locked_in_batch == batch_number_ && state.changed_at != collapses_) relocked_.push_back(w);
    state.locked_in_batch = batch_number_;
    state.changed_at = collapses_;
  };
  lock(v);
  topo_.forEachNeighbour(v, lock);
}

void Simplifier::refreshAfterCollapse(uint32_t kept) {
  // Done now, while the neighbourhood the collapse just walked is in the
  // cache; after the batch, thousands of collapses later, every one of these
  // reads was a cache miss. The results are the same as if it were all done
  // after the batch: the vertices changed here are locked, so no later
  // collapse of the batch reads their quadrics or takes an edge around the
  // kept vertex.
  auto update = [&](uint32_t v) {
    simplify::vertexQuadric(topo_, positions_, planes_, v, kBoundaryWeight, &terms_[v].quadric, &terms_[v].volume);
  };
  update(kept);
  topo_.forEachNeighbour(kept, update);
  // The edges around a kept vertex changed shape, and their costs change
  // most: they are recomputed now. Around its neighbours only one end's
  // quadric changed; those candidates are outdated (outdated()) and are
  // recomputed only when a batch is about to take them, which few are.
  refreshEdgesAround(kept);
  // A neighbour that an earlier collapse of the batch had locked already may
  // be a neighbour of that collapse's kept vertex too: the candidate of their
  // edge, computed after that collapse, is now outdated and is recomputed
  // with the neighbour's new quadric. (About one per collapse: a batch packs
  // its collapses so that their neighbourhoods touch.)
  for (uint32_t w : relocked_) {
    forEachEdgeAround(w, [&](uint32_t c) {
      const uint32_t other = topo_.vertexOf(c) == w ? topo_.target(c) : topo_.vertexOf(c);
      if (other != kept && vertex_[other].kept_in_batch == batch_number_) refreshEdge(c);
    });
  }
  relocked_.clear();
}

void Simplifier::refreshAfterBatch() {
  if (options_.cost == CollapseCost::kQuadric) return;  // refreshAfterCollapse() did it all
  relocked_.clear();  // not needed: every candidate around a changed vertex is recomputed
  scratch_.clear();
  for (uint32_t v : changed_) {
    if (!topo_.alive(v) || vertex_[v].refreshed_in == batch_number_) continue;
    vertex_[v].refreshed_in = batch_number_;
    scratch_.push_back(v);
    simplify::vertexQuadric(topo_, positions_, planes_, v, kBoundaryWeight, &terms_[v].quadric, &terms_[v].volume);
    normals_[v] = simplify::vertexNormal(topo_, positions_, v);
  }
  changed_.clear();
  // The paper's energies, which the sort order depends on more, are
  // recomputed around every changed vertex.
  for (uint32_t v : kept_in_batch_) {
    if (topo_.alive(v)) refreshEdgesAround(v);
  }
  kept_in_batch_.clear();
  for (uint32_t v : scratch_) refreshEdgesAround(v);
}

void Simplifier::run(SimplifyResult* result) {
  result->batches.clear();
  const uint64_t start_triangles = topo_.liveTriangles();
  const uint64_t target = options_.target_triangles;
  const double max_fraction = std::clamp(options_.batch_max_fraction, 0.0, 1.0);
  const double coarse_below = options_.coarse_vertex_fraction * static_cast<double>(live_vertices_);
  const double fine_above = options_.fine_vertex_fraction * static_cast<double>(live_vertices_);
  const auto start_time = std::chrono::steady_clock::now();
  auto report = [&](bool final) {
    if (!options_.progress) return;
    const double goal = static_cast<double>(start_triangles) - static_cast<double>(target);
    const double done = static_cast<double>(start_triangles - topo_.liveTriangles());
    options_.progress(final || goal <= 0.0 ? 1.0 : std::min(1.0, done / goal));
  };

  bool stop = topo_.liveTriangles() <= target;
  std::vector<HalfEdgeCollapse> batch;
  const double free_below = options_.free_placement_below * static_cast<double>(live_vertices_);
  while (!stop) {
    if (options_.placement == Placement::kFree && !moving_ && static_cast<double>(live_vertices_) <= free_below) {
      // Free placement starts: every candidate is priced again with it.
      moving_ = true;
      for (uint32_t h : edges_)
        if (edge_[h].live) refreshEdge(h);
    }
    ++batch_number_;
    batch.clear();
    // The batch rule of this stretch: wide near full resolution, narrow at
    // the coarse end (SimplifyOptions).
    const double live = static_cast<double>(live_vertices_);
    double ratio = options_.batch_cost_ratio, min_fraction = options_.batch_min_fraction;
    if (live < coarse_below) {
      ratio = options_.coarse_batch_cost_ratio;
      min_fraction = options_.coarse_batch_min_fraction;
    } else if (live > fine_above) {
      ratio = options_.fine_batch_cost_ratio;
      min_fraction = options_.fine_batch_min_fraction;
    }
    ratio = std::max(1.0, ratio);
    min_fraction = std::clamp(min_fraction, 0.0, 1.0);
    const uint64_t cap = std::max<uint64_t>(
        1, static_cast<uint64_t>(max_fraction * static_cast<double>(live_vertices_)));
    // Usually one round; another only when every candidate of a round failed
    // the checks (those are then set aside, so the next round goes further).
    while (batch.empty()) {
      // Pass 1: drop dead edges from the list, retry failed directions whose
      // neighbourhood changed, find the cheapest candidate.
      double cheapest = std::numeric_limits<double>::infinity();
      size_t kept_edges = 0;
      sample_.clear();
      candidates_.clear();
      for (size_t i = 0; i < edges_.size(); ++i) {
        const uint32_t h = edges_[i];
        EdgeState& edge = edge_[h];
        if (!edge.live) {
          edge.listed = 0;
          continue;
        }
        edges_[kept_edges++] = h;
        if (edge.failed != 0 && outdated(h)) {
          refreshEdge(h);  // the neighbourhood changed since the failure
        }
        if (edge.direction != kNoDirection) {
          cheapest = std::min(cheapest, edge.cost);
          if (kept_edges % kSampleStride == 0) sample_.push_back(edge.cost);
          candidates_.push_back({edge.cost, h});
        }
      }
      edges_.resize(kept_edges);
      if (cheapest == std::numeric_limits<double>::infinity()) break;
      // The batch takes collapses up to `ratio` times the cheapest candidate's
      // cost (costs near zero count as cost_floor_; negative costs of the
      // paper's energies are measured by their magnitude).
      double limit = cheapest + (ratio - 1.0) * std::max(std::fabs(cheapest), cost_floor_);
      if (min_fraction > 0.0 && !sample_.empty()) {
        const size_t k = std::min(sample_.size() - 1,
                                  static_cast<size_t>(min_fraction * static_cast<double>(sample_.size())));
        std::nth_element(sample_.begin(), sample_.begin() + k, sample_.end());
        limit = std::max(limit, sample_[k]);
      }
      // Pass 2: the candidates within the limit, in cost order. (Pass 1
      // copied the candidates into one dense array: reading them back from
      // edge_ was a cache miss each once most edges are gone.)
      pool_.clear();
      for (const Entry& e : candidates_) {
        if (e.cost <= limit) pool_.push_back(e);
      }
      std::sort(pool_.begin(), pool_.end(), cheaper);

      for (const Entry& e : pool_) {
        const uint32_t h = e.h;
        const uint32_t a = topo_.vertexOf(h);
        if (a == kNone) continue;  // died in this batch (its ends are locked)
        const uint32_t b = topo_.target(h);
        if (vertex_[a].locked_in_batch == batch_number_ || vertex_[b].locked_in_batch == batch_number_) continue;
        // The guard reads both ends' members after the checks below.
        if (guarded_) guard_.prefetch(a, b);
        if (outdated(h)) {
          refreshEdge(h);
          if (edge_[h].direction == kNoDirection || edge_[h].cost > limit) continue;
        }
        Vec3 position;
        uint32_t removed = 0, kept = 0;
        bool ok = false;
        // The candidate, and if it fails, the other direction if cheap enough.
        for (int attempt = 0; attempt < 2 && !ok; ++attempt) {
          if (edge_[h].direction == kNoDirection || edge_[h].cost > limit) break;
          removed = edge_[h].direction == kOriginGoes ? a : b;
          kept = edge_[h].direction == kOriginGoes ? b : a;
          ok = consistent(h, removed, kept, &position);
        }
        if (!ok) continue;
        if (guarded_) {
          // The guard is charged here, lazily, rather than for every
          // candidate: it costs a walk over the members and the fan. The
          // quadric cost is a lower bound of the charged one, so a batch
          // still takes its collapses in quadric order; the charge decides
          // only whether one waits for a later batch, where it is sorted by
          // its charged cost.
          const double deviation = guard_.cost(topo_, positions_, removed, kept, position);
          if (deviation > edge_[h].cost) {
            edge_[h].cost = deviation;
            if (deviation > limit) continue;  // waits for a later batch
          }
        }

        // Lock the neighbourhoods as they are before the collapse (afterwards
        // the kept vertex's neighbours are their union: the same set).
        ++collapses_;
        lockNeighbourhood(removed);
        lockNeighbourhood(kept);
        collapse(h, removed, kept);
        positions_[kept] = position;
        if (guarded_) guard_.merge(topo_, positions_, removed, kept);
        // Every triangle whose shape changed is now in the kept vertex's fan.
        topo_.forEachOutgoing(kept, [&](uint32_t e) { updatePlane(EdgeTopology::triangleOf(e)); });
        --live_vertices_;
        batch.push_back({removed, kept, position});
        vertex_[kept].kept_in_batch = batch_number_;
        if (options_.cost == CollapseCost::kPaper) {
          kept_in_batch_.push_back(kept);
          changed_.push_back(kept);
          topo_.forEachNeighbour(kept, [&](uint32_t w) { changed_.push_back(w); });
        } else {
          refreshAfterCollapse(kept);
        }

        if (topo_.liveTriangles() <= target) stop = true;
        if (collapses_ % kCheckInterval == 0) {
          report(false);
          if (options_.time_budget_seconds > 0.0) {
            const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start_time;
            if (spent.count() >= options_.time_budget_seconds) stop = true;
          }
        }
        if (stop || batch.size() >= cap) break;
      }
    }
    if (batch.empty()) break;  // no consistent collapse is left
    result->batches.push_back(batch);
    if (!stop) refreshAfterBatch();
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
