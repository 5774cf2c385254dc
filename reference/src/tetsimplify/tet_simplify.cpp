// The tet simplifier's driver: per-vertex candidates in cost order, grouped
// into batches of independent half-edge collapses.
//
// A half-edge collapse removes its vt, so every live vertex keeps one
// candidate: its cheapest target vs that Table 1 allows, and that cost. A
// batch takes the candidates up to batch_cost_ratio times the cheapest one or
// the batch_min_fraction quantile, whichever is higher, sorted, and tries each
// against the consistency tests: exact orientation of every changed tet, the
// optional minimum dihedral angle, the link condition (with the PT decoder's
// split rule), and the boundary self-intersection test. With quadric costs
// the candidate's own target is tried first; if it fails, and always with the
// paper's costs, all targets are listed with fresh costs and tried cheapest
// first up to the batch's limit. A collapse locks every vertex of star(vs) u
// star(vt); a candidate with a locked vs or vt waits for the next batch, which
// is exactly the independence rule (stars are disjoint unless an end of one
// collapse is a neighbour of an end of the other), and keeps every unlocked
// vertex's star as it was at the start of the batch. A vertex whose targets
// all failed is not tried again until a collapse changes its neighbourhood.
//
// Quadrics accumulate (Garland-Heckbert): vs takes vt's quadric, so a cost
// measures the error against the input's field over every input tet the
// vertex stands for, and only the candidates around vs change: they are
// brought up to date right after the collapse, so candidate costs are always
// exact. The paper's costs depend on the tets around both ends: the
// candidates of the new star of vs (all locked) are recomputed at the end of
// the batch, those of their neighbours go stale and are recomputed when
// taken, and a candidate whose cost rose above the batch's limit waits.
#include "tetsimplify/tet_simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "tetsimplify/boundary_index.h"
#include "tetsimplify/exact_predicates.h"
#include "tetsimplify/link_condition.h"
#include "tetsimplify/tet_complex.h"
#include "tetsimplify/tet_costs.h"

namespace mrsv {

namespace {

using tetsimplify::IPoint;
using tetsimplify::kNone;
using tetsimplify::Quadric5;
using tetsimplify::TetComplex;
using tetsimplify::Vec3;

// How often (in collapses) the clock and the progress callback are consulted.
constexpr uint32_t kCheckInterval = 256;
// A tie-break on the squared edge length (in mean edge lengths) added to the
// quadric cost, so flat regions (where the field's error is zero) collapse
// their shortest edges first instead of in index order.
constexpr double kLengthTieBreak = 1e-9;

// Remembered failures per vertex: targets that failed the tests since the
// vertex's neighbourhood last changed, so later batches do not test them
// again (a candidate whose cheapest target fails is otherwise retried in
// every batch).
constexpr int kFailedTargets = 3;

struct VertexState {
  double cost = 0.0;
  uint32_t best = kNone;   // the target giving `cost`
  uint32_t locked_in = 0;  // the batch that last locked it
  uint32_t dirty_in = 0;   // the batch that last changed its star
  uint32_t failed_targets[kFailedTargets] = {kNone, kNone, kNone};
  uint8_t failed = 0;      // no target passed the tests since its star last changed
  uint8_t has_target = 0;  // Table 1 allows at least one target
  bool failedBefore(uint32_t vs) const {
    return failed_targets[0] == vs || failed_targets[1] == vs || failed_targets[2] == vs;
  }
  void rememberFailure(uint32_t vs) {
    for (uint32_t& f : failed_targets) {
      if (f == kNone) {
        f = vs;
        return;
      }
    }
  }
  void forgetFailures() { failed_targets[0] = failed_targets[1] = failed_targets[2] = kNone; }
};

struct Entry {
  double cost;
  uint32_t v;
};

struct Target {
  double cost;
  uint32_t vs;
  bool allowed;  // by Table 1
};

enum class Outcome { kOk, kLink, kInversion, kDegenerate, kMinDihedral, kSelfIntersection };

class TetSimplifier {
 public:
  TetSimplifier(const TetSimplifyOptions& options) : options_(options) {}
  Error init(const QuantizedTetMesh& mesh);
  void run(TetSimplifyResult* out);

 private:
  // Collects v's neighbours into neighbours_, each with whether v u is a
  // boundary edge.
  void gatherNeighbours(uint32_t v);
  // Whether Table 1 allows removing vt into vs, given whether the edge is on
  // the boundary.
  bool tableAllows(uint32_t vs, uint32_t vt, bool edge_on_boundary) const {
    const bool bs = complex_.onBoundary(vs), bt = complex_.onBoundary(vt);
    if (bs && bt) return edge_on_boundary;  // case 5; case 4 never
    if (bs != bt) return options_.allow_boundary_cases_2_3;
    return true;  // case 1
  }
  double cost(uint32_t vs, uint32_t vt);
  // vt's neighbours with their costs and whether Table 1 allows them, into
  // targets_.
  void targetsOf(uint32_t vt);
  void refreshCandidate(uint32_t v);
  // Quadric costs, right after collapsing vt into vs: the candidates around
  // vs. Only vs's quadric and star changed, so a neighbour x whose best
  // target was neither vs nor vt just compares its candidate with x -> vs.
  void updateAfterCollapse(uint32_t vs, uint32_t vt);
  Outcome check(uint32_t vs, uint32_t vt, uint32_t* vanishing);
  // Whether all of v's boundary faces lie in one plane (exactly). Collapsing
  // a boundary edge of such a v then needs no intersection test: the new
  // faces lie in the same plane, each oriented as the face it replaces (the
  // orientation test of the tet below it sees to that), so they triangulate
  // the same polygon, star-shaped from vs, and the boundary as a point set
  // does not change. (Every boundary collapse inside a flat side of a grid.)
  bool planarFan(uint32_t v);
  void lockStar(uint32_t v);

  const TetSimplifyOptions& options_;
  TetComplex complex_;
  tetsimplify::LinkCondition link_;
  tetsimplify::BoundaryIndex index_;
  std::vector<Vec3> positions_;  // normalised
  std::vector<double> scalars_;  // normalised first field (zeros without one)
  std::vector<Quadric5> quadrics_;
  std::vector<double> self_error_;  // per vertex, its quadric at its own place
  std::vector<Vec3> normals_;  // kPaper
  tetsimplify::PaperWeights paper_;
  std::vector<VertexState> state_;
  // The vertices that may be candidates (each with a target and not failed
  // when enlisted; a batch drops the others): a batch reads these, not every
  // vertex (598 batches of the LOX post's 109,744 vertices).
  std::vector<uint32_t> pool_vertices_;
  std::vector<uint8_t> in_pool_;
  std::vector<uint32_t> neighbour_stamp_;
  std::vector<uint32_t> neighbour_slot_;  // where in neighbours_, when stamped
  uint32_t stamp_ = 0;
  std::vector<std::pair<uint32_t, bool>> neighbours_;
  std::vector<std::pair<uint32_t, bool>> around_;
  std::vector<Target> targets_;
  std::vector<uint32_t> dirty_;
  std::vector<std::array<uint32_t, 3>> new_faces_;
  uint32_t batch_ = 0;
  TetSimplifyStats stats_;
};

Error TetSimplifier::init(const QuantizedTetMesh& mesh) {
  Error error;
  std::string message;
  if (!complex_.build(mesh.positions, mesh.tets, &message)) {
    error.status = Status::kInvalidArgument;
    error.field = "tet mesh";
    error.message = message;
    return error;
  }
  const uint32_t nv = complex_.numVertices();
  for (const auto& f : mesh.fields) {
    if (f.size() != nv) {
      error.status = Status::kInvalidArgument;
      error.field = "tet mesh";
      error.message = "a scalar field has " + std::to_string(f.size()) + " values for " + std::to_string(nv) +
                      " vertices";
      return error;
    }
  }
  // Normalisation: lengths in mean edge lengths, the scalar in its range.
  double length_sum = 0.0;
  uint64_t edges = 0;
  std::array<int32_t, 3> lo = {INT32_MAX, INT32_MAX, INT32_MAX};
  for (const auto& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]);
  }
  for (const auto& t : mesh.tets) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const auto &a = mesh.positions[t[i]], &b = mesh.positions[t[j]];
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) d2 += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
        length_sum += std::sqrt(d2);
        ++edges;
      }
    }
  }
  const double unit = edges && length_sum > 0.0 ? length_sum / double(edges) : 1.0;
  positions_.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) positions_[v][k] = (double(mesh.positions[v][k]) - lo[k]) / unit;
  }
  scalars_.assign(nv, 0.0);
  if (!mesh.fields.empty() && nv > 0) {
    const auto& f = mesh.fields[0];
    const auto [mn, mx] = std::minmax_element(f.begin(), f.end());
    const double range = *mx > *mn ? *mx - *mn : 1.0;
    for (uint32_t v = 0; v < nv; ++v) scalars_[v] = (f[v] - *mn) / range;
  }
  double volume_sum = 0.0;
  for (const auto& t : mesh.tets) {
    const Vec3 &a = positions_[t[0]], &b = positions_[t[1]], &c = positions_[t[2]], &d = positions_[t[3]];
    volume_sum += simplify::dot(simplify::sub(b, a), simplify::cross(simplify::sub(c, a), simplify::sub(d, a))) / 6.0;
  }
  paper_.gradient = options_.weight_gradient;
  paper_.volume = options_.weight_volume;
  paper_.equilateral = options_.weight_equilateral;
  paper_.edge_length = options_.weight_edge_length;
  paper_.normal = options_.weight_normal;
  paper_.inverse_volume_unit = volume_sum > 0.0 ? double(mesh.tets.size()) / volume_sum : 1.0;
  if (options_.cost == TetCost::kQuadric) {
    tetsimplify::initialQuadrics(complex_, positions_, scalars_, options_.quadric_boundary_weight, &quadrics_);
    self_error_.resize(nv);
    for (uint32_t v = 0; v < nv; ++v) self_error_[v] = quadrics_[v].evaluate(positions_[v], scalars_[v]);
  } else {
    normals_.resize(nv);
    for (uint32_t v = 0; v < nv; ++v) normals_[v] = tetsimplify::boundaryNormal(complex_, positions_, v);
  }
  link_.init(nv);
  if (options_.boundary_intersection_test) index_.build(complex_);
  state_.assign(nv, VertexState{});
  in_pool_.assign(nv, 0);
  neighbour_stamp_.assign(nv, 0);
  neighbour_slot_.assign(nv, 0);
  for (uint32_t v = 0; v < nv; ++v) {
    if (complex_.vertexAlive(v)) refreshCandidate(v);
  }
  return error;
}

void TetSimplifier::gatherNeighbours(uint32_t v) {
  if (++stamp_ == 0) {
    std::fill(neighbour_stamp_.begin(), neighbour_stamp_.end(), 0);
    stamp_ = 1;
  }
  neighbours_.clear();
  neighbour_stamp_[v] = stamp_;
  complex_.forEachTet(v, [&](uint32_t t, uint32_t corner) {
    const auto& w = complex_.tet(t);
    const uint8_t mask = complex_.boundaryMask(t);
    for (uint32_t i = 0; i < 4; ++i) {
      if (i == corner) continue;
      const uint32_t u = w[i];
      if (neighbour_stamp_[u] != stamp_) {
        neighbour_stamp_[u] = stamp_;
        neighbour_slot_[u] = static_cast<uint32_t>(neighbours_.size());
        neighbours_.push_back({u, false});
      }
      // v u is a boundary edge when a boundary face of this tet holds both:
      // any face but the ones opposite v and u.
      if ((mask & ~((1u << corner) | (1u << i))) != 0) neighbours_[neighbour_slot_[u]].second = true;
    }
  });
}

double TetSimplifier::cost(uint32_t vs, uint32_t vt) {
  if (options_.cost == TetCost::kQuadric) {
    // (Q_vs + Q_vt)(vs), with Q_vs(vs) kept per vertex.
    const Vec3 d = simplify::sub(positions_[vs], positions_[vt]);
    return self_error_[vs] + quadrics_[vt].evaluate(positions_[vs], scalars_[vs]) +
           kLengthTieBreak * simplify::dot(d, d);
  }
  return tetsimplify::paperCost(complex_, positions_, scalars_, normals_, vs, vt, paper_);
}

void TetSimplifier::targetsOf(uint32_t vt) {
  gatherNeighbours(vt);
  targets_.clear();
  for (const auto& [vs, boundary_edge] : neighbours_) {
    targets_.push_back({cost(vs, vt), vs, tableAllows(vs, vt, boundary_edge)});
  }
}

void TetSimplifier::refreshCandidate(uint32_t v) {
  targetsOf(v);
  VertexState& s = state_[v];
  s.failed = 0;
  s.forgetFailures();
  s.has_target = 0;
  s.cost = 0.0;
  s.best = kNone;
  for (const Target& t : targets_) {
    if (!t.allowed) continue;
    if (!s.has_target || t.cost < s.cost) {
      s.cost = t.cost;
      s.best = t.vs;
    }
    s.has_target = 1;
  }
  if (s.has_target && !in_pool_[v]) {
    in_pool_[v] = 1;
    pool_vertices_.push_back(v);
  }
}

void TetSimplifier::updateAfterCollapse(uint32_t vs, uint32_t vt) {
  gatherNeighbours(vs);
  around_.assign(neighbours_.begin(), neighbours_.end());
  for (const auto& [x, boundary_edge] : around_) {
    VertexState& s = state_[x];
    if (s.failed || s.best == vs || s.best == vt || !s.has_target) {
      refreshCandidate(x);
      continue;
    }
    // x's other targets kept their costs; its star, or the star of vs, may
    // have changed, so earlier failures may pass now.
    s.forgetFailures();
    if (!tableAllows(vs, x, boundary_edge)) continue;
    const double c = cost(vs, x);
    if (c < s.cost) {
      s.cost = c;
      s.best = vs;
    }
  }
  refreshCandidate(vs);
}

Outcome TetSimplifier::check(uint32_t vs, uint32_t vt, uint32_t* vanishing) {
  // Orientation (exact) and shape of every tet that keeps vt first: one walk
  // over vt's star, and the test most collapses fail; then the link
  // condition (three walks), then the boundary (a grid query per face).
  Outcome outcome = Outcome::kOk;
  uint32_t ring = 0;
  const IPoint& ps = complex_.position(vs);
  const bool dihedral = options_.min_dihedral_degrees > 0.0;
  const bool boundary_moves = options_.boundary_intersection_test && complex_.onBoundary(vt);
  new_faces_.clear();
  complex_.forEachTet(vt, [&](uint32_t t, uint32_t corner) {
    if (outcome != Outcome::kOk) return;
    const auto& w = complex_.tet(t);
    if (w[0] == vs || w[1] == vs || w[2] == vs || w[3] == vs) {
      ++ring;
      return;
    }
    IPoint p[4] = {complex_.position(w[0]), complex_.position(w[1]), complex_.position(w[2]),
                   complex_.position(w[3])};
    p[corner] = ps;
    const int s = tetsimplify::sign(tetsimplify::orient3d(p[0], p[1], p[2], p[3]));
    if (s <= 0) {
      outcome = s < 0 ? Outcome::kInversion : Outcome::kDegenerate;
      return;
    }
    if (dihedral && minDihedralDegrees(p[0], p[1], p[2], p[3]) < options_.min_dihedral_degrees) {
      outcome = Outcome::kMinDihedral;
      return;
    }
    const uint8_t mask = complex_.boundaryMask(t);
    if (boundary_moves && mask != 0) {
      constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
      for (uint32_t f = 0; f < 4; ++f) {
        if (f == corner || !(mask >> f & 1)) continue;
        std::array<uint32_t, 3> tri = {w[kFace[f][0]], w[kFace[f][1]], w[kFace[f][2]]};
        for (uint32_t& x : tri) x = x == vt ? vs : x;
        new_faces_.push_back(tri);
      }
    }
  });
  *vanishing = ring;
  if (outcome != Outcome::kOk) return outcome;
  if (!link_.holds(complex_, vs, vt, !options_.allow_boundary_cases_2_3)) return Outcome::kLink;
  if (boundary_moves && !planarFan(vt)) {
    for (size_t i = 0; i < new_faces_.size(); ++i) {
      if (index_.clashes(complex_, new_faces_[i], vt)) return Outcome::kSelfIntersection;
      for (size_t j = 0; j < i; ++j) {
        if (tetsimplify::trianglesClash(new_faces_[i], new_faces_[j], complex_.positions().data())) {
          return Outcome::kSelfIntersection;
        }
      }
    }
  }
  return Outcome::kOk;
}

bool TetSimplifier::planarFan(uint32_t v) {
  constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  const IPoint* plane[3] = {nullptr, nullptr, nullptr};
  bool planar = true;
  complex_.forEachTet(v, [&](uint32_t t, uint32_t corner) {
    const uint8_t mask = complex_.boundaryMask(t);
    if (!planar || mask == 0) return;
    const auto& w = complex_.tet(t);
    for (uint32_t f = 0; f < 4; ++f) {
      if (f == corner || !(mask >> f & 1)) continue;
      for (int i = 0; i < 3; ++i) {
        const IPoint& p = complex_.position(w[kFace[f][i]]);
        if (!plane[0]) {
          for (int j = 0; j < 3; ++j) plane[j] = &complex_.position(w[kFace[f][j]]);
          break;
        }
        if (tetsimplify::orient3d(*plane[0], *plane[1], *plane[2], p) != 0) planar = false;
      }
    }
  });
  return planar;
}

void TetSimplifier::lockStar(uint32_t v) {
  state_[v].locked_in = batch_;
  complex_.forEachTet(v, [&](uint32_t t, uint32_t) {
    for (uint32_t u : complex_.tet(t)) state_[u].locked_in = batch_;
  });
}

void TetSimplifier::run(TetSimplifyResult* out) {
  const auto start = std::chrono::steady_clock::now();
  out->batches.clear();
  const uint64_t initial_tets = complex_.liveTets();
  const uint64_t target_tets = std::min<uint64_t>(initial_tets, options_.min_base_tets);
  const uint64_t min_vertices = std::max<uint64_t>(options_.min_base_vertices, 1);
  std::vector<Entry> pool, candidates;
  std::vector<TetCollapse> batch;
  bool stop = false;
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto report = [&] {
    if (!options_.progress || initial_tets <= target_tets) return;
    options_.progress(std::min(1.0, double(initial_tets - complex_.liveTets()) / double(initial_tets - target_tets)));
  };
  while (!stop) {
    ++batch_;
    batch.clear();
    pool.clear();
    // (The pool's order does not matter: its least cost, its k-th least
    // and the candidates sorted by cost and vertex are what is read.)
    size_t enlisted = 0;
    for (uint32_t v : pool_vertices_) {
      const VertexState& s = state_[v];
      if (complex_.vertexAlive(v) && s.has_target && !s.failed) {
        pool_vertices_[enlisted++] = v;
        pool.push_back({s.cost, v});
      } else {
        in_pool_[v] = 0;
      }
    }
    pool_vertices_.resize(enlisted);
    if (pool.empty()) break;
    double cheapest = pool[0].cost;
    for (const Entry& e : pool) cheapest = std::min(cheapest, e.cost);
    double limit = cheapest > 0.0 ? options_.batch_cost_ratio * cheapest : cheapest;
    if (options_.batch_min_fraction > 0.0) {
      const size_t k = std::min(pool.size() - 1, size_t(options_.batch_min_fraction * double(pool.size())));
      candidates = pool;
      std::nth_element(candidates.begin(), candidates.begin() + k, candidates.end(),
                       [](const Entry& a, const Entry& b) { return a.cost < b.cost; });
      limit = std::max(limit, candidates[k].cost);
    }
    candidates.clear();
    for (const Entry& e : pool) {
      if (e.cost <= limit) candidates.push_back(e);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Entry& a, const Entry& b) { return a.cost < b.cost || (a.cost == b.cost && a.v < b.v); });
    dirty_.clear();
    for (const Entry& e : candidates) {
      const uint32_t vt = e.v;
      if (state_[vt].locked_in == batch_ || !complex_.vertexAlive(vt)) continue;
      if (complex_.liveVertices() <= min_vertices) {
        stop = true;
        break;
      }
      // Quadric costs are kept exact, so the remembered best target is the
      // cheapest: try it alone first, and list all targets only if it fails.
      const VertexState& sv = state_[vt];
      bool done = false, waiting = false;
      if (options_.cost == TetCost::kQuadric && sv.best != kNone && sv.cost <= limit &&
          state_[sv.best].locked_in != batch_ && !sv.failedBefore(sv.best)) {
        targets_.assign(1, Target{sv.cost, sv.best, true});
      } else {
        targetsOf(vt);
      }
      for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        if (done || stop || targets_.size() != 1 || options_.cost != TetCost::kQuadric) break;
        targetsOf(vt);  // the best target failed: all of them
      }
      std::sort(targets_.begin(), targets_.end(),
                [](const Target& a, const Target& b) { return a.cost < b.cost || (a.cost == b.cost && a.vs < b.vs); });
      for (const Target& target : targets_) {
        if (target.cost > limit) {
          state_[vt].cost = target.cost;  // waits for a later batch at its true cost
          waiting = true;
          break;
        }
        if (!target.allowed) {
          // Counted only where it stands in the way: cheaper than what the
          // vertex gets, and within the batch's limit.
          ++stats_.evaded_boundary_table;
          continue;
        }
        if (state_[target.vs].locked_in == batch_) {
          waiting = true;
          continue;
        }
        if (state_[vt].failedBefore(target.vs)) continue;
        uint32_t vanishing = 0;
        const Outcome outcome = check(target.vs, vt, &vanishing);
        switch (outcome) {
          case Outcome::kOk: break;
          case Outcome::kLink: ++stats_.evaded_link; break;
          case Outcome::kInversion: ++stats_.evaded_inversion; break;
          case Outcome::kDegenerate: ++stats_.evaded_degenerate; break;
          case Outcome::kMinDihedral: ++stats_.evaded_min_dihedral; break;
          case Outcome::kSelfIntersection: ++stats_.evaded_self_intersection; break;
        }
        if (outcome != Outcome::kOk) {
          state_[vt].rememberFailure(target.vs);
          continue;
        }
        if (complex_.liveTets() - vanishing < target_tets) {
          stop = true;
          break;
        }
        // (updateAfterCollapse() refills targets_: keep vs.)
        const uint32_t vs = target.vs;
        lockStar(vt);
        lockStar(vs);
        const bool boundary = complex_.onBoundary(vt);
        complex_.collapse(vs, vt);
        if (boundary && options_.boundary_intersection_test) index_.addFacesAround(complex_, vs);
        if (options_.cost == TetCost::kQuadric) {
          quadrics_[vs].add(quadrics_[vt]);
          self_error_[vs] = quadrics_[vs].evaluate(positions_[vs], scalars_[vs]);
          updateAfterCollapse(vs, vt);
        } else {
          dirty_.push_back(vs);
        }
        batch.push_back({vs, vt});
        ++stats_.collapses;
        done = true;
        break;
      }
      }
      if (stop) break;
      if (!done && !waiting) state_[vt].failed = 1;
      if (done && stats_.collapses % kCheckInterval == 0) {
        report();
        if (options_.time_budget_seconds > 0.0 && seconds() >= options_.time_budget_seconds) {
          stop = true;
          break;
        }
      }
    }
    // The paper's costs: the collapses changed the stars of their vs and of
    // every vertex around it, all locked in this batch: new candidates and
    // normals for them once, now.
    ++stamp_;
    std::vector<uint32_t>& changed = dirty_;
    const size_t kept = changed.size();
    for (size_t i = 0; i < kept; ++i) {
      const uint32_t vs = changed[i];
      complex_.forEachTet(vs, [&](uint32_t t, uint32_t) {
        for (uint32_t u : complex_.tet(t)) {
          if (state_[u].dirty_in != batch_) {
            state_[u].dirty_in = batch_;
            changed.push_back(u);
          }
        }
      });
    }
    if (options_.cost == TetCost::kPaper) {
      for (size_t i = kept; i < changed.size(); ++i) {
        normals_[changed[i]] = tetsimplify::boundaryNormal(complex_, positions_, changed[i]);
      }
    }
    for (size_t i = kept; i < changed.size(); ++i) refreshCandidate(changed[i]);
    // An empty batch still made progress: its candidates failed for good or
    // now wait at their true, higher cost.
    if (!batch.empty()) out->batches.push_back(batch);
  }
  if (options_.progress) options_.progress(1.0);
  stats_.batches = out->batches.size();
  stats_.final_tets = complex_.liveTets();
  stats_.final_vertices = complex_.liveVertices();
  stats_.seconds = seconds();
  out->stats = stats_;
}

}  // namespace

Error simplifyTets(const QuantizedTetMesh& mesh, const TetSimplifyOptions& options, TetSimplifyResult* out) {
  TetSimplifier simplifier(options);
  const auto start = std::chrono::steady_clock::now();
  Error error = simplifier.init(mesh);
  if (!error.ok()) return error;
  simplifier.run(out);
  out->stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return error;
}

}  // namespace mrsv
