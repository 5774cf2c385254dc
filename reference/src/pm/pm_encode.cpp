// spec: 6.9 the reference PM encoder (informative).
#include "pm/pm_encode.h"

#include <algorithm>
#include <cmath>

#include "bitstream/range_encoder.h"
#include "common/byte_writer.h"
#include "mrsv/container.h"
#include "mrsv/limits.h"
#include "pm/pm_records.h"
#include "simplify/triangle_distance.h"

namespace mrsv {
namespace {

constexpr uint32_t kNone = CornerTable::kNone;

// Uniform quantisation over [lo, lo + step * (2^bits - 1)].
struct Quantiser {
  double origin = 0, step = 1;
  int32_t top = 0;
  void fit(double lo, double hi, int bits) {
    origin = lo;
    top = static_cast<int32_t>((int64_t{1} << bits) - 1);
    step = hi > lo ? (hi - lo) / top : 1.0;
  }
  // v in steps from the origin, not rounded.
  double inSteps(double v) const { return (v - origin) / step; }
  int32_t operator()(double v) const {
    double q = std::nearbyint(inSteps(v));
    return static_cast<int32_t>(std::clamp(q, 0.0, static_cast<double>(top)));
  }
};

// What the decoder needs to know of one collapse, found by replaying it.
struct ReplayedCollapse {
  uint32_t removed, kept;
  uint32_t left, right;  // third vertex of the face with edge removed->kept / kept->removed
  std::array<int32_t, 3> removed_position, kept_position_before;
  int32_t removed_scalar;
};

// The most a slide onto the grid of a move may take vs off the plane of one
// of its triangles, in quantisation steps; beyond it the move is coded to the
// step (decision D33: 0.5 saved 1 to 3 % of a 14-bit stream, 2 saved 7 to
// 13 % but raised the turbine blade's RMS at 10 % of the faces by 14 %).
constexpr double kSlideTolerance = 1.0;

// A triangle (v, x, y) around a vertex v, rotated to start at v: the face
// F_i = (v, w_i, w_(i+1)) of v's ring (spec 6.6.1).
struct FanFace {
  uint32_t x, y;
};

FanFace rotatedTo(const std::array<uint32_t, 3>& tri, uint32_t v) {
  const int k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
  return {tri[(k + 1) % 3], tri[(k + 2) % 3]};
}

simplify::Vec3 toVec3(const std::array<int32_t, 3>& q) { return {double(q[0]), double(q[1]), double(q[2])}; }
const simplify::Vec3& toVec3(const simplify::Vec3& q) { return q; }

// The twice-area normal (x - p) x (y - p) of fan face f with the vertex at p.
template <typename Point>
simplify::Vec3 faceNormal(const std::vector<Point>& position, const FanFace& f, const simplify::Vec3& p) {
  return simplify::cross(simplify::sub(toVec3(position[f.x]), p), simplify::sub(toVec3(position[f.y]), p));
}

// spec 6.7.3 step 1, from the encoder's side: where the kept vertex goes.
// `p` is the quantised optimum of the collapse and `child` the kept vertex's
// position before it (where the split puts vs back). Along the two axes
// other than the plane axis the move child - p must be a multiple of
// 2^shift, so p slides along its plane to the nearest such point. The
// decoder finds the shift and the axis from vs's ring at the parent level:
// `fan` is the faces around the kept vertex after the collapse, `kept` the
// faces the split leaves it (those it had before that did not touch the
// removed vertex; the whole fan for a boundary vertex). The axis depends on
// p, so the slid point is checked against the axis it gives. When that does
// not settle, the point leaves the grid, or the slide would take vs more than
// kSlideTolerance off one of its planes, p stays and its move is coded to the
// step (the split's move_fine flag).
std::array<int32_t, 3> snappedPlacement(const std::vector<std::array<int32_t, 3>>& position,
                                        const std::vector<FanFace>& fan, const std::vector<FanFace>& kept,
                                        const std::array<int32_t, 3>& p, const std::array<int32_t, 3>& child,
                                        int position_bits, uint8_t move_detail) {
  int64_t longest = 0;
  for (const FanFace& f : fan) longest = std::max(longest, pm::squaredDistance(position[f.x], position[f.y]));
  const int shift = pm::moveShift(longest, move_detail);
  if (shift == 0) return p;
  const int drop = pm::normalDrop(position_bits);
  auto normalAt = [&](const std::array<int32_t, 3>& at) {
    std::array<int64_t, 3> n{0, 0, 0};
    int64_t e0[3], e1[3];
    for (const FanFace& f : kept) {
      pm::reducedEdge(position[f.x], at, drop, e0);
      pm::reducedEdge(position[f.y], at, drop, e1);
      pm::addCross(e0, e1, &n);
    }
    pm::reduceNormal(&n);
    return n;
  };
  auto axisOf = [](const std::array<int64_t, 3>& n) {
    const int axis = pm::normalAxis(n);
    return axis < 0 ? 2 : axis;
  };
  // How far q lies off the planes of the fan's triangles (with v at p), in
  // quantisation steps: the part of a slide that changes the surface.
  auto offPlanes = [&](const std::array<int32_t, 3>& q) {
    const simplify::Vec3 at = toVec3(p);
    const simplify::Vec3 d = simplify::sub(toVec3(q), at);
    double worst = 0.0;
    for (const FanFace& f : fan) {
      const simplify::Vec3 n = faceNormal(position, f, at);
      const double length = simplify::length(n);
      if (length > 0.0) worst = std::max(worst, std::fabs(simplify::dot(n, d)) / length);
    }
    return worst;
  };
  const int64_t unit = int64_t{1} << shift;
  const int64_t top = (int64_t{1} << position_bits) - 1;
  const std::array<int64_t, 3> normal = normalAt(p);
  int axis = axisOf(normal);
  for (int attempt = 0; attempt < 3; ++attempt) {
    // The nearest grid point along the two axes, then back onto the plane
    // through p along the third: a slide along the surface, not off it.
    int64_t slide[3] = {0, 0, 0};
    for (int k : pm::otherAxes(axis)) {
      const int64_t units = pm::floorDivide(int64_t{child[k]} - p[k] + unit / 2, unit);
      slide[k] = int64_t{child[k]} - units * unit - p[k];
    }
    if (normal[axis] != 0) slide[axis] = pm::offsetOnPlane(normal, axis, slide);
    std::array<int32_t, 3> q;
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const int64_t at = p[k] + slide[k];
      inside = inside && at >= 0 && at <= top;
      q[k] = static_cast<int32_t>(std::clamp<int64_t>(at, 0, top));
    }
    const int settled = axisOf(normalAt(q));
    if (inside && settled == axis) return offPlanes(q) <= kSlideTolerance ? q : p;
    axis = settled;
  }
  return p;
}

// Grid points for vertices (decision D34). Rounding errs by up to half a
// step across the surface as well as along it, and only the part across it
// moves the surface. So of the 27 grid points around the nearest one, a
// vertex takes the one that leaves the surface least, measured as a
// collapse measures it (by the area-weighted squared distances to the planes
// of the fan's triangles through the vertex's exact place), among those no
// further from the fan's triangles than the nearest grid point is (so the
// largest error does not grow where the fan is small or sharply bent). A
// boundary vertex takes the nearest point: along its surface it would move
// the boundary.
class GridPointChooser {
 public:
  GridPointChooser(uint32_t vertices, int32_t top) : ends_(vertices, 0), top_(top) {}

  // Whether a vertex's fan is open (the vertex is on the boundary): some
  // face starts at a neighbour at which no face ends. Linear in the fan.
  bool open(const std::vector<FanFace>& fan) {
    ++round_;
    for (const FanFace& f : fan) ends_[f.y] = round_;
    for (const FanFace& f : fan)
      if (ends_[f.x] != round_) return true;
    return false;
  }

  // The grid point for a vertex whose exact place is p (in steps), given the
  // triangles around it (`fan`, with `position` in steps too).
  template <typename Point>
  std::array<int32_t, 3> choose(const std::vector<Point>& position, const std::vector<FanFace>& fan,
                                const std::array<double, 3>& p, bool open) {
    using simplify::Vec3;
    auto onGrid = [this](double x) { return static_cast<int32_t>(std::clamp(x, 0.0, static_cast<double>(top_))); };
    const double nearest[3] = {std::nearbyint(p[0]), std::nearbyint(p[1]), std::nearbyint(p[2])};
    const std::array<int32_t, 3> rounded = {onGrid(nearest[0]), onGrid(nearest[1]), onGrid(nearest[2])};
    if (fan.empty() || open) return rounded;

    // The error of an offset d from p is the quadratic form d' A d, with A
    // the sum over the fan's triangles of n n' / |n| (n the twice-area
    // normal: area times squared distance to the plane, up to a factor 2)
    // plus the tie-break's multiple of the identity.
    double a[6] = {0, 0, 0, 0, 0, 0};  // a00 a01 a02 a11 a12 a22
    double area_sum = 0.0;
    const Vec3 at = {p[0], p[1], p[2]};
    for (const FanFace& f : fan) {
      const Vec3 n = faceNormal(position, f, at);
      const double length = simplify::length(n);
      if (!(length > 0.0)) continue;
      area_sum += length;
      const double w = 1.0 / length;
      a[0] += w * n[0] * n[0], a[1] += w * n[0] * n[1], a[2] += w * n[0] * n[2];
      a[3] += w * n[1] * n[1], a[4] += w * n[1] * n[2], a[5] += w * n[2] * n[2];
    }
    // The distance from p itself weighs a tenth of a plane's: on a flat fan
    // it prefers the nearest point, and elsewhere it keeps the point from
    // straying along the surface to gain little across it (with a hundredth,
    // the largest error at full resolution grew by up to 40 %).
    a[0] += 0.1 * area_sum, a[3] += 0.1 * area_sum, a[5] += 0.1 * area_sum;
    std::array<int32_t, 3> candidate[27];
    double error[27];
    for (int i = 0; i < 27; ++i) {
      candidate[i] = {onGrid(nearest[0] + i % 3 - 1), onGrid(nearest[1] + i / 3 % 3 - 1), onGrid(nearest[2] + i / 9 - 1)};
      const double x = candidate[i][0] - p[0], y = candidate[i][1] - p[1], z = candidate[i][2] - p[2];
      error[i] = x * (a[0] * x + 2.0 * (a[1] * y + a[2] * z)) + y * (a[3] * y + 2.0 * a[4] * z) + z * a[5] * z;
    }
    // The least error among the points within the bound, tried in order of
    // error: the first nearly always is. (The nearest point is within it.)
    double bound = -1.0;  // found only when a point other than the nearest is best
    for (;;) {
      const int best = static_cast<int>(std::min_element(error, error + 27) - error);
      if (candidate[best] == rounded) return rounded;
      if (bound < 0.0) {
        triangles_.clear();
        for (const FanFace& f : fan)
          triangles_.push_back(simplify::makeTriangle(at, toVec3(position[f.x]), toVec3(position[f.y])));
        bound = simplify::fanDistance2(toVec3(rounded), triangles_, 0.0);
      }
      if (simplify::fanDistance2(toVec3(candidate[best]), triangles_, bound) <= bound) return candidate[best];
      error[best] = INFINITY;
    }
  }

 private:
  // Per vertex, the round of open() in which a face of the fan ended at it.
  std::vector<uint64_t> ends_;
  uint64_t round_ = 0;
  int32_t top_;
  std::vector<simplify::Triangle> triangles_;
};

}  // namespace

bool encodeProgressiveMesh(const TriangleMesh& mesh, const SimplifyResult& collapses,
                           const PmEncodeOptions& options, const Metadata& metadata,
                           std::vector<uint8_t>* out, PmEncodeReport* report, std::string* error) {
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  const bool free_placement = options.placement == Placement::kFree;
  const bool has_scalars = !mesh.scalars.empty();
  if (n > kMaxMeshVertices) {
    *error = "more than 2^28 vertices";
    return false;
  }
  if (options.position_bits < 1 || options.position_bits > kMaxPositionBits ||
      (has_scalars && (options.scalar_bits < 1 || options.scalar_bits > kMaxPositionBits))) {
    *error = "position and scalar bits must be 1 to 30";
    return false;
  }
  if (options.move_detail > kMaxPositionBits) {
    *error = "move_detail must be 0 to 30";
    return false;
  }
  // Quantisation: one step for all axes, so that the shape keeps its proportions.
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  auto grow = [&](const std::array<double, 3>& p) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  };
  for (const auto& p : mesh.positions) grow(p);
  if (free_placement)
    for (const auto& batch : collapses.batches)
      for (const auto& c : batch) grow(c.kept_position);
  double extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, hi[k] - lo[k]);
  Quantiser axis[3];
  for (int k = 0; k < 3; ++k) axis[k].fit(lo[k], lo[k] + extent, options.position_bits);
  Quantiser scalar_q;
  if (has_scalars) {
    auto [smin, smax] = std::minmax_element(mesh.scalars.begin(), mesh.scalars.end());
    scalar_q.fit(*smin, *smax, options.scalar_bits);
  }

  // Replay the collapses on per-vertex face lists.
  std::vector<std::array<uint32_t, 3>> faces = mesh.triangles;
  std::vector<uint8_t> alive(faces.size(), 1);
  std::vector<std::vector<uint32_t>> vertex_faces(n);
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (uint32_t v : faces[f]) {
      if (v >= n) {
        *error = "triangle " + std::to_string(f) + " uses a vertex out of range";
        return false;
      }
      vertex_faces[v].push_back(f);
    }
  std::vector<std::array<int32_t, 3>> position(n);
  GridPointChooser grid_points(n, axis[0].top);
  {
    // Each input vertex goes to the grid point nearest its surface.
    std::vector<std::array<double, 3>> in_steps(n);
    for (uint32_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) in_steps[v][k] = axis[k].inSteps(mesh.positions[v][k]);
    std::vector<FanFace> fan;
    for (uint32_t v = 0; v < n; ++v) {
      fan.clear();
      for (uint32_t f : vertex_faces[v]) fan.push_back(rotatedTo(faces[f], v));
      position[v] = grid_points.choose(in_steps, fan, in_steps[v], grid_points.open(fan));
    }
  }
  // Where each vertex is before quantisation (free placement).
  std::vector<std::array<double, 3>> exact(free_placement ? mesh.positions : std::vector<std::array<double, 3>>{});
  std::vector<int32_t> scalar(has_scalars ? n : 0);
  for (uint32_t v = 0; v < scalar.size(); ++v) scalar[v] = scalar_q(mesh.scalars[v]);
  std::vector<uint8_t> removed(n, 0);
  std::vector<std::vector<ReplayedCollapse>> replayed(collapses.batches.size());
  const bool snap = free_placement && options.move_detail > 0;
  std::vector<FanFace> kept_faces, fan_faces;
  for (size_t t = 0; t < collapses.batches.size(); ++t) {
    for (const HalfEdgeCollapse& c : collapses.batches[t]) {
      const uint32_t u = c.removed, v = c.kept;
      if (u >= n || v >= n || u == v || removed[u] || removed[v]) {
        *error = "collapse " + std::to_string(u) + " -> " + std::to_string(v) + " names a removed vertex";
        return false;
      }
      ReplayedCollapse r{u, v, kNone, kNone, position[u], position[v], has_scalars ? scalar[u] : 0};
      for (uint32_t f : vertex_faces[u]) {
        if (!alive[f]) continue;
        const auto& tri = faces[f];
        for (int k = 0; k < 3; ++k) {
          if (tri[k] == u && tri[(k + 1) % 3] == v) r.left = tri[(k + 2) % 3];
          if (tri[k] == v && tri[(k + 1) % 3] == u) r.right = tri[(k + 2) % 3];
        }
      }
      if (r.left == kNone && r.right == kNone) {
        *error = "collapse " + std::to_string(u) + " -> " + std::to_string(v) + " is not along an edge";
        return false;
      }
      kept_faces.clear();
      if (snap)
        for (uint32_t f : vertex_faces[v])
          if (alive[f] && faces[f][0] != u && faces[f][1] != u && faces[f][2] != u)
            kept_faces.push_back(rotatedTo(faces[f], v));
      for (uint32_t f : vertex_faces[u]) {
        if (!alive[f]) continue;
        auto& tri = faces[f];
        if (tri[0] == v || tri[1] == v || tri[2] == v) {
          alive[f] = 0;
          continue;
        }
        for (uint32_t& x : tri)
          if (x == u) x = v;
        vertex_faces[v].push_back(f);
      }
      vertex_faces[u].clear();
      vertex_faces[u].shrink_to_fit();
      removed[u] = 1;
      if (free_placement) {
        fan_faces.clear();
        for (uint32_t f : vertex_faces[v])
          if (alive[f]) fan_faces.push_back(rotatedTo(faces[f], v));
        const bool open = grid_points.open(fan_faces);
        // A kept vertex that stays, or takes the removed one's place, keeps
        // that vertex's grid point.
        std::array<int32_t, 3> optimum;
        if (c.kept_position == exact[v]) {
          optimum = position[v];
        } else if (c.kept_position == exact[u]) {
          optimum = position[u];
        } else {
          std::array<double, 3> at;
          for (int k = 0; k < 3; ++k) at[k] = axis[k].inSteps(c.kept_position[k]);
          optimum = grid_points.choose(position, fan_faces, at, open);
        }
        exact[v] = c.kept_position;
        if (!snap) {
          position[v] = optimum;
        } else {
          if (open) kept_faces = fan_faces;  // a boundary vertex keeps all its faces
          position[v] = snappedPlacement(position, fan_faces, kept_faces, optimum, position[v],
                                         options.position_bits, options.move_detail);
        }
      }
      replayed[t].push_back(r);
    }
  }

  // The base mesh: surviving faces in input order, vertices numbered by first use.
  std::vector<uint32_t> id(n, kNone);
  std::vector<std::array<uint32_t, 3>> base_faces;
  ProgressiveMesh pm;
  ProgressiveMesh::Impl& s = pm.state();
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (!alive[f]) continue;
    std::array<uint32_t, 3> tri;
    for (int k = 0; k < 3; ++k) {
      uint32_t v = faces[f][k];
      if (id[v] == kNone) {
        id[v] = static_cast<uint32_t>(s.positions.size());
        s.positions.push_back(position[v]);
        if (has_scalars) s.scalars.push_back(scalar[v]);
      }
      tri[k] = id[v];
    }
    base_faces.push_back(tri);
  }
  PmHeader& h = s.header;
  h.placement = free_placement ? kPlacementFree : kPlacementEndpoint;
  h.move_detail = free_placement ? options.move_detail : 0;
  h.position_bits = options.position_bits;
  h.scalar_bits = has_scalars ? options.scalar_bits : 0;
  h.base_vertex_count = static_cast<uint32_t>(s.positions.size());
  h.base_triangle_count = static_cast<uint32_t>(base_faces.size());
  uint64_t split_total = 0;
  for (const auto& batch : replayed) split_total += batch.size();
  h.vertex_count = static_cast<uint32_t>(h.base_vertex_count + split_total);
  h.batch_count = 0;
  for (const auto& batch : replayed) h.batch_count += batch.empty() ? 0 : 1;
  for (int k = 0; k < 3; ++k) h.origin[k] = axis[k].origin;
  h.position_step = axis[0].step;
  if (has_scalars) {
    h.scalar_origin = scalar_q.origin;
    h.scalar_step = scalar_q.step;
  }
  if (h.base_vertex_count < 3) {
    *error = "the base mesh has fewer than 3 vertices";
    return false;
  }
  if (std::string problem = s.table.build(h.base_vertex_count, base_faces); !problem.empty()) {
    *error = "the base mesh is not an oriented manifold: " + problem;
    return false;
  }

  ContainerWriter writer;
  writer.addChunk(kChunkMeshHeader, serializePmHeader(h));
  if (!metadata.entries.empty()) writer.addChunk(kChunkMeta, serializeMetadata(metadata));
  pm::PmContexts ctx;
  {
    std::vector<uint8_t> payload;
    RangeEncoder rc(&payload);
    EncodingCoder coder{&rc};
    std::vector<std::array<uint32_t, 3>> tris = base_faces;
    std::string problem = pm::codeBaseMesh(coder, ctx, s, &tris);
    if (!problem.empty()) {
      *error = "base mesh: " + problem;
      return false;
    }
    rc.finish();
    report->base_bytes = payload.size();
    writer.addChunk(kChunkBaseMesh, payload);
  }
  report->split_bytes = 0;
  for (size_t t = replayed.size(); t-- > 0;) {
    std::vector<ReplayedCollapse>& batch = replayed[t];
    if (batch.empty()) continue;
    for (const auto& r : batch)
      if (id[r.kept] == kNone) {
        *error = "a kept vertex is not in the mesh when its split is decoded";
        return false;
      }
    std::sort(batch.begin(), batch.end(),
              [&](const ReplayedCollapse& x, const ReplayedCollapse& y) { return id[x.kept] < id[y.kept]; });
    std::vector<uint8_t> payload;
    ByteWriter(&payload).u32(static_cast<uint32_t>(batch.size()));
    RangeEncoder rc(&payload);
    EncodingCoder coder{&rc};
    BatchCursor cursor = s.beginBatch();
    const CornerTable::Ring& ring = s.ring;
    for (const ReplayedCollapse& c : batch) {
      SplitRecord record;
      record.vs = id[c.kept];
      s.findRing(record.vs);  // codeSplit codes positions in this ring
      const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
      auto where = [&](uint32_t v, uint32_t absent) {
        if (v == kNone) return absent;
        auto it = std::find(ring.neighbours.begin(), ring.neighbours.end(), id[v]);
        return it == ring.neighbours.end() ? kNone : static_cast<uint32_t>(it - ring.neighbours.begin());
      };
      record.a = where(c.left, 0);
      record.b = where(c.right, d - 1);
      record.shape = {c.left != kNone, c.right != kNone};
      if (record.a == kNone || record.b == kNone || (c.left == kNone && !ring.boundary) ||
          (c.right == kNone && !ring.boundary)) {
        *error = "collapse " + std::to_string(c.removed) + " -> " + std::to_string(c.kept) +
                 " does not match the decoder's ring (simplifier broke batch independence?)";
        return false;
      }
      record.vt_position = c.removed_position;
      for (int k = 0; k < 3; ++k) record.vs_move[k] = c.kept_position_before[k] - s.positions[record.vs][k];
      record.vt_scalar = c.removed_scalar;
      std::string problem = pm::codeSplit(coder, ctx, s, &cursor, &record);
      if (!problem.empty()) {
        *error = "split of vertex " + std::to_string(record.vs) + ": " + problem;
        return false;
      }
      id[c.removed] = s.table.vertexCount();
      s.splits.push_back(record);
      s.applySplit(s.ring);
    }
    rc.finish();
    report->split_bytes += payload.size();
    writer.addChunk(kChunkSplits, payload);
  }
  *out = writer.finish();
  report->base_vertices = h.base_vertex_count;
  report->base_triangles = h.base_triangle_count;
  report->splits = static_cast<uint32_t>(split_total);
  report->batches = h.batch_count;
  return true;
}

}  // namespace mrsv
