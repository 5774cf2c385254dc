// spec: 8.5 greedy insertion, 8.6 the border rule, 8.7 stages.
#include "mrsv/terrain_insertion.h"

#include <algorithm>
#include <queue>

#include "reconstruct/delaunay2.h"
#include "reconstruct/line_insertion.h"

namespace mrsv {

using reconstruct::Delaunay2;
using reconstruct::orient2d;
using reconstruct::Point2;

namespace {

// A triangle's worst lattice sample: error num / den (den = twice the
// triangle's area), the sample's linear index breaking ties.
struct Candidate {
  __int128 num = 0;
  int64_t den = 1;
  uint64_t sample = 0;
  uint32_t triangle = 0;
  uint32_t version = 0;
};

// Larger error first, then the smaller sample index: the order of spec 8.5.
bool worse(const Candidate& a, const Candidate& b) {
  const __int128 l = a.num * b.den, r = b.num * a.den;
  if (l != r) return l > r;
  return a.sample < b.sample;
}

struct HeapOrder {
  bool operator()(const Candidate& a, const Candidate& b) const { return worse(b, a); }
};

int64_t floorDiv(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
int64_t ceilDiv(int64_t a, int64_t b) { return -floorDiv(-a, b); }

}  // namespace

struct TerrainInserter::State {
  uint32_t nx, ny;
  Delaunay2 dt;
  std::vector<uint8_t> is_vertex;       // per sample
  std::vector<uint64_t> vertex_sample;  // per vertex
  std::vector<int32_t> vertex_value;    // per vertex, from the last stage's field
  std::vector<uint32_t> version;        // per triangle; heap entries of older versions are stale
  std::priority_queue<Candidate, std::vector<Candidate>, HeapOrder> heap;
  std::vector<uint32_t> touched;
  // The current stage.
  const SampleField* field = nullptr;
  int64_t step = 1;  // 2^shift
  bool skip_border = false;
  Candidate last_max;

  State(uint32_t x, uint32_t y) : nx(x), ny(y), dt(int32_t(x - 1), int32_t(y - 1)), is_vertex(uint64_t{x} * y) {
    for (uint32_t v = 0; v < 4; ++v) {
      const Point2 p = dt.point(v);
      vertex_sample.push_back(uint64_t(p.y) * nx + uint64_t(p.x));
      is_vertex[vertex_sample.back()] = 1;
    }
    vertex_value.assign(4, 0);
  }

  // The lattice coordinates of an axis of n samples within [lo, hi], in order:
  // multiples of step, and n - 1.
  template <class F>
  void forLattice(int64_t lo, int64_t hi, int64_t n, F&& f) const {
    for (int64_t c = ceilDiv(lo, step) * step; c <= hi; c += step) f(c);
    if ((n - 1) % step != 0 && lo <= n - 1 && n - 1 <= hi) f(n - 1);
  }

  // spec 8.5: a triangle's worst lattice sample, exactly.
  void scan(uint32_t t) {
    ++version[t];
    const auto& tv = dt.triangle(t);
    const Point2 a = dt.point(tv[0]), b = dt.point(tv[1]), c = dt.point(tv[2]);
    const int64_t za = vertex_value[tv[0]], zb = vertex_value[tv[1]] - za, zc = vertex_value[tv[2]] - za;
    const int64_t den = orient2d(a, b, c);
    // Barycentric numerators as functions of the sample (x, y): w = ex * x + ey * y + e0.
    struct Edge {
      int64_t ex, ey, e0;
    };
    auto edge = [](Point2 u, Point2 v) {
      return Edge{int64_t{u.y} - v.y, int64_t{v.x} - u.x, int64_t{u.x} * v.y - int64_t{u.y} * v.x};
    };
    const Edge ea = edge(b, c), eb = edge(c, a), ec = edge(a, b);
    int64_t x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
    int64_t y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
    if (skip_border) {
      x0 = std::max<int64_t>(x0, 1), x1 = std::min<int64_t>(x1, int64_t{nx} - 2);
      y0 = std::max<int64_t>(y0, 1), y1 = std::min<int64_t>(y1, int64_t{ny} - 2);
    }
    Candidate best;
    best.den = den;
    best.triangle = t;
    best.version = version[t];
    bool found = false;
    const int32_t* values = field->values.data();
    forLattice(y0, y1, ny, [&](int64_t y) {
      // The x range where all three barycentric numerators are >= 0.
      int64_t lo = x0, hi = x1;
      for (const Edge& e : {ea, eb, ec}) {
        const int64_t r = -(e.ey * y + e.e0);  // need ex * x >= r
        if (e.ex > 0) lo = std::max(lo, ceilDiv(r, e.ex));
        else if (e.ex < 0) hi = std::min(hi, floorDiv(-r, -e.ex));
        else if (r > 0) return;
      }
      if (lo > hi) return;
      const int64_t row = y * nx;
      forLattice(lo, hi, nx, [&](int64_t x) {
        const int64_t wb = eb.ex * x + eb.ey * y + eb.e0, wc = ec.ex * x + ec.ey * y + ec.e0;
        __int128 e = __int128{values[row + x] - za} * den - (__int128{wb} * zb + __int128{wc} * zc);
        if (e < 0) e = -e;
        // Samples come in increasing index order: on a tie the first stays.
        if (e > best.num) {
          best.num = e;
          best.sample = uint64_t(row + x);
          found = true;
        }
      });
    });
    if (found) heap.push(best);
  }

  // The worst candidate still current, or false when none is left.
  bool top(Candidate* out) {
    while (!heap.empty()) {
      const Candidate& c = heap.top();
      if (c.version == version[c.triangle]) {
        *out = c;
        return true;
      }
      heap.pop();
    }
    return false;
  }

  // Every vertex's rank (spec 8.3) is its insertion number, corners 0 to 3:
  // ties of cocircular vertices go to the older ones (decision D47).
  void insertSample(uint64_t sample, uint32_t hint) {
    const Point2 p{int32_t(sample % nx), int32_t(sample / nx)};
    const uint32_t t = dt.locate(p, hint);
    touched.clear();
    dt.insert(p, dt.vertexCount(), t, &touched);
    is_vertex[sample] = 1;
    vertex_sample.push_back(sample);
    vertex_value.push_back(field->values[sample]);
    version.resize(dt.triangleCount(), 0);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (uint32_t s : touched) scan(s);
  }

  // spec 8.6: each side refined by 1-D insertion from its own samples.
  void borderRule(__int128 bound_num, int64_t bound_den) {
    struct Side {
      uint64_t start, stride, count;
    };
    const Side sides[4] = {{0, 1, nx},
                           {uint64_t{ny - 1} * nx, 1, nx},
                           {0, nx, ny},
                           {nx - 1, nx, ny}};
    for (const Side& s : sides) {
      std::vector<int64_t> positions, values;
      std::vector<uint8_t> kept;
      forLattice(0, int64_t(s.count) - 1, int64_t(s.count), [&](int64_t c) {
        const uint64_t sample = s.start + uint64_t(c) * s.stride;
        positions.push_back(c);
        values.push_back(field->values[sample]);
        kept.push_back(is_vertex[sample]);
      });
      reconstruct::insertAlongLine(positions, values, bound_num, bound_den, &kept);
      uint32_t hint = 0;
      for (size_t k = 0; k < positions.size(); ++k) {
        const uint64_t sample = s.start + uint64_t(positions[k]) * s.stride;
        if (!kept[k] || is_vertex[sample]) continue;
        const Point2 p{int32_t(sample % nx), int32_t(sample / nx)};
        hint = dt.locate(p, hint);
        touched.clear();
        dt.insert(p, dt.vertexCount(), hint, &touched);
        hint = touched.front();
        is_vertex[sample] = 1;
        vertex_sample.push_back(sample);
        vertex_value.push_back(field->values[sample]);
      }
    }
  }
};

TerrainInserter::TerrainInserter(uint32_t size_x, uint32_t size_y)
    : state_(std::make_unique<State>(size_x, size_y)) {}
TerrainInserter::~TerrainInserter() = default;

bool TerrainInserter::refine(const SampleField& field, unsigned shift, const InsertionLimits& limits,
                             std::string* error, const InsertionProgress& progress) {
  State& s = *state_;
  if (field.size[0] != s.nx || field.size[1] != s.ny || field.size[2] != 1) {
    *error = "the field's sizes differ from the mesh's grid";
    return false;
  }
  if (!limits.max_error.set() && limits.max_cells == 0) {
    *error = "no limit: give a maximum error or a triangle count";
    return false;
  }
  if (shift > 16) {
    *error = "lattice shift above 16";
    return false;
  }
  s.field = &field;
  s.step = int64_t{1} << shift;
  for (size_t v = 0; v < s.vertex_sample.size(); ++v) s.vertex_value[v] = field.values[s.vertex_sample[v]];
  // spec 8.7: a stage on a lattice of step 2^shift > 1 stops at 2^(shift+1)
  // times the bound (decision D46: coarse stages, which see blurred samples,
  // then place few vertices the finer stages would not have chosen).
  const __int128 bound_num = __int128{limits.max_error.num} << (shift == 0 ? 0 : shift + 1);
  const int64_t bound_den = limits.max_error.den;
  const bool border = limits.border_rule && limits.max_error.set();
  if (border) s.borderRule(bound_num, bound_den);
  s.version.assign(s.dt.triangleCount(), 0);
  s.heap = {};
  s.skip_border = border;
  for (uint32_t t = 0; t < s.dt.triangleCount(); ++t) s.scan(t);

  uint64_t since_progress = 0;
  Candidate worst;
  while (s.top(&worst)) {
    if (limits.max_error.set() &&
        worst.num * bound_den <= bound_num * worst.den)
      break;
    if (limits.max_cells != 0 && s.dt.triangleCount() >= limits.max_cells) break;
    s.insertSample(worst.sample, worst.triangle);
    if (progress && ++since_progress == 4096) {
      since_progress = 0;
      if (!progress(s.dt.triangleCount())) break;
    }
  }
  if (!s.top(&s.last_max)) s.last_max = Candidate{};
  return true;
}

double TerrainInserter::maxError() const {
  return static_cast<double>(state_->last_max.num) / static_cast<double>(state_->last_max.den);
}

uint64_t TerrainInserter::vertexCount() const { return state_->dt.vertexCount(); }
uint64_t TerrainInserter::cellCount() const { return state_->dt.triangleCount(); }

void TerrainInserter::mesh(GridMesh* out) const {
  const State& s = *state_;
  out->dims = 2;
  out->size[0] = s.nx, out->size[1] = s.ny, out->size[2] = 1;
  out->points.resize(s.dt.vertexCount());
  out->values.resize(s.dt.vertexCount());
  for (uint32_t v = 0; v < s.dt.vertexCount(); ++v) {
    const Point2 p = s.dt.point(v);
    out->points[v] = {uint32_t(p.x), uint32_t(p.y), 0};
    out->values[v] = s.vertex_value[v];
  }
  out->cells.resize(s.dt.triangleCount());
  for (uint32_t t = 0; t < s.dt.triangleCount(); ++t) {
    const auto& c = s.dt.triangle(t);
    out->cells[t] = {c[0], c[1], c[2], 0};
  }
}

}  // namespace mrsv
