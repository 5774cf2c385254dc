// spec: 5.10 the baseline entropy mode, encoder side: run/size symbols, a
// length-limited canonical Huffman code built from their counts, amplitude bits.
#include <algorithm>
#include <queue>

#include "grid/baseline_coding.h"

namespace mrsv {
namespace {

class BitWriter {
 public:
  explicit BitWriter(std::vector<uint8_t>* out) : out_(out) {}
  void bits(uint64_t value, int n) {
    while (n--) {
      acc_ = static_cast<uint8_t>(acc_ << 1 | ((value >> n) & 1));
      if (++count_ == 8) flushByte();
    }
  }
  void finish() {  // zero padding to the byte boundary
    if (count_) {
      acc_ = static_cast<uint8_t>(acc_ << (8 - count_));
      flushByte();
    }
  }

 private:
  void flushByte() {
    out_->push_back(acc_);
    acc_ = 0;
    count_ = 0;
  }
  std::vector<uint8_t>* out_;
  uint8_t acc_ = 0;
  int count_ = 0;
};

int bitLength(uint64_t v) {
  int n = 0;
  while (v) {
    ++n;
    v >>= 1;
  }
  return n;
}

// Huffman code lengths for `counts` (symbols with count 0 get none), limited
// to kBaselineMaxCodeLength by flattening the counts until they fit.
std::vector<int> codeLengths(std::vector<uint64_t> counts) {
  const size_t n = counts.size();
  std::vector<int> lengths(n, 0);
  size_t used = 0;
  for (uint64_t c : counts) used += c > 0;
  if (used == 1) {
    for (size_t i = 0; i < n; ++i)
      if (counts[i]) lengths[i] = 1;
    return lengths;
  }
  while (true) {
    // Heap of (count, node); nodes >= n are internal.
    using Item = std::pair<uint64_t, size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    std::vector<size_t> parent(2 * n, 0);
    for (size_t i = 0; i < n; ++i)
      if (counts[i]) heap.push({counts[i], i});
    size_t next = n;
    while (heap.size() > 1) {
      Item a = heap.top();
      heap.pop();
      Item b = heap.top();
      heap.pop();
      parent[a.second] = parent[b.second] = next;
      heap.push({a.first + b.first, next++});
    }
    size_t root = next - 1;
    int longest = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!counts[i]) continue;
      int depth = 0;
      for (size_t node = i; node != root; node = parent[node]) ++depth;
      lengths[i] = depth;
      longest = std::max(longest, depth);
    }
    if (longest <= kBaselineMaxCodeLength) return lengths;
    for (uint64_t& c : counts)
      if (c) c = (c + 1) / 2;
  }
}

}  // namespace

void encodeBaselineArray(const int64_t* values, const ArrayBox& box, ArrayPrediction prediction,
                         const uint8_t* skip, std::vector<uint8_t>* out) {
  // The symbols of the coded positions in raster order.
  std::vector<int64_t> s;
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  for (uint32_t z = 0; z < box.size[2]; ++z)
    for (uint32_t y = 0; y < box.size[1]; ++y)
      for (uint32_t x = 0; x < box.size[0]; ++x) {
        size_t i = x + y * sx + z * sxy;
        if (skip && skip[i]) continue;
        int64_t v = values[i];
        if (prediction == ArrayPrediction::kNeighbour) v -= predictNeighbour(values, box, x, y, z);
        s.push_back(v);
      }
  // Run/size symbols (with the amplitude to follow each).
  struct Token {
    uint16_t symbol;
    int64_t value;
  };
  std::vector<Token> tokens;
  int run = 0;
  for (int64_t v : s) {
    if (v == 0) {
      ++run;
      continue;
    }
    while (run >= 16) {
      tokens.push_back({kBaselineZeroRun, 0});
      run -= 16;
    }
    tokens.push_back({baselineSymbol(run, bitLength(magnitudeOf(v))), v});
    run = 0;
  }
  if (run > 0) tokens.push_back({kBaselineEndOfArray, 0});

  std::vector<uint64_t> counts(1024, 0);
  for (const Token& t : tokens) ++counts[t.symbol];
  if (tokens.empty()) ++counts[kBaselineEndOfArray];  // an empty array still needs a table
  std::vector<int> lengths = codeLengths(counts);
  std::vector<std::pair<int, uint16_t>> table;
  for (uint16_t sym = 0; sym < 1024; ++sym)
    if (lengths[sym]) table.emplace_back(lengths[sym], sym);
  std::sort(table.begin(), table.end());
  std::vector<uint32_t> code(1024, 0);
  uint32_t c = 0;
  int len = table.front().first;
  for (size_t i = 0; i < table.size(); ++i) {
    if (i > 0) {
      ++c;
      c <<= (table[i].first - len);
      len = table[i].first;
    } else {
      c = 0;
    }
    code[table[i].second] = c;
  }
  BitWriter w(out);
  w.bits(table.size(), 16);
  for (const auto& [length, sym] : table) {
    w.bits(sym, 16);
    w.bits(static_cast<uint64_t>(length), 8);
  }
  for (const Token& t : tokens) {
    w.bits(code[t.symbol], lengths[t.symbol]);
    int size = t.symbol & 63;
    if (size) {
      uint64_t magnitude = magnitudeOf(t.value);
      uint64_t low = magnitude & ((uint64_t{1} << (size - 1)) - 1);
      w.bits((uint64_t{t.value < 0} << (size - 1)) | low, size);
    }
  }
  w.finish();
}

}  // namespace mrsv
