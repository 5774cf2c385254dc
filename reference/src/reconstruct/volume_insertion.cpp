// spec: 10.4 (the error of a sample), 10.5 (the greedy order), 10.6 (the
// paper's distance), 10.7 (stages).
#include "mrsv/volume_insertion.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "reconstruct/delaunay3.h"

namespace mrsv {

using reconstruct::Delaunay3;
using reconstruct::GridPoint;
using reconstruct::orient3dValue;

namespace {

// Floor and ceiling of b / a for a > 0 (C++ division truncates toward 0).
int64_t floorDiv(int64_t b, int64_t a) { return b >= 0 ? b / a : -((-b + a - 1) / a); }
int64_t ceilDiv(int64_t b, int64_t a) { return b >= 0 ? (b + a - 1) / a : -((-b) / a); }

// The lattice of a stage on one axis of n samples: multiples of step, and n - 1.
struct AxisLattice {
  int64_t n, step;
  // Calls f(c) for every lattice coordinate c in [lo, hi], ascending.
  template <typename F>
  void each(int64_t lo, int64_t hi, F&& f) const {
    lo = std::max<int64_t>(lo, 0);
    hi = std::min<int64_t>(hi, n - 1);
    int64_t c = ceilDiv(lo, step) * step;
    for (; c <= hi; c += step) f(c);
    if ((n - 1) % step != 0 && n - 1 >= lo && n - 1 <= hi) f(n - 1);
  }
  bool has(int64_t c) const { return c % step == 0 || c == n - 1; }
};

__int128 gcd128(__int128 a, __int128 b) {
  while (b != 0) {
    const __int128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

}  // namespace

struct VolumeInserter::State {
  uint32_t size[3] = {0, 0, 0};
  bool valid = false;
  std::string init_error;
  Delaunay3 dt;
  VolumeDistance distance = VolumeDistance::kMesh;
  std::vector<int32_t> value;        // per vertex (vertex 0, the infinite one, unused)
  std::vector<uint8_t> is_vertex;    // per sample
  // Each finite cell's worst lattice sample: error err / det (det = 6 x its
  // volume), err == 0 when none is off the mesh.
  struct Worst {
    __int128 err = 0;
    int64_t det = 1;
    uint64_t sample = 0;
  };
  std::vector<Worst> worst;
  // Max-heap of cells by (error, -sample). Each entry carries the error as a
  // double so that sifting stays in the heap's own memory; orders the double
  // cannot settle (relative gap below 1e-14, where its rounding could decide)
  // are decided exactly from `worst`, so the order is the exact one.
  struct HeapEntry {
    double key;
    uint32_t cell;
  };
  std::vector<HeapEntry> heap;
  std::vector<uint32_t> heap_pos;
  __int128 last_err = 0;
  int64_t last_det = 1;

  // Stage data.
  const SampleField* field = nullptr;
  AxisLattice lattice[3];
  bool wide = false;  // interpolants need 128 bits (spec 10.4's bound)
  bool bounded = false;
  // This stage's bound num / den (spec 10.7, as 8.7).
  __int128 bound_num = 0;
  int64_t bound_den = 1;

  bool exactlyBetter(uint32_t a, uint32_t b) const {
    const __int128 l = worst[a].err * worst[b].det, r = worst[b].err * worst[a].det;
    return l != r ? l > r : worst[a].sample < worst[b].sample;
  }
  bool better(const HeapEntry& a, const HeapEntry& b) const {
    if (a.key > b.key * (1 + 1e-14)) return true;
    if (b.key > a.key * (1 + 1e-14)) return false;
    return exactlyBetter(a.cell, b.cell);
  }
  void siftUp(size_t i) {
    const HeapEntry e = heap[i];
    while (i > 0) {
      const size_t up = (i - 1) / 2;
      if (!better(e, heap[up])) break;
      heap[i] = heap[up];
      heap_pos[heap[i].cell] = static_cast<uint32_t>(i);
      i = up;
    }
    heap[i] = e;
    heap_pos[e.cell] = static_cast<uint32_t>(i);
  }
  void siftDown(size_t i) {
    const HeapEntry e = heap[i];
    for (;;) {
      size_t best = i;
      const HeapEntry* best_entry = &e;
      for (size_t k = 2 * i + 1; k <= 2 * i + 2 && k < heap.size(); ++k)
        if (better(heap[k], *best_entry)) best = k, best_entry = &heap[k];
      if (best == i) break;
      heap[i] = *best_entry;
      heap_pos[heap[i].cell] = static_cast<uint32_t>(i);
      i = best;
    }
    heap[i] = e;
    heap_pos[e.cell] = static_cast<uint32_t>(i);
  }
  void heapPush(uint32_t c) {
    heap.push_back(HeapEntry{static_cast<double>(worst[c].err) / static_cast<double>(worst[c].det), c});
    siftUp(heap.size() - 1);
  }
  void heapRemove(uint32_t c) {
    if (c >= heap_pos.size() || heap_pos[c] == Delaunay3::kNone) return;
    const size_t i = heap_pos[c];
    heap_pos[c] = Delaunay3::kNone;
    const HeapEntry last = heap.back();
    heap.pop_back();
    if (i == heap.size()) return;
    heap[i] = last;
    heap_pos[last.cell] = static_cast<uint32_t>(i);
    siftUp(i);
    siftDown(heap_pos[last.cell]);
  }

  template <typename Acc>
  void scanCell(uint32_t c);
  void scan(uint32_t c) {
    if (worst.size() < dt.cellSlots()) worst.resize(dt.cellSlots());
    if (heap_pos.size() < dt.cellSlots()) heap_pos.resize(dt.cellSlots(), Delaunay3::kNone);
    if (wide) scanCell<__int128>(c);
    else scanCell<int64_t>(c);
    // A tet within the bound is never chosen before the stage ends: out of
    // the heap, which then holds only the tets left to refine (most tets are
    // within it at the end; the heap's cache misses were a third of the time).
    if (worst[c].err > 0 && !(bounded && worst[c].err * bound_den <= bound_num * worst[c].det))
      heapPush(c);
  }
  void insertVertex(const GridPoint& p, uint32_t cell);
  void trilinearPass(const ErrorBound& bound);
};

// spec 10.4: the error of a lattice sample p in the tet (a0, a1, a2, a3) is
// |s(p) * D - sum_k v_k lambda_k(p)| / D with D = orient(a0..a3) > 0 and
// lambda_k(p) = orient of the tet with a_k replaced by p (affine in p, >= 0
// exactly when p is in the closed tet). Rows of the bounding box are cut to
// the x range where all four lambda_k >= 0, by exact integer division.
template <typename Acc>
void VolumeInserter::State::scanCell(uint32_t c) {
  const Delaunay3::Cell& t = dt.cell(c);
  const GridPoint* P[4] = {&dt.point(t.v[0]), &dt.point(t.v[1]), &dt.point(t.v[2]), &dt.point(t.v[3])};
  const int64_t D = orient3dValue(*P[0], *P[1], *P[2], *P[3]);
  int64_t g[4][3], h[4];
  Acc G[3] = {0, 0, 0}, H = 0;
  for (int k = 0; k < 4; ++k) {
    GridPoint q[4] = {*P[0], *P[1], *P[2], *P[3]};
    q[k] = GridPoint{0, 0, 0};
    h[k] = orient3dValue(q[0], q[1], q[2], q[3]);
    for (int a = 0; a < 3; ++a) {
      q[k] = GridPoint{a == 0, a == 1, a == 2};
      g[k][a] = orient3dValue(q[0], q[1], q[2], q[3]) - h[k];
    }
    const Acc v = value[t.v[k]];
    for (int a = 0; a < 3; ++a) G[a] += v * g[k][a];
    H += v * h[k];
  }
  int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::min(std::min((*P[0])[a], (*P[1])[a]), std::min((*P[2])[a], (*P[3])[a]));
    hi[a] = std::max(std::max((*P[0])[a], (*P[1])[a]), std::max((*P[2])[a], (*P[3])[a]));
  }
  Acc best = 0;
  uint64_t best_sample = 0;
  const int32_t* samples = field->values.data();
  const uint64_t sx = size[0], sy = size[1];
  lattice[2].each(lo[2], hi[2], [&](int64_t z) {
    lattice[1].each(lo[1], hi[1], [&](int64_t y) {
      int64_t xlo = lo[0], xhi = hi[0];
      for (int k = 0; k < 4 && xlo <= xhi; ++k) {
        const int64_t b = g[k][1] * y + g[k][2] * z + h[k], a = g[k][0];
        if (a > 0) xlo = std::max(xlo, ceilDiv(-b, a));
        else if (a < 0) xhi = std::min(xhi, floorDiv(b, -a));
        else if (b < 0) xhi = xlo - 1;
      }
      if (xlo > xhi) return;
      const uint64_t row = (uint64_t(z) * sy + uint64_t(y)) * sx;
      const Acc base = H + G[1] * y + G[2] * z;
      lattice[0].each(xlo, xhi, [&](int64_t x) {
        Acc e = Acc{samples[row + x]} * D - (base + G[0] * x);
        if (e < 0) e = -e;
        // Ascending sample order: strictly larger keeps the smallest index.
        if (e > best) best = e, best_sample = row + uint64_t(x);
      });
    });
  });
  worst[c].err = best;
  worst[c].det = D;
  worst[c].sample = best_sample;
}

void VolumeInserter::State::insertVertex(const GridPoint& p, uint32_t cell) {
  if (cell == Delaunay3::kNone) dt.insert(p);
  else dt.insertInCell(p, cell);
  const uint64_t s = field->index(p[0], p[1], p[2]);
  value.push_back(field->values[s]);
  is_vertex[s] = 1;
}

// spec 10.6: the paper's distance, |s - trilinear interpolant of the eight
// corners of the sample's cell of the previous lattice (step 2^(shift+1))|,
// as (|s * den - num|) / den with den the product of the cell's sides.
void VolumeInserter::State::trilinearPass(const ErrorBound& bound) {
  AxisLattice parent[3];
  for (int a = 0; a < 3; ++a) parent[a] = AxisLattice{lattice[a].n, lattice[a].step * 2};
  lattice[2].each(0, lattice[2].n - 1, [&](int64_t z) {
    lattice[1].each(0, lattice[1].n - 1, [&](int64_t y) {
      lattice[0].each(0, lattice[0].n - 1, [&](int64_t x) {
        const int64_t c[3] = {x, y, z};
        if (parent[0].has(x) && parent[1].has(y) && parent[2].has(z)) return;
        const uint64_t s = field->index(uint32_t(x), uint32_t(y), uint32_t(z));
        if (is_vertex[s]) return;
        int64_t lo[3], hi[3];
        __int128 den = 1;
        for (int a = 0; a < 3; ++a) {
          if (parent[a].has(c[a])) {
            lo[a] = hi[a] = c[a];
            continue;
          }
          lo[a] = c[a] / parent[a].step * parent[a].step;
          hi[a] = std::min(lo[a] + parent[a].step, parent[a].n - 1);
          den *= hi[a] - lo[a];
        }
        __int128 num = 0;
        for (int corner = 0; corner < 8; ++corner) {
          __int128 w = 1;
          uint32_t q[3];
          bool skip = false;
          for (int a = 0; a < 3; ++a) {
            const bool up = (corner >> a) & 1;
            if (lo[a] == hi[a]) {
              if (up) skip = true;
              q[a] = uint32_t(lo[a]);
              continue;
            }
            q[a] = uint32_t(up ? hi[a] : lo[a]);
            w *= up ? c[a] - lo[a] : hi[a] - c[a];
          }
          if (!skip) num += w * field->at(q[0], q[1], q[2]);
        }
        __int128 d = __int128{field->values[s]} * den - num;
        if (d < 0) d = -d;
        if (d * bound.den > __int128{bound.num} * den)
          insertVertex(GridPoint{int32_t(x), int32_t(y), int32_t(z)}, Delaunay3::kNone);
      });
    });
  });
}

VolumeInserter::VolumeInserter(uint32_t size_x, uint32_t size_y, uint32_t size_z) : state_(new State) {
  State& s = *state_;
  s.size[0] = size_x, s.size[1] = size_y, s.size[2] = size_z;
  s.valid = s.dt.init(size_x, size_y, size_z, &s.init_error);
  if (!s.valid) return;
  s.is_vertex.assign(uint64_t{size_x} * size_y * size_z, 0);
  s.value.assign(s.dt.vertexSlots(), 0);
  for (uint32_t v = 1; v < s.dt.vertexSlots(); ++v) {
    const GridPoint& p = s.dt.point(v);
    s.is_vertex[(uint64_t(p[2]) * size_y + p[1]) * size_x + p[0]] = 1;
  }
}

VolumeInserter::~VolumeInserter() = default;

void VolumeInserter::setDistance(VolumeDistance distance) { state_->distance = distance; }

bool VolumeInserter::refine(const SampleField& field, unsigned shift, const InsertionLimits& limits,
                            std::string* error, const InsertionProgress& progress) {
  State& s = *state_;
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!s.valid) return fail(s.init_error);
  if (field.size[0] != s.size[0] || field.size[1] != s.size[1] || field.size[2] != s.size[2])
    return fail("volume insertion: the field's sizes differ from the mesh's");
  if (field.values.size() != uint64_t{s.size[0]} * s.size[1] * s.size[2])
    return fail("volume insertion: the field's sample count does not match its sizes");
  if (shift > 30) return fail("volume insertion: shift above 30");
  if (!limits.max_error.set() && limits.max_cells == 0)
    return fail("volume insertion needs a maximum error or a tet count");
  if (limits.max_error.set() && (limits.max_error.den <= 0 || limits.max_error.den > (int64_t{1} << 30) ||
                                 limits.max_error.num > (int64_t{1} << 62)))
    return fail("volume insertion: the maximum error is out of range");

  s.field = &field;
  s.bounded = limits.max_error.set();
  // spec 10.7 (as 8.7, decision D46): a stage on a lattice of step 2^shift > 1
  // stops at 2^(shift+1) times the bound. No error exceeds 2^33 sample units
  // (int32 samples), so the bound is capped at 2^34, which keeps its products
  // with a tet's 6 x volume (below 2^48) within 128 bits.
  s.bound_den = limits.max_error.den;
  s.bound_num = limits.max_error.num;
  if (shift > 0 && s.bounded) {
    const __int128 cap = (__int128{1} << 34) * s.bound_den;
    s.bound_num = s.bound_num << (shift + 1 > 40 ? 40 : shift + 1);
    if (s.bound_num > cap) s.bound_num = cap;
  }
  for (int a = 0; a < 3; ++a) s.lattice[a] = AxisLattice{int64_t{s.size[a]}, int64_t{1} << shift};
  // spec 10.4: 64-bit interpolants when max|sample| x side^3 < 2^57 (the
  // terms of the error stay below 24 x that), else 128-bit.
  int64_t vmax = 0;
  for (int32_t v : field.values) vmax = std::max<int64_t>(vmax, std::llabs(int64_t{v}));
  const int64_t n = std::max(std::max(s.size[0], s.size[1]), s.size[2]);
  s.wide = static_cast<__int128>(vmax) * n * n * n >= (__int128{1} << 57);

  for (uint32_t v = 1; v < s.dt.vertexSlots(); ++v) {
    const GridPoint& p = s.dt.point(v);
    s.value[v] = field.at(uint32_t(p[0]), uint32_t(p[1]), uint32_t(p[2]));
  }
  if (s.distance == VolumeDistance::kTrilinear && limits.max_error.set()) s.trilinearPass(limits.max_error);

  // Every cell's worst sample on this stage's lattice, from scratch.
  s.heap.clear();
  s.heap_pos.assign(s.dt.cellSlots(), Delaunay3::kNone);
  s.worst.assign(s.dt.cellSlots(), State::Worst{});
  for (uint32_t c = 0; c < s.dt.cellSlots(); ++c)
    if (s.dt.isLive(c) && s.dt.isFinite(c)) s.scan(c);

  uint64_t inserted = 0;
  while (!s.heap.empty()) {
    const uint32_t top = s.heap[0].cell;
    const State::Worst w = s.worst[top];
    if (s.bounded && w.err * s.bound_den <= s.bound_num * w.det) break;
    if (limits.max_cells != 0 && s.dt.finiteCellCount() >= limits.max_cells) break;
    const uint32_t x = uint32_t(w.sample % s.size[0]);
    const uint32_t y = uint32_t(w.sample / s.size[0] % s.size[1]);
    const uint32_t z = uint32_t(w.sample / (uint64_t{s.size[0]} * s.size[1]));
    // The top cell holds its worst sample: no walk needed.
    s.insertVertex(GridPoint{int32_t(x), int32_t(y), int32_t(z)}, top);
    for (uint32_t c : s.dt.removedCells()) s.heapRemove(c);
    for (uint32_t c : s.dt.createdCells())
      if (s.dt.isFinite(c)) s.scan(c);
    if (progress && (++inserted & 1023) == 0 && !progress(s.dt.finiteCellCount())) break;
  }
  if (!s.heap.empty()) {
    s.last_err = s.worst[s.heap[0].cell].err, s.last_det = s.worst[s.heap[0].cell].det;
  } else {
    // Every tet within the bound: the largest error is among all of them.
    s.last_err = 0, s.last_det = 1;
    for (uint32_t c = 0; c < s.dt.cellSlots(); ++c)
      if (s.dt.isLive(c) && s.dt.isFinite(c) &&
          s.worst[c].err * s.last_det > s.last_err * s.worst[c].det)
        s.last_err = s.worst[c].err, s.last_det = s.worst[c].det;
  }
  s.field = nullptr;
  return true;
}

void VolumeInserter::maxError(int64_t* num, int64_t* den) const {
  __int128 a = state_->last_err, b = state_->last_det;
  const __int128 g = a == 0 ? b : gcd128(a, b);
  a /= g, b /= g;
  // An error that needs more than 63 bits (int32 samples of a wide range) is
  // rounded down in the last bits it cannot keep; the mesh itself is exact.
  while (a > INT64_MAX) a >>= 1, b >>= 1;
  *num = static_cast<int64_t>(a);
  *den = static_cast<int64_t>(b == 0 ? 1 : b);
}

uint64_t VolumeInserter::vertexCount() const { return state_->valid ? state_->dt.vertexSlots() - 1 : 0; }

uint64_t VolumeInserter::cellCount() const { return state_->valid ? state_->dt.finiteCellCount() : 0; }

void VolumeInserter::mesh(GridMesh* out) const {
  const State& s = *state_;
  *out = GridMesh{};
  out->dims = 3;
  for (int a = 0; a < 3; ++a) out->size[a] = s.size[a];
  if (!s.valid) return;
  for (uint32_t v = 1; v < s.dt.vertexSlots(); ++v) {
    const GridPoint& p = s.dt.point(v);
    out->points.push_back({uint32_t(p[0]), uint32_t(p[1]), uint32_t(p[2])});
    out->values.push_back(s.value[v]);
  }
  out->cells.reserve(s.dt.finiteCellCount());
  for (uint32_t c = 0; c < s.dt.cellSlots(); ++c)
    if (s.dt.isLive(c) && s.dt.isFinite(c)) {
      const auto& v = s.dt.cell(c).v;
      out->cells.push_back({v[0] - 1, v[1] - 1, v[2] - 1, v[3] - 1});
    }
}

}  // namespace mrsv
