// The cells' worst samples in a max-heap indexed by cell, as the greedy
// insertion of spec 8.5 needs it: the worst sample of all (largest error,
// then smallest sample index), with each cell's entry replaced in place when
// the cell changes, so that the heap holds one entry per cell and never a
// stale one.
#pragma once

#include <cstdint>
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
    heap_.clear();
    pos_.clear();
    key_.clear();
    cand_.clear();
  }
  bool empty() const { return heap_.empty(); }
  uint32_t top() const { return heap_.front(); }
  const Candidate& candidate(uint32_t cell) const { return cand_[cell]; }

  // Sets (or replaces) the entry of `cell`.
  void set(uint32_t cell, const Candidate& c) {
    grow(cell);
    cand_[cell] = c;
    key_[cell] = double(c.num) / double(c.den);
    if (pos_[cell] == kAbsent) {
      pos_[cell] = uint32_t(heap_.size());
      heap_.push_back(cell);
    }
    siftUp(pos_[cell]);
    siftDown(pos_[cell]);
  }

  // Removes the entry of `cell`, if any.
  void remove(uint32_t cell) {
    if (cell >= pos_.size() || pos_[cell] == kAbsent) return;
    const uint32_t i = pos_[cell];
    pos_[cell] = kAbsent;
    const uint32_t last = heap_.back();
    heap_.pop_back();
    if (last == cell) return;
    heap_[i] = last;
    pos_[last] = i;
    siftUp(i);
    siftDown(pos_[last]);
  }

 private:
  void grow(uint32_t cell) {
    if (cell < pos_.size()) return;
    const size_t n = size_t(cell) + 1 + (size_t(cell) >> 1);
    pos_.resize(n, kAbsent);
    key_.resize(n, 0.0);
    cand_.resize(n);
  }
  // Whether cell a comes before cell b. Doubles carry 53 bits: keys further
  // apart than 2^-40 relative are in the exact order; closer ones are
  // compared exactly.
  bool before(uint32_t a, uint32_t b) const {
    const double ka = key_[a], kb = key_[b];
    if (ka > kb * (1 + 0x1p-40)) return true;
    if (kb > ka * (1 + 0x1p-40)) return false;
    return worse(cand_[a], cand_[b]);
  }
  void place(uint32_t i, uint32_t cell) {
    heap_[i] = cell;
    pos_[cell] = i;
  }
  void siftUp(uint32_t i) {
    const uint32_t cell = heap_[i];
    while (i > 0) {
      const uint32_t parent = (i - 1) / 2;
      if (!before(cell, heap_[parent])) break;
      place(i, heap_[parent]);
      i = parent;
    }
    place(i, cell);
  }
  void siftDown(uint32_t i) {
    const uint32_t cell = heap_[i];
    const uint32_t n = uint32_t(heap_.size());
    for (;;) {
      uint32_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], cell)) break;
      place(i, heap_[child]);
      i = child;
    }
    place(i, cell);
  }

  std::vector<uint32_t> heap_;  // cells
  std::vector<uint32_t> pos_;   // per cell: index in heap_, or kAbsent
  std::vector<double> key_;     // per cell: the error as a double
  std::vector<Candidate> cand_;  // per cell
};

}  // namespace mrsv::reconstruct
