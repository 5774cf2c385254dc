// spec: 4.5 fixed-point synthesis, 4.6 accumulator bound.
//
// How the work is organised. None of it changes a result: the lines of one pass
// may go in any order and the sums are exact, so the order of their terms is free
// (spec 4.5, 4.6).
// - At each level the x pass and the y pass go slice by slice (z fixed): a line
//   along y reads only values of its own slice, which the x pass of that slice has
//   just written and which are still in cache.
// - Lines along x are transformed in place one at a time. Lines along y and z are
//   transformed in blocks of neighbouring lines, copied to scratch first, so that
//   each output row of a block is a run of neighbouring values.
// - The interior rows of [P Q] are applied as the two phases of a filter bank,
//   with the interior taps as compile-time constants; the few rows at the ends
//   keep explicit lists of terms.
// - Work whose inputs are all 0 is skipped or reduced: a product with a 0 input
//   adds nothing, and an all-0 sum gives sat((0 + 2^23) >> 24) = 0.
// - Saturation is left out where it provably changes nothing (kSmallInput).
#include "wavelet/synthesis_fixed.h"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <utility>
#include <vector>

#include "wavelet/cdf97.h"
#include "wavelet/level_filters.h"

namespace mrsv::wavelet {
namespace {

constexpr int64_t kHalf = int64_t{1} << (kTapFracBits - 1);

// Inputs in [-2^33, 2^33) cannot give a result beyond kValueLimit: every acc of
// such inputs is within kMaxRowTapSum * 2^33 + 2^23 < kValueLimit * 2^24 (the
// bound of 4.6 with 2^33 for kValueLimit). Inputs are that small unless an encoder
// scales its values close to the limit. For a line or block of small inputs the
// kernels leave out the saturation of their results, and the passes along x
// that of their inputs.
constexpr int64_t kSmallInput = int64_t{1} << 33;
static_assert(kMaxRowTapSum * kSmallInput + kHalf < kValueLimit * (int64_t{1} << kTapFracBits),
              "a row of small inputs could saturate");
// v + 2^33 modulo 2^64: below 2^34 exactly when v is small, and so is the OR of
// such terms exactly when all of them are.
uint64_t smallBits(int64_t v) {
  return static_cast<uint64_t>(v) + static_cast<uint64_t>(kSmallInput);
}
bool isSmall(uint64_t or_of_small_bits) {
  return or_of_small_bits < 2 * static_cast<uint64_t>(kSmallInput);
}

// spec: 4.5 out = sat((acc + 2^23) >> 24), for an acc that started at 2^23; the
// caller may leave out sat for a row of small inputs.
template <bool Saturate = true>
int64_t finish(int64_t acc) {
  return Saturate ? saturate(shiftFloor(acc)) : shiftFloor(acc);
}

// floor(v / 2) and ceil(v / 2) for either sign (C++ division truncates).
int64_t floorHalf(int64_t v) { return v >= 0 ? v / 2 : -((1 - v) / 2); }
int64_t ceilHalf(int64_t v) { return -floorHalf(-v); }

// Why acc cannot overflow (spec 4.6): acc = 2^23 + the sum over the P and Q taps
// of fine row i of tap * value. Each |tap| <= 2^24 and |value| <= 2^35 - 1 (values
// are saturated as they are read), so each product is below 2^59; the taps of one
// row have sum |tap| <= kMaxRowTapSum = 44656268 < 2^25.42 (order 4; the generator
// computes it and a test rechecks it), so every partial sum, in whatever order the
// terms are added, is at most 44656268 * (2^35 - 1) + 2^23 < 2^61 < 2^63. Where two
// terms have taps a and +-a, the kernels add a * (v1 +- v2): the same exact value,
// and |a * (v1 +- v2)| <= |a| |v1| + |a| |v2| keeps every partial sum within the
// same bound. The static_assert in synthesis_fixed.h checks the inequality.

// ---------------------------------------------------------------------------
// The interior filters with constant taps.

// The interior taps of spec 4.2 (the tables of filter_tables.cpp), as constants
// so that the kernels multiply by immediates and shift for powers of two.
// LinePlan compares them with the tables and, should the two ever differ, uses
// the general kernel instead.
template <int K>
struct InteriorTaps;
template <>
struct InteriorTaps<1> {
  static constexpr int32_t p[] = {16777216, 16777216};
  static constexpr int32_t q[] = {16777216, -16777216};
};
template <>
struct InteriorTaps<2> {
  static constexpr int32_t p[] = {8388608, 16777216, 8388608};
  static constexpr int32_t q[] = {1677722, -10066330, 16777216, -10066330, 1677722};
};
template <>
struct InteriorTaps<3> {
  static constexpr int32_t p[] = {4194304, 12582912, 12582912, 4194304};
  static constexpr int32_t q[] = {-55370, 1605740, -8139441, 16777216,
                                  -16777216, 8139441, -1605740, 55370};
};
template <>
struct InteriorTaps<4> {
  static constexpr int32_t p[] = {2097152, 8388608, 12582912, 8388608, 2097152};
  static constexpr int32_t q[] = {-691,      85739,   -1159553, 5465179, -12779282, 16777216,
                                  -12779282, 5465179, -1159553, 85739,   -691};
};
// Interior columns of P and Q both start at fine row 2j - (k - 1) (spec 4.2).
constexpr int interiorFirst(int k) { return 1 - k; }

// One phase of an interior filter: the taps t = E, E + 2, ... of `Taps`. Term n
// (tap t = E + 2n) multiplies the input n places before the first, x[-n * Pitch].
template <const int32_t* Taps, int Count, int E, int Pitch>
struct Phase {
  static constexpr int kTerms = (Count - E + 1) / 2;

  // Term n with its mirror kTerms - 1 - n. In the even orders the interior
  // filters are symmetric and the two taps of a pair are equal, so one product
  // serves both (a pair of opposite taps likewise); otherwise two products.
  template <int N>
  static int64_t pair(const int64_t* x) {
    constexpr int M = kTerms - 1 - N;
    constexpr int64_t a = Taps[E + 2 * N], b = Taps[E + 2 * M];
    if constexpr (N > M) {
      return 0;  // added with its mirror
    } else if constexpr (N == M) {
      return a * x[-N * Pitch];
    } else if constexpr (a == b) {
      return a * (x[-N * Pitch] + x[-M * Pitch]);
    } else if constexpr (a == -b) {
      return a * (x[-N * Pitch] - x[-M * Pitch]);
    } else {
      return a * x[-N * Pitch] + b * x[-M * Pitch];
    }
  }
  template <int... N>
  static int64_t sum(const int64_t* x, std::integer_sequence<int, N...>) {
    return (pair<N>(x) + ... + 0);
  }
  static int64_t sum(const int64_t* x) {
    return sum(x, std::make_integer_sequence<int, kTerms>());
  }
};

// spec: 4.5 interior rows of phase E (E = (i - first) mod 2) of order K, count of
// them: out[k * Step] = sat((2^23 + P part + Q part) >> 24), where the P part
// takes its inputs at p[k - n * Pitch] and the Q part at q[k - n * Pitch]. Without
// WithQ the caller knows every Q input is 0.
template <int K, int E, bool WithQ, bool Saturate, int Pitch, int Step>
void phaseRows(const int64_t* p, const int64_t* q, int64_t* out, size_t count) {
  using T = InteriorTaps<K>;
  using PPhase = Phase<T::p, K + 1, E, Pitch>;
  using QPhase = Phase<T::q, 3 * K - 1, E, Pitch>;
  for (size_t k = 0; k < count; ++k) {
    int64_t acc = kHalf + PPhase::sum(p + k);
    if constexpr (WithQ) acc += QPhase::sum(q + k);
    out[k * Step] = finish<Saturate>(acc);
  }
}

template <int K, bool Saturate, int Pitch, int Step>
void constantRows(int e, bool with_q, const int64_t* p, const int64_t* q, int64_t* out,
                  size_t count) {
  if (e == 0) {
    if (with_q) phaseRows<K, 0, true, Saturate, Pitch, Step>(p, q, out, count);
    else phaseRows<K, 0, false, Saturate, Pitch, Step>(p, q, out, count);
  } else {
    if (with_q) phaseRows<K, 1, true, Saturate, Pitch, Step>(p, q, out, count);
    else phaseRows<K, 1, false, Saturate, Pitch, Step>(p, q, out, count);
  }
}

// ---------------------------------------------------------------------------
// The general kernel: taps and inputs given at run time.

// out[k * Step] = sat((2^23 + sum over t < N of tap[t] * in[t][k]) >> 24), k < count.
template <int N, int Step>
void combine(const int64_t* const* in, const int64_t* tap, int64_t* out, size_t count) {
  const int64_t* p[N];
  int64_t c[N];
  for (int t = 0; t < N; ++t) p[t] = in[t], c[t] = tap[t];
  for (size_t k = 0; k < count; ++k) {
    int64_t acc = kHalf;
    for (int t = 0; t < N; ++t) acc += c[t] * p[t][k];
    out[k * Step] = finish(acc);
  }
}

// combine() for any n: the edge rows, and interior rows with tables unlike InteriorTaps.
template <int Step>
void combineAny(int n, const int64_t* const* in, const int64_t* tap, int64_t* out,
                size_t count) {
  switch (n) {
    case 1: return combine<1, Step>(in, tap, out, count);
    case 2: return combine<2, Step>(in, tap, out, count);
    case 3: return combine<3, Step>(in, tap, out, count);
    case 4: return combine<4, Step>(in, tap, out, count);
    case 5: return combine<5, Step>(in, tap, out, count);
    case 6: return combine<6, Step>(in, tap, out, count);
    case 7: return combine<7, Step>(in, tap, out, count);
    case 8: return combine<8, Step>(in, tap, out, count);
    case 9: return combine<9, Step>(in, tap, out, count);
    default:
      for (size_t k = 0; k < count; ++k) {
        int64_t acc = kHalf;
        for (int t = 0; t < n; ++t) acc += tap[t] * in[t][k];
        out[k * Step] = finish(acc);
      }
  }
}

// ---------------------------------------------------------------------------
// The rows of one pass.

// One term of an edge row: tap * (value `input` of the line).
struct Term {
  uint32_t input;
  int32_t tap;
};

// Room for the terms of any row: the rows of the tables have at most 9 (order 4),
// the interior rows at most ceil((k + 1) / 2) + ceil((3k - 1) / 2).
constexpr int kMaxTerms = 16;

// One pass of spec 4.5 over lines of fine() values, seen as the rows of the
// matrix [P Q] (4.3). The input of a line is v[0 .. coarse) (the P columns) then
// v[coarse .. fine) (the Q columns). A row i in [lo, hi) is interior: only
// interior columns reach it, so with h = i - first its taps are the interior
// taps t = h mod 2, h mod 2 + 2, ... on column (h - t) / 2: the same taps for
// every row of one parity (the two phases of the filter bank). The rows outside
// [lo, hi), a handful at each end where the boundary columns of 4.3 are, keep an
// explicit list of terms, as do all rows should the tables have more than
// kMaxTerms in an interior row.
struct LinePlan {
  int order = 0;
  uint32_t fine = 0, coarse = 0;
  uint32_t lo = 0, hi = 0;
  int p_first = 0, p_count = 0, q_first = 0, q_count = 0;
  const int32_t* p_taps = nullptr;
  const int32_t* q_taps = nullptr;
  bool constant_taps = false;        // the tables' interior filters are InteriorTaps<order>
  std::vector<uint32_t> edge_rows;   // increasing
  std::vector<uint32_t> edge_begin;  // terms of edge_rows[r]: [edge_begin[r], edge_begin[r + 1])
  std::vector<Term> terms;

  LinePlan() = default;
  explicit LinePlan(const LevelFilters& f);

  // The inputs [*a, *b] of the P columns, and [*c, *d] of the Q columns, that
  // reach the interior rows [r0, r1).
  void windows(uint32_t r0, uint32_t r1, uint32_t* a, uint32_t* b, uint32_t* c,
               uint32_t* d) const {
    *a = static_cast<uint32_t>(ceilHalf(int64_t{r0} - p_first - p_count + 1));
    *b = static_cast<uint32_t>(floorHalf(int64_t{r1} - 1 - p_first));
    *c = coarse + static_cast<uint32_t>(ceilHalf(int64_t{r0} - q_first - q_count + 1));
    *d = coarse + static_cast<uint32_t>(floorHalf(int64_t{r1} - 1 - q_first));
  }

  // Interior row i: the phase of its P taps (that of its Q taps is the same with
  // constant_taps), and the inputs of its first P and first Q term.
  int phase(uint32_t i) const { return static_cast<int>((int64_t{i} - p_first) & 1); }
  uint32_t firstP(uint32_t i) const {
    return static_cast<uint32_t>((int64_t{i} - p_first - phase(i)) / 2);
  }
  uint32_t firstQ(uint32_t i) const {
    const int64_t h = int64_t{i} - q_first;
    return coarse + static_cast<uint32_t>((h - (h & 1)) / 2);
  }

  // The terms of interior row i for the general kernel: input u[t] (P terms
  // first), tap[t]; *np of them are P terms. Returns the number of terms.
  int rowTerms(uint32_t i, uint32_t* u, int64_t* tap, int* np) const {
    const int64_t hp = int64_t{i} - p_first, hq = int64_t{i} - q_first;
    int n = 0;
    for (int t = static_cast<int>(hp & 1); t < p_count; t += 2, ++n) {
      u[n] = static_cast<uint32_t>((hp - t) / 2);
      tap[n] = p_taps[t];
    }
    *np = n;
    for (int t = static_cast<int>(hq & 1); t < q_count; t += 2, ++n) {
      u[n] = coarse + static_cast<uint32_t>((hq - t) / 2);
      tap[n] = q_taps[t];
    }
    return n;
  }
};

template <int K>
bool matchesInteriorTaps(const OrderFilters& of) {
  using T = InteriorTaps<K>;
  static_assert(std::size(T::p) == K + 1 && std::size(T::q) == 3 * K - 1, "spec 4.2 counts");
  if (of.p_interior_count != K + 1 || of.q_interior_count != 3 * K - 1 ||
      of.p_interior_first != interiorFirst(K) || of.q_interior_first != interiorFirst(K))
    return false;
  return std::equal(std::begin(T::p), std::end(T::p), of.p_interior_fixed) &&
         std::equal(std::begin(T::q), std::end(T::q), of.q_interior_fixed);
}

LinePlan::LinePlan(const LevelFilters& f) {
  const OrderFilters& of = f.filters();
  order = of.order;
  fine = f.fine();
  coarse = f.coarse();
  p_first = of.p_interior_first;
  p_count = of.p_interior_count;
  p_taps = of.p_interior_fixed;
  q_first = of.q_interior_first;
  q_count = of.q_interior_count;
  q_taps = of.q_interior_fixed;
  switch (order) {
    case 1: constant_taps = matchesInteriorTaps<1>(of); break;
    case 2: constant_taps = matchesInteriorTaps<2>(of); break;
    case 3: constant_taps = matchesInteriorTaps<3>(of); break;
    default: constant_taps = matchesInteriorTaps<4>(of); break;
  }
  const uint32_t wavelets = f.wavelets();
  const uint32_t nbp = static_cast<uint32_t>(of.p_boundary);
  const uint32_t nbq = static_cast<uint32_t>(of.q_boundary);

  // Edge rows: those a boundary column reaches, and those whose interior formula
  // would take a column that is not interior (or not there).
  std::vector<uint8_t> edge(fine, 0);
  auto mark = [&](const Column& c) {
    for (int r = 0; r < c.count; ++r) edge[c.first_row + r] = 1;
  };
  for (uint32_t j = 0; j < coarse; ++j)
    if (j < nbp || j >= coarse - nbp) mark(f.p(j));
  for (uint32_t j = 0; j < wavelets; ++j)
    if (j < nbq || j >= wavelets - nbq) mark(f.q(j));
  auto leaves = [](int64_t h, int count, uint32_t nb, uint32_t columns) {
    return ceilHalf(h - count + 1) < int64_t{nb} || floorHalf(h) >= int64_t{columns} - nb;
  };
  for (uint32_t i = 0; i < fine; ++i)
    if (leaves(int64_t{i} - p_first, p_count, nbp, coarse) ||
        leaves(int64_t{i} - q_first, q_count, nbq, wavelets))
      edge[i] = 1;
  // The interior rows are one run; should they not be, every row is an edge row.
  while (lo < fine && edge[lo]) ++lo;
  hi = lo;
  while (hi < fine && !edge[hi]) ++hi;
  if (std::find(edge.begin() + hi, edge.end(), 0) != edge.end() ||
      (p_count + 1) / 2 + (q_count + 1) / 2 > kMaxTerms)
    lo = hi = 0;

  struct Entry {
    uint32_t row;
    Term term;
  };
  std::vector<Entry> entries;
  auto collect = [&](const Column& c, uint32_t input) {
    for (int r = 0; r < c.count; ++r) {
      const uint32_t row = c.first_row + r;
      if (row < lo || row >= hi) entries.push_back({row, {input, c.fixed[r]}});
    }
  };
  for (uint32_t j = 0; j < coarse; ++j) collect(f.p(j), j);
  for (uint32_t j = 0; j < wavelets; ++j) collect(f.q(j), coarse + j);
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b) { return a.row < b.row; });
  for (size_t e = 0; e < entries.size(); ++e) {
    if (e == 0 || entries[e].row != entries[e - 1].row) {
      edge_rows.push_back(entries[e].row);
      edge_begin.push_back(static_cast<uint32_t>(e));
    }
    terms.push_back(entries[e].term);
  }
  edge_begin.push_back(static_cast<uint32_t>(terms.size()));
}

// Interior row i over `count` positions k: input u at position k is
// in[u * Pitch + k], the result goes to out[k * Step]. Without with_q the caller
// knows every Q input of the row is 0; with `small` that every input is small.
template <int K, int Pitch, int Step>
void interiorRow(const LinePlan& lp, uint32_t i, bool with_q, bool small, const int64_t* in,
                 int64_t* out, size_t count) {
  if (lp.constant_taps) {
    const int64_t* p = in + size_t{lp.firstP(i)} * Pitch;
    const int64_t* q = in + size_t{lp.firstQ(i)} * Pitch;
    if (small) constantRows<K, false, Pitch, Step>(lp.phase(i), with_q, p, q, out, count);
    else constantRows<K, true, Pitch, Step>(lp.phase(i), with_q, p, q, out, count);
    return;
  }
  uint32_t u[kMaxTerms];
  int64_t tap[kMaxTerms];
  const int64_t* ptr[kMaxTerms];
  int np;
  const int n = lp.rowTerms(i, u, tap, &np);
  for (int t = 0; t < n; ++t) ptr[t] = in + size_t{u[t]} * Pitch;
  combineAny<Step>(with_q ? n : np, ptr, tap, out, count);
}

// Scratch of the passes, kept from line to line.
struct Scratch {
  std::vector<int64_t> line, block;  // saturated input values
  std::vector<uint32_t> line_nonzero, block_nonzero, count;
};

template <class T>
T* atLeast(std::vector<T>* v, size_t n) {
  if (v->size() < n) v->resize(n);
  return v->data();
}

// Lines along x: rows are processed in chunks of this many, so that the work of
// a chunk whose Q inputs are all 0 (most of them at low rates) can be reduced.
constexpr uint32_t kChunkRows = 32;

// spec: 4.5 one pass along x over one line, in place: `line` holds fine() values.
template <int K>
void rowPass(const LinePlan& lp, int64_t* line, Scratch* s) {
  const uint32_t fine = lp.fine;
  int64_t* in = atLeast(&s->line, fine);
  uint32_t* nz = atLeast(&s->line_nonzero, fine + 1);  // nz[u]: nonzero inputs before u
  uint32_t count = 0;
  uint64_t bits = 0;
  for (uint32_t u = 0; u < fine; ++u) {
    const int64_t v = line[u];
    in[u] = v;
    nz[u] = count;
    count += v != 0;
    bits |= smallBits(v);
  }
  nz[fine] = count;
  // Inputs are saturated as they are read (a no-op for conforming input) so that
  // the bound of 4.6 holds for any data a caller passes in; small ones need not be.
  const bool small = isSmall(bits);
  if (!small)
    for (uint32_t u = 0; u < fine; ++u) in[u] = saturate(in[u]);
  if (count == 0) return;  // all 0 in, all 0 out
  for (size_t r = 0; r + 1 < lp.edge_begin.size(); ++r) {
    int64_t acc = kHalf;
    for (uint32_t e = lp.edge_begin[r]; e < lp.edge_begin[r + 1]; ++e)
      acc += int64_t{lp.terms[e].tap} * in[lp.terms[e].input];
    line[lp.edge_rows[r]] = finish(acc);
  }
  for (uint32_t r0 = lp.lo; r0 < lp.hi; r0 += kChunkRows) {
    const uint32_t r1 = std::min(lp.hi, r0 + kChunkRows);
    uint32_t pa, pb, qa, qb;
    lp.windows(r0, r1, &pa, &pb, &qa, &qb);
    const bool with_q = nz[qb + 1] != nz[qa];
    if (!with_q && nz[pb + 1] == nz[pa]) {
      std::fill(line + r0, line + r1, 0);
      continue;
    }
    // The rows of one parity share their taps, and row i + 2 reads the inputs of
    // row i moved by one: r0, r0 + 2, ..., then r0 + 1, r0 + 3, ...
    interiorRow<K, 1, 2>(lp, r0, with_q, small, in, line + r0, (r1 - r0 + 1) / 2);
    if (r1 - r0 > 1)
      interiorRow<K, 1, 2>(lp, r0 + 1, with_q, small, in, line + r0 + 1, (r1 - r0) / 2);
  }
}

// Neighbouring lines along y or z, transformed together: `rows` runs of `width`
// lines; line x of run r holds its fine() values at base[u * stride + r *
// row_stride + x].
struct Block {
  int64_t* base;
  size_t stride, row_stride;
  uint32_t rows, width;
};

// A run of a block is cut into segments of at most Segment lines (64, or 16 for
// narrow blocks and long lines). In scratch, segment g holds input u of its
// lines at in[(g * fine + u) * Segment + x], and the zero tests are made per
// segment.
constexpr uint32_t kWideSegment = 64, kNarrowSegment = 16;
// A block's scratch holds about this many bytes (and at least one segment).
constexpr size_t kBlockBytes = size_t{1} << 20;

// spec: 4.5 one pass along y or z over a block of lines, in place. With
// `Saturated` the caller knows the inputs are outputs of an earlier pass of this
// level (which covered the whole box), already in [-kValueLimit, kValueLimit].
template <int K, bool Saturated, uint32_t Segment>
void blockPass(const LinePlan& lp, const Block& b, Scratch* s) {
  const uint32_t fine = lp.fine;
  const uint32_t segments = (b.width + Segment - 1) / Segment;  // per run
  const size_t groups = size_t{b.rows} * segments;
  auto segmentStart = [&](uint32_t sg) { return sg * b.width / segments; };
  int64_t* in = atLeast(&s->block, groups * fine * Segment);
  // nz[g * (fine + 1) + u]: inputs before u that are nonzero in segment g.
  uint32_t* nz = atLeast(&s->block_nonzero, groups * (fine + 1));
  uint32_t* count = atLeast(&s->count, groups);
  std::fill(count, count + groups, 0);
  uint64_t bits = 0;
  for (uint32_t u = 0; u < fine; ++u) {
    for (uint32_t r = 0; r < b.rows; ++r) {
      const int64_t* src = b.base + u * b.stride + r * b.row_stride;
      for (uint32_t sg = 0; sg < segments; ++sg) {
        const size_t g = size_t{r} * segments + sg;
        const uint32_t x0 = segmentStart(sg), x1 = segmentStart(sg + 1);
        const int64_t* from = src + x0;
        int64_t* dst = in + (g * fine + u) * Segment;
        int64_t any = 0;
        for (uint32_t x = 0; x < x1 - x0; ++x) {
          const int64_t v = Saturated ? from[x] : saturate(from[x]);  // as in rowPass
          dst[x] = v;
          any |= v;
          bits |= smallBits(v);
        }
        nz[g * (fine + 1) + u] = count[g];
        count[g] += any != 0;
      }
    }
  }
  uint32_t total = 0;
  for (size_t g = 0; g < groups; ++g) {
    nz[g * (fine + 1) + fine] = count[g];
    total += count[g];
  }
  if (total == 0) return;  // all 0 in, all 0 out
  const bool small = isSmall(bits);

  for (size_t e = 0; e + 1 < lp.edge_begin.size(); ++e) {
    const uint32_t first = lp.edge_begin[e];
    const int n = static_cast<int>(lp.edge_begin[e + 1] - first);
    for (uint32_t r = 0; r < b.rows; ++r)
      for (uint32_t sg = 0; sg < segments; ++sg) {
        const size_t g = size_t{r} * segments + sg;
        const int64_t* seg = in + g * fine * Segment;
        const uint32_t* z = nz + g * (fine + 1);
        const uint32_t x0 = segmentStart(sg), x1 = segmentStart(sg + 1);
        int64_t* out = b.base + lp.edge_rows[e] * b.stride + r * b.row_stride + x0;
        if (n > kMaxTerms) {  // not in the tables; for completeness
          for (uint32_t x = 0; x < x1 - x0; ++x) {
            int64_t acc = kHalf;
            for (int t = 0; t < n; ++t)
              acc += int64_t{lp.terms[first + t].tap} *
                     seg[size_t{lp.terms[first + t].input} * Segment + x];
            out[x] = finish(acc);
          }
          continue;
        }
        // The terms whose input is nonzero somewhere in the segment.
        const int64_t* ptr[kMaxTerms];
        int64_t tap[kMaxTerms];
        int m = 0;
        for (int t = 0; t < n; ++t) {
          const uint32_t u = lp.terms[first + t].input;
          if (z[u + 1] == z[u]) continue;
          ptr[m] = seg + size_t{u} * Segment;
          tap[m++] = lp.terms[first + t].tap;
        }
        if (m == 0) std::fill(out, out + (x1 - x0), 0);
        else combineAny<1>(m, ptr, tap, out, x1 - x0);
      }
  }
  for (uint32_t i = lp.lo; i < lp.hi; ++i) {
    uint32_t pa, pb, qa, qb;
    lp.windows(i, i + 1, &pa, &pb, &qa, &qb);
    for (uint32_t r = 0; r < b.rows; ++r) {
      for (uint32_t sg = 0; sg < segments; ++sg) {
        const size_t g = size_t{r} * segments + sg;
        const uint32_t* z = nz + g * (fine + 1);
        const bool with_q = z[qb + 1] != z[qa];
        const uint32_t x0 = segmentStart(sg), x1 = segmentStart(sg + 1);
        int64_t* out = b.base + i * b.stride + r * b.row_stride + x0;
        if (!with_q && z[pb + 1] == z[pa]) {
          std::fill(out, out + (x1 - x0), 0);
          continue;
        }
        interiorRow<K, Segment, 1>(lp, i, with_q, small, in + g * fine * Segment, out, x1 - x0);
      }
    }
  }
}

// The passes for the order of the line plan.
void synthesizeRow(const LinePlan& lp, int64_t* line, Scratch* s) {
  switch (lp.order) {
    case 1: return rowPass<1>(lp, line, s);
    case 2: return rowPass<2>(lp, line, s);
    case 3: return rowPass<3>(lp, line, s);
    default: return rowPass<4>(lp, line, s);
  }
}
template <bool Saturated, uint32_t Segment>
void synthesizeBlock(const LinePlan& lp, const Block& b, Scratch* s) {
  switch (lp.order) {
    case 1: return blockPass<1, Saturated, Segment>(lp, b, s);
    case 2: return blockPass<2, Saturated, Segment>(lp, b, s);
    case 3: return blockPass<3, Saturated, Segment>(lp, b, s);
    default: return blockPass<4, Saturated, Segment>(lp, b, s);
  }
}
void synthesizeBlock(bool saturated, uint32_t segment, const LinePlan& lp, const Block& b,
                     Scratch* s) {
  if (segment == kWideSegment) {
    if (saturated) synthesizeBlock<true, kWideSegment>(lp, b, s);
    else synthesizeBlock<false, kWideSegment>(lp, b, s);
  } else {
    if (saturated) synthesizeBlock<true, kNarrowSegment>(lp, b, s);
    else synthesizeBlock<false, kNarrowSegment>(lp, b, s);
  }
}

// The blocks of a pass along y or z over lines of `fine` values: segments of
// `segment` lines, `width` lines per run and `rows` runs (at most max_rows), so
// that the scratch holds about kBlockBytes (and at least one segment).
struct BlockShape {
  uint32_t segment, width, rows;
};
BlockShape blockShape(uint32_t fine, uint32_t max_width, uint32_t max_rows) {
  const size_t lines = kBlockBytes / (size_t{fine} * sizeof(int64_t));
  const uint32_t segment =
      lines >= kWideSegment && max_width >= kWideSegment / 2 ? kWideSegment : kNarrowSegment;
  const size_t segments_fit = std::max<size_t>(1, lines / segment);
  const uint32_t width =
      static_cast<uint32_t>(std::min<size_t>(max_width, segments_fit * segment));
  const size_t segments_per_run = (width + segment - 1) / segment;
  const uint32_t rows = static_cast<uint32_t>(
      std::max<size_t>(1, std::min<size_t>(max_rows, segments_fit / segments_per_run)));
  return {segment, width, rows};
}

// spec: 4.5 the passes of one level, x then y then z, over the box of that level.
void synthesizeLevel(const GridPlan& plan, int level, int64_t* data, Scratch* scratch) {
  const size_t stride[3] = {1, size_t{plan.axis[0].size(0)},
                            size_t{plan.axis[0].size(0)} * plan.axis[1].size(0)};
  uint32_t box[3];
  bool split[3];
  LinePlan lp[3];
  for (int a = 0; a < 3; ++a) {
    const AxisPlan& axis = plan.axis[a];
    box[a] = axis.size(level - 1);
    split[a] = axis.levels >= level;
    if (split[a]) lp[a] = LinePlan(LevelFilters(axis.order, axis.intervals(level)));
  }
  if (split[0] || split[1]) {
    const BlockShape shape = split[1] ? blockShape(lp[1].fine, box[0], 1) : BlockShape{};
    for (uint32_t z = 0; z < box[2]; ++z) {
      int64_t* slice = data + z * stride[2];
      if (split[0])
        for (uint32_t y = 0; y < box[1]; ++y) synthesizeRow(lp[0], slice + y * stride[1], scratch);
      if (split[1])
        for (uint32_t x = 0; x < box[0]; x += shape.width)
          synthesizeBlock(split[0], shape.segment, lp[1],
                          {slice + x, stride[1], 0, 1, std::min(shape.width, box[0] - x)},
                          scratch);
    }
  }
  if (split[2]) {
    const BlockShape shape = blockShape(lp[2].fine, box[0], box[1]);
    for (uint32_t y = 0; y < box[1]; y += shape.rows)
      for (uint32_t x = 0; x < box[0]; x += shape.width)
        synthesizeBlock(split[0] || split[1], shape.segment, lp[2],
                        {data + y * stride[1] + x, stride[2], stride[1],
                         std::min(shape.rows, box[1] - y), std::min(shape.width, box[0] - x)},
                        scratch);
  }
}

}  // namespace

// spec: 4.5
void synthesizeFixed(const GridPlan& plan, int64_t* data, int stop_level, int start_level) {
  if (!isValidGridPlan(plan)) return;
  if (isCdf97(plan.axis[0].order)) return synthesizeFixedCdf97(plan, data, stop_level, start_level);
  if (stop_level < 0) stop_level = 0;
  Scratch scratch;
  for (int level = std::min(plan.maxLevels(), start_level); level > stop_level; --level)
    synthesizeLevel(plan, level, data, &scratch);
}

}  // namespace mrsv::wavelet
