// spec: 7.6.1 the link of a vertex and its rotations, as a decoded split needs them.
#include "tetmesh/star_link.h"

#include <algorithm>
#include <cstddef>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mrsv {

// A repeated edge (no manifold) keeps its first triangle, as
// Link::triangleFrom finds it.
inline void StarLink::insertHashed(uint32_t a, uint32_t b, uint32_t third, uint32_t f) {
  const uint64_t key = (uint64_t{a} << 32) | b;
  uint32_t e = slotOf(key);
  while (edge_key_[e] != kEmpty && edge_key_[e] != key) e = (e + 1) & mask_;
  if (edge_key_[e] == key) return;
  edge_key_[e] = key;
  edge_triangle_[e] = f;
  edge_third_[e] = third;
}

// The directed edges of a link too large for dense_: a hash table at most
// half full.
void StarLink::buildHashed() {
  const uint32_t faces = static_cast<uint32_t>(triangles.size());
  uint32_t capacity = 16;
  shift_ = 60;
  while (capacity < 6 * faces) capacity *= 2, --shift_;
  mask_ = capacity - 1;
  edge_key_.assign(capacity, kEmpty);
  edge_triangle_.resize(capacity);
  edge_third_.resize(capacity);
  for (uint32_t f = 0; f < faces; ++f) {
    const auto& t = triangles[f];
    insertHashed(t[0], t[1], t[2], f);
    insertHashed(t[1], t[2], t[0], f);
    insertHashed(t[2], t[0], t[1], f);
  }
}

void StarLink::build(const TetComplex& mesh, uint32_t v) {
  center = v;
  const IncidenceLists::View star = mesh.incident.of(v);
  const uint32_t faces = star.size();
  // The decoder adds a vertex per split: grown by half at a time, the
  // table is not resized (and its new entries filled) at every split.
  if (tag_of_.size() < mesh.positions.size())
    tag_of_.resize(std::max(mesh.positions.size(), tag_of_.size() + tag_of_.size() / 2), 0);
  if (dense_.empty()) dense_.assign(kDense * kDense, 0);
  if (++stamp_ == 0) {
    std::fill(tag_of_.begin(), tag_of_.end(), 0);
    stamp_ = 1;
  }
  if (++edge_stamp_ == 1u << 16) {
    std::fill(dense_.begin(), dense_.end(), 0);
    edge_stamp_ = 1;
  }
  triangles.resize(faces);
  triangle_tet.resize(faces);
  // Collected in gathered_, which only grows: resizing `vertices` up to
  // 3 * faces and back down at every split filled it each time.
  if (gathered_.size() < 3 * size_t{faces}) gathered_.resize(3 * size_t{faces});
  // One pass over the star: each tet's link triangle (7.6.1), its corners
  // numbered as first met, and its directed edges in dense_ while the link
  // fits it. Raw pointers: through the vectors the compiler reloads every
  // base pointer after each store.
  uint32_t* gathered = gathered_.data();
  uint64_t* tag_of = tag_of_.data();
  uint32_t* dense = dense_.data();
  std::array<uint32_t, 3>* tris = triangles.data();
  uint32_t* tet_of = triangle_tet.data();
  const Tet* tets = mesh.tets.data();
  const uint64_t stamp = uint64_t{stamp_} << 32;
  bool fits = faces <= kDenseFaces;
  // A link is connected (7.3): it has at most faces + 2 vertices; when it
  // is not (a broken stream), m outgrows the row and the hashed table takes it.
  const uint32_t shift = faces + 2 <= 64 ? 6 : 7;
  const uint32_t row_width = 1u << shift;
  dense_shift_ = shift;
  uint32_t m = 0;
  // The star's tets lie anywhere in the mesh (most first-level cache
  // misses of a split): asked for all at once, they arrive together, where
  // the loop below, about 100 instructions a tet, waited for them one or
  // two at a time (perf: 40 % of the build's time on the first use of the tet).
  for (uint32_t f = 0; f < faces; ++f) __builtin_prefetch(&tets[star[f]]);
  // First each tet's link triangle as vertex numbers (7.6.1), in tris,
  // asking for their entries in tag_of_ on the way, then their local
  // numbers: the entries of a link's 17 or so vertices, a random 8 bytes
  // each in a table per vertex number, come in together rather than one by one.
  for (uint32_t f = 0; f < faces; ++f) {
    const uint32_t slot = star[f];
    tet_of[f] = slot;
    const Tet& t = tets[slot];
    const int at = cornerOf(t, v);
    for (int j = 0; j < 3; ++j) {
      const uint32_t u = t[kLinkOrder[at][j]];
      tris[f][j] = u;
      __builtin_prefetch(&tag_of[u]);
    }
  }
  for (uint32_t f = 0; f < faces; ++f) {
    uint32_t l[3];
    for (int j = 0; j < 3; ++j) {
      // Whether u is met for the first time cannot be predicted either:
      // u's entry is written and gathered_ extended either way, and m
      // counts it only when it is new (cachegrind: 24 mispredictions per
      // split less on the CT crop). One 64-bit entry (stamp, local) per
      // vertex number: one cache line where two arrays took two.
      const uint32_t u = tris[f][j];
      const uint64_t entry = tag_of[u];
      const bool fresh = (entry & ~uint64_t{0xFFFFFFFF}) != stamp;
      const uint32_t local = fresh ? m : static_cast<uint32_t>(entry);
      tag_of[u] = stamp | local;
      gathered[m] = u;
      m += fresh;
      l[j] = local;
    }
    tris[f] = {l[0], l[1], l[2]};
    if (fits && m <= row_width) {
      const uint32_t tag = edge_stamp_;
      dense[l[0] << shift | l[1]] = denseEntry(tag, f, l[2]);
      dense[l[1] << shift | l[2]] = denseEntry(tag, f, l[0]);
      dense[l[2] << shift | l[0]] = denseEntry(tag, f, l[1]);
    } else {
      fits = false;
    }
  }
  vertices.assign(gathered, gathered + m);
  // cut() and the split read the positions and values of the link's
  // vertices: asked for now, they come while the cut is decoded.
  const Point3i* positions = mesh.positions.data();
  for (uint32_t p = 0; p < m; ++p) __builtin_prefetch(&positions[gathered[p]]);
  if (mesh.field_count > 0) {
    const int32_t* scalars = mesh.scalars.data();
    for (uint32_t p = 0; p < m; ++p) __builtin_prefetch(&scalars[size_t{gathered[p]} * mesh.field_count]);
  }
  dense_used_ = fits;
  if (!dense_used_) buildHashed();
  // spec 7.3: every level's links are spheres or disks, and a sphere on m
  // vertices has exactly 2m - 4 triangles, a disk fewer: only a link with
  // another count can have a boundary edge, and only then are its edges
  // scanned for one.
  has_boundary = false;
  if (uint64_t{faces} + 4 != 2 * uint64_t{m}) {
    on_boundary.assign(m, 0);
    for (const auto& tri : triangles)
      for (int j = 0; j < 3; ++j) {
        const uint32_t a = tri[j], b = tri[(j + 1) % 3];
        if (find(b, a) == kNone) {
          on_boundary[a] = on_boundary[b] = 1;
          has_boundary = true;
        }
      }
  }
}

uint32_t StarLink::localOfRank(uint32_t r) const {
  // The vertex with r smaller ones, counted without branches on the data:
  // nth_element's comparisons mispredicted 21 times per split on the CT
  // crop (cachegrind). Where SSE2 is there, the counts of four candidates
  // at a time, each vertex compared with all four at once (vertex numbers
  // are below 2^28: signed comparisons order them): 540 -> 465
  // instructions per split on the CT crop (callgrind).
  const uint32_t m = static_cast<uint32_t>(vertices.size());
  const uint32_t* v = vertices.data();
  uint32_t i = 0;
#if defined(__SSE2__)
  const __m128i wanted = _mm_set1_epi32(static_cast<int>(r));
  for (; i + 4 <= m; i += 4) {
    const __m128i candidates = _mm_loadu_si128(reinterpret_cast<const __m128i*>(v + i));
    __m128i smaller = _mm_setzero_si128();
    for (uint32_t j = 0; j < m; ++j)  // each smaller one subtracts -1
      smaller = _mm_sub_epi32(smaller, _mm_cmplt_epi32(_mm_set1_epi32(static_cast<int>(v[j])), candidates));
    const int hit = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(smaller, wanted)));
    if (hit != 0) return i + static_cast<uint32_t>(__builtin_ctz(static_cast<unsigned>(hit)));
  }
#endif
  for (; i < m; ++i) {
    uint32_t smaller = 0;
    for (uint32_t j = 0; j < m; ++j) smaller += v[j] < v[i];
    if (smaller == r) return i;
  }
  return 0;
}

void StarLink::boundaryVertices(std::vector<uint32_t>* out) const {
  out->clear();
  if (!has_boundary) return;
  for (uint32_t p = 0; p < vertices.size(); ++p)
    if (on_boundary[p]) out->push_back(p);
  // By ascending vertex number. The few of a link (a handful) are placed by
  // their ranks, counted without branches: insertion sort's comparisons
  // mispredicted (perf on the hand: 3 % of the decoding time).
  const size_t n = out->size();
  if (n > 64) {
    std::sort(out->begin(), out->end(), [&](uint32_t a, uint32_t b) { return vertices[a] < vertices[b]; });
    return;
  }
  uint32_t local[64], number[64];
  for (size_t i = 0; i < n; ++i) number[i] = vertices[local[i] = (*out)[i]];
  for (size_t i = 0; i < n; ++i) {
    uint32_t rank = 0;
    for (size_t j = 0; j < n; ++j) rank += number[j] < number[i];
    (*out)[rank] = local[i];
  }
}

bool StarLink::rotationFromLowest(uint32_t p, std::vector<uint32_t>* out) const {
  // Around an interior p (where cut() asks) its neighbours form one cycle
  // of next(p, .): the cycle from any neighbour, turned to start at the
  // smallest vertex number, is the rotation from there (one walk, not a
  // walk to find the smallest and another from it).
  uint32_t first = UINT32_MAX;
  for (uint32_t f = 0; f < triangles.size() && first == UINT32_MAX; ++f)
    for (int j = 0; j < 3; ++j)
      if (triangles[f][j] == p) first = triangles[f][(j + 1) % 3];
  if (first == UINT32_MAX || !rotation(p, first, out)) return false;
  size_t lowest = 0;
  for (size_t i = 1; i < out->size(); ++i)
    if (vertices[(*out)[i]] < vertices[(*out)[lowest]]) lowest = i;
  std::rotate(out->begin(), out->begin() + static_cast<std::ptrdiff_t>(lowest), out->end());
  return true;
}

uint32_t StarLink::rotationInto(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
  if (has_boundary && on_boundary[p]) return rotation(p, start, out) ? static_cast<uint32_t>(out->size()) : 0;
  // As rotation(): the cycle of next(p, .) from start back to start, no
  // neighbour twice.
  const uint32_t m = static_cast<uint32_t>(vertices.size());
  if (out->size() < m) out->resize(m);
  uint32_t* r = out->data();
  uint32_t n = 0, x = start;
  if (dense_used_) {
    // p's row of the table and the stamp in registers: through find() both
    // were loaded again at every step, after each store to `out`.
    const uint32_t* row = dense_.data() + (size_t{p} << dense_shift_);
    const uint32_t stamp = edge_stamp_;
    do {
      const uint32_t e = row[x];
      if ((e >> 16) != stamp || n == m) return 0;
      r[n++] = x;
      x = e & 0xFF;
    } while (x != start);
    return n;
  }
  do {
    const uint32_t e = find(p, x);
    if (e == kNone || n == m) return 0;
    r[n++] = x;
    x = thirdOf(e);
  } while (x != start);
  return n;
}

uint32_t StarLink::rotationFromLowestInto(uint32_t p, std::vector<uint32_t>* out) const {
  // As rotationFromLowest().
  uint32_t first = UINT32_MAX;
  for (uint32_t f = 0; f < triangles.size() && first == UINT32_MAX; ++f)
    for (int j = 0; j < 3; ++j)
      if (triangles[f][j] == p) first = triangles[f][(j + 1) % 3];
  if (first == UINT32_MAX) return 0;
  const uint32_t n = rotationInto(p, first, out);
  if (n == 0) return 0;
  uint32_t* r = out->data();
  uint32_t lowest = 0;
  for (uint32_t i = 1; i < n; ++i) lowest = vertices[r[i]] < vertices[r[lowest]] ? i : lowest;
  std::rotate(r, r + lowest, r + n);
  return n;
}

bool StarLink::rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
  out->clear();
  const size_t m = vertices.size();
  if (!has_boundary || !on_boundary[p]) {
    // The cycle of next(p, .) from start back to start; no neighbour twice.
    uint32_t x = start;
    while (true) {
      const uint32_t e = find(p, x);
      if (e == kNone) return false;
      out->push_back(x);
      x = thirdOf(e);
      if (x == start) return true;
      if (out->size() >= m) return false;
    }
  }
  // A boundary p: back from any neighbour to the x with p -> x a boundary
  // edge (no triangle holds x -> p), then forward to the fan's other end.
  uint32_t x = UINT32_MAX;
  for (const auto& tri : triangles) {
    for (int j = 0; j < 3 && x == UINT32_MAX; ++j)
      if (tri[j] == p) x = tri[(j + 1) % 3];
    if (x != UINT32_MAX) break;
  }
  if (x == UINT32_MAX) return false;
  for (size_t steps = 0;; ++steps) {
    const uint32_t e = find(x, p);
    if (e == kNone) break;
    if (steps >= m) return false;  // a closed fan: p has no boundary edge
    x = thirdOf(e);
  }
  while (true) {
    out->push_back(x);
    const uint32_t e = find(p, x);
    if (e == kNone) return out->size() >= 2;
    if (out->size() > m) return false;
    x = thirdOf(e);
  }
}

}  // namespace mrsv
