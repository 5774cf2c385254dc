// The cells' worst samples in a max-heap indexed by cell, as the greedy
// insertion of spec 8.5 needs it: the worst sample of all (largest error,
// then smallest sample index), with each cell's entry replaced in place when
// the cell changes, so that the heap holds one entry per cell and never a
// stale one.
#pragma once

#include <cstdint>
#include <cstring>
#include <new>
#include <unordered_map>
#include <vector>

namespace mrsv::reconstruct {

// An error num / den (den > 0) at a sample.
struct Candidate {
  __int128 num = 0;
  int64_t den = 1;
  uint64_t sample = 0;
};

// Larger error first, then the smaller sample index: spec 8.5's order.
inline bool worse(const Candidate& a, const Candidate& b) {
  const __int128 l = a.num * b.den, r = b.num * a.den;
  if (l != r) return l > r;
  return a.sample < b.sample;
}

class CandidateQueue {
 public:
  static constexpr uint32_t kAbsent = UINT32_MAX;

  void clear() {
    heap_.assign(kRoot, Entry{});
    pos_.clear();
    inexact_.clear();
  }
  bool empty() const { return heap_.size() <= kRoot; }
  uint32_t top() const { return heap_[kRoot].cell(); }
  // The sample of the top entry, from the heap array when the entry carries it.
  uint64_t topSample() const {
    const Entry& e = heap_[kRoot];
    return e.tie & kInexact ? inexact_.at(e.cell()).sample : kMaxTie - (e.tie >> 32);
  }

  // Sets (or replaces) the entry of `cell`.
  void set(uint32_t cell, const Candidate& c) {
    grow(cell);
    const bool exact = c.num < kExactNum && c.den < kExactDen && c.sample <= kMaxTie;
    // (An exact entry carries all it needs; an inexact one's candidate is
    // kept aside, and a cell's stale one is overwritten or never read.)
    if (!exact) inexact_[cell] = c;
    // (An exact num converts from 64 bits, without the 128-bit library call.)
    const double num = exact ? double(int64_t(c.num)) : double(c.num);
    const double key = num / double(c.den);
    uint64_t bits;
    std::memcpy(&bits, &key, sizeof bits);
    const Entry e{bits, exact ? uint64_t(kMaxTie - c.sample) << 32 | cell : kInexact | cell};
    if (pos_[cell] == kAbsent) {
      heap_.push_back(e);
      siftUp(uint32_t(heap_.size() - 1), e);
      return;
    }
    const uint32_t i = pos_[cell];
    if (i > kRoot && before(e, at(parent(i)))) siftUp(i, e);
    else siftDown(i, e);
  }

  // Starts loading what set() or remove() of `cell` reads first (its heap
  // position, a random read): for a caller with work to do in between.
  void prefetch(uint32_t cell) const {
    if (cell < pos_.size()) __builtin_prefetch(&pos_[cell]);
  }

  // The error num / den of an exact entry (0 < num < 2^30, 0 < den < 2^20)
  // from its key, the double nearest to it, in lowest terms, with integers
  // alone: two such errors differ relatively by more than 2^-50 (above), the
  // key from the error by at most 2^-53, so the error is the fraction of
  // denominator below 2^20 nearest to the key, which is the last convergent
  // of the key's continued fraction within that bound or the largest
  // semiconvergent after it. (An exact entry keeps no candidate: a cell's
  // triangle changes before its scan replaces its entry, so the triangle
  // would not give it.)
  static void exactError(uint64_t key_bits, int64_t* num, int64_t* den) {
    using U = unsigned __int128;
    // The key, a normal double in [2^-20, 2^30), is a / b exactly: its
    // 53-bit significand over 2^(1075 - biased exponent) <= 2^72.
    const U a = U((key_bits & ((uint64_t{1} << 52) - 1)) | uint64_t{1} << 52);
    const U b = U{1} << (1075 - int(key_bits >> 52));
    constexpr U kMax = U(kExactDen - 1);
    U p0 = 0, q0 = 1, p1 = 1, q1 = 0, n = a, d = b;
    while (d != 0) {
      const U c = n / d;
      if (q0 + c * q1 > kMax) break;  // (c q1 < 2^92)
      const U p2 = p0 + c * p1, q2 = q0 + c * q1;
      p0 = p1, q0 = q1, p1 = p2, q1 = q2;
      const U r = n - c * d;
      n = d, d = r;
    }
    if (d != 0) {
      // The semiconvergent with the largest denominator within the bound,
      // if nearer to a / b than p1 / q1: |p b - a q| / q compared across, the
      // products below 2^112 (|p / q - a / b| <= 1, q < 2^20).
      const U k = (kMax - q0) / q1;
      const U ps = p0 + k * p1, qs = q0 + k * q1;
      const auto gap = [&](U p, U q) { return p * b > a * q ? p * b - a * q : a * q - p * b; };
      if (gap(ps, qs) * q1 < gap(p1, q1) * qs) p1 = ps, q1 = qs;
    }
    *num = int64_t(p1), *den = int64_t(q1);
  }

  // Removes the entry of `cell`, if any.
  void remove(uint32_t cell) {
    if (cell >= pos_.size() || pos_[cell] == kAbsent) return;
    const uint32_t i = pos_[cell];
    pos_[cell] = kAbsent;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (last.cell() == cell) return;
    if (i > kRoot && before(last, at(parent(i)))) siftUp(i, last);
    else siftDown(i, last);
  }

 private:
  // Four children per node: half the depth of a binary heap, and a node's
  // children (16 bytes each) fill one cache line: the root is at position 3
  // of an array of 64-byte groups, the children of position i at 4 i - 8 to
  // 4 i - 5, its parent at i / 4 + 2.
  static constexpr uint32_t kRoot = 3;
  static uint32_t parent(uint32_t i) { return i / 4 + 2; }
  static uint32_t firstChild(uint32_t i) { return 4 * i - 8; }

  // The error as a double beside the cell, so that most comparisons read the
  // heap array alone. When num < 2^30 and den < 2^20 (most errors: small
  // triangles, heights in whole units), the doubles of two such errors are
  // in their exact order and equal only when the errors are: two distinct
  // errors differ by at least 1 / (den den'), relatively by 1 / (num den')
  // > 2^-50, while each quotient of exact doubles is rounded by at most
  // 2^-53. Such an entry carries its sample too, so that the order of two of
  // them (larger error, then smaller sample, then larger cell: a sample on an
  // edge is in two cells with the same error) is that of two 128-bit
  // integers: (key, tie) with the key's bits (a positive double's bits are
  // in its order) and tie = (kMaxTie - sample) << 32 | cell. Other entries
  // have the bit kInexact in tie, and their near-ties read the exact
  // candidates.
  static constexpr uint64_t kMaxTie = (uint64_t{1} << 31) - 1;
  static constexpr uint64_t kInexact = uint64_t{1} << 63;
  static constexpr __int128 kExactNum = __int128{1} << 30;
  static constexpr int64_t kExactDen = int64_t{1} << 20;
  struct Entry {
    uint64_t key;  // the error's double, as bits
    uint64_t tie;
    uint32_t cell() const { return uint32_t(tie); }
  };
  static unsigned __int128 wide(const Entry& e) { return (unsigned __int128){e.key} << 64 | e.tie; }
  // An allocator of cache-line-aligned blocks, for the heap.
  template <class T>
  struct LineAligned {
    using value_type = T;
    LineAligned() = default;
    template <class U>
    LineAligned(const LineAligned<U>&) {}
    T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{64})); }
    void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t{64}); }
    bool operator==(const LineAligned&) const { return true; }
    bool operator!=(const LineAligned&) const { return false; }
  };
  Entry& at(uint32_t i) { return heap_[i]; }
  const Entry& at(uint32_t i) const { return heap_[i]; }

  void grow(uint32_t cell) {
    if (cell < pos_.size()) return;
    const size_t n = size_t(cell) + 1 + (size_t(cell) >> 1);
    pos_.resize(n, kAbsent);
  }
  // Whether a comes before b.
  bool before(const Entry& a, const Entry& b) const {
    if (((a.tie | b.tie) & kInexact) == 0)
      return wide(a) > wide(b);
    return beforeInexact(a, b);
  }
  // Doubles carry 53 bits: keys further apart than 2^-40 relative are in the
  // exact order; closer ones are compared exactly.
  [[gnu::noinline]] bool beforeInexact(const Entry& a, const Entry& b) const {
    double ka, kb;
    std::memcpy(&ka, &a.key, sizeof ka);
    std::memcpy(&kb, &b.key, sizeof kb);
    if (ka > kb * (1 + 0x1p-40)) return true;
    if (kb > ka * (1 + 0x1p-40)) return false;
    return worse(candidate(a), candidate(b));
  }
  // An exact entry's candidate from its key (the error in lowest terms: the
  // comparisons read its value).
  Candidate candidate(const Entry& e) const {
    if (e.tie & kInexact) return inexact_.at(e.cell());
    Candidate c;
    int64_t num = 0, den = 1;
    exactError(e.key, &num, &den);
    c.num = num, c.den = den;
    c.sample = kMaxTie - (e.tie >> 32);
    return c;
  }
  void place(uint32_t i, const Entry& e) {
    at(i) = e;
    pos_[e.cell()] = i;
  }
  void siftUp(uint32_t i, const Entry& e) {
    while (i > kRoot) {
      const uint32_t up = parent(i);
      if (!before(e, at(up))) break;
      place(i, at(up));
      i = up;
    }
    place(i, e);
  }
  void siftDown(uint32_t i, const Entry& e) {
    const uint32_t n = uint32_t(heap_.size());
    for (;;) {
      const uint32_t first = firstChild(i);
      if (first >= n) break;
      uint32_t child = first;
      if (first + 3 < n) {
        // Four children, as nearly every node has: two pairs, then their
        // winners (the same three comparisons, two of them independent).
        const uint32_t left = before(at(first + 1), at(first)) ? first + 1 : first;
        const uint32_t right = before(at(first + 3), at(first + 2)) ? first + 3 : first + 2;
        child = before(at(right), at(left)) ? right : left;
      } else {
        for (uint32_t k = first + 1; k < n; ++k)
          if (before(at(k), at(child))) child = k;
      }
      if (!before(at(child), e)) break;
      place(i, at(child));
      i = child;
    }
    place(i, e);
  }

  std::vector<Entry, LineAligned<Entry>> heap_ = std::vector<Entry, LineAligned<Entry>>(kRoot);  // from position 3
  std::vector<uint32_t> pos_;  // per cell: position in the heap, or kAbsent
  // The candidates of inexact entries (few: the largest cells' errors), by
  // cell. A per-cell array of them was a random write of its own at every
  // set, and most of the memory the insertion touched.
  std::unordered_map<uint32_t, Candidate> inexact_;
};

}  // namespace mrsv::reconstruct
