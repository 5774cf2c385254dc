// spec: 5.10 the baseline entropy mode, decoder side.
#include <algorithm>

#include "grid/baseline_coding.h"

namespace mrsv {
namespace {

// Bits most significant first; reading past the end yields zeros and sets
// the sticky overrun flag, checked once per array.
class BitReader {
 public:
  BitReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint32_t bit() {
    if (pos_ >= size_) {
      overrun_ = true;
      return 0;
    }
    uint32_t b = (data_[pos_] >> (7 - bit_)) & 1u;
    if (++bit_ == 8) {
      bit_ = 0;
      ++pos_;
    }
    return b;
  }
  uint64_t bits(int n) {
    uint64_t v = 0;
    while (n--) v = (v << 1) | bit();
    return v;
  }
  bool overrun() const { return overrun_; }
  size_t bytePosition() const { return pos_; }
  int bitInByte() const { return bit_; }
  // The bits left in the current byte must be zero (spec 5.10.3).
  bool paddingIsZero() const {
    return bit_ == 0 || (data_[pos_] & ((1u << (8 - bit_)) - 1)) == 0;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  int bit_ = 0;
  bool overrun_ = false;
};

bool validSymbol(uint16_t s) {
  int run = s >> 6, size = s & 63;
  if (run > 15 || size > kBaselineMaxSize) return false;
  return size != 0 || run == 0 || run == 15;
}

// spec: 5.10.2 the canonical Huffman table.
struct HuffmanTable {
  // For each length L: codes first[L] .. first[L] + count[L] - 1 map to
  // symbols[offset[L] ...], in table order.
  uint32_t first[kBaselineMaxCodeLength + 1] = {};
  uint32_t count[kBaselineMaxCodeLength + 1] = {};
  uint32_t offset[kBaselineMaxCodeLength + 1] = {};
  std::vector<uint16_t> symbols;
};

std::string readTable(BitReader& r, HuffmanTable* t) {
  uint32_t n = static_cast<uint32_t>(r.bits(16));
  if (n == 0 || n > 16 * 64) return "symbol count of the Huffman table must be 1 to 1024";
  std::vector<std::pair<int, uint16_t>> entries;  // (length, symbol)
  std::vector<uint8_t> seen(1024, 0);
  for (uint32_t i = 0; i < n; ++i) {
    uint16_t symbol = static_cast<uint16_t>(r.bits(16));
    int length = static_cast<int>(r.bits(8));
    if (r.overrun()) return "the Huffman table runs past the end of the payload";
    if (!validSymbol(symbol)) return "Huffman table entry " + std::to_string(i) + " is not a run/size symbol";
    if (seen[symbol]) return "symbol listed twice in the Huffman table";
    seen[symbol] = 1;
    if (length < 1 || length > kBaselineMaxCodeLength) return "code length must be 1 to 20";
    if (i > 0 && (length < entries.back().first ||
                  (length == entries.back().first && symbol <= entries.back().second)))
      return "Huffman table entries must be sorted by length, then symbol";
    entries.emplace_back(length, symbol);
  }
  // Kraft sum <= 1, in units of 2^-20.
  uint64_t kraft = 0;
  for (const auto& e : entries) kraft += uint64_t{1} << (kBaselineMaxCodeLength - e.first);
  if (kraft > (uint64_t{1} << kBaselineMaxCodeLength)) return "code lengths over-subscribe the code space";
  uint32_t code = 0;
  size_t k = 0;
  for (int len = 1; len <= kBaselineMaxCodeLength; ++len) {
    t->first[len] = code;
    t->offset[len] = static_cast<uint32_t>(k);
    while (k < entries.size() && entries[k].first == len) {
      t->symbols.push_back(entries[k].second);
      ++t->count[len];
      ++k;
      ++code;
    }
    code <<= 1;
  }
  return {};
}

bool readSymbol(BitReader& r, const HuffmanTable& t, uint16_t* symbol) {
  uint32_t code = 0;
  for (int len = 1; len <= kBaselineMaxCodeLength; ++len) {
    code = (code << 1) | r.bit();
    if (code - t.first[len] < t.count[len]) {
      *symbol = t.symbols[t.offset[len] + code - t.first[len]];
      return true;
    }
  }
  return false;
}

}  // namespace

std::string decodeBaselineArray(const uint8_t* payload, size_t size, const ArrayBox& box,
                                ArrayPrediction prediction, const uint8_t* skip, int64_t* values) {
  BitReader r(payload, size);
  HuffmanTable table;
  if (std::string problem = readTable(r, &table); !problem.empty()) return problem;
  const uint64_t total = box.count();
  std::fill(values, values + total, 0);
  // Symbols are the values (or prediction residuals) of the coded positions in
  // raster order; skipped positions are not counted.
  std::vector<int64_t> symbols;
  uint64_t coded = 0;
  for (uint64_t i = 0; i < total; ++i) coded += !(skip && skip[i]);
  symbols.assign(coded, 0);
  uint64_t filled = 0;
  while (filled < coded) {
    uint16_t s;
    if (!readSymbol(r, table, &s)) return "a code that is not in the Huffman table";
    if (r.overrun()) return "coded data ends before the array does";
    int run = s >> 6, bits = s & 63;
    if (s == kBaselineEndOfArray) break;
    if (s == kBaselineZeroRun) {
      if (coded - filled < 16) return "a run of 16 zeros past the end of the array";
      filled += 16;
      continue;
    }
    if (static_cast<uint64_t>(run) >= coded - filled) return "a run past the end of the array";
    filled += static_cast<uint64_t>(run);
    uint64_t amplitude = r.bits(bits);
    // spec: 5.10.1 the first amplitude bit is the sign (1 negative), the rest
    // are the magnitude below its leading one.
    uint64_t magnitude = (uint64_t{1} << (bits - 1)) | (amplitude & ((uint64_t{1} << (bits - 1)) - 1));
    bool negative = (amplitude >> (bits - 1)) & 1;
    symbols[filled++] = negative ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
  }
  if (r.overrun()) return "coded data ends before the array does";
  if (!r.paddingIsZero()) return "the bits after the last symbol must be 0";
  size_t used = r.bytePosition() + (r.bitInByte() ? 1 : 0);
  if (used != size) return std::to_string(size - used) + " bytes of coded data left over";

  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  uint64_t k = 0;
  for (uint32_t z = 0; z < box.size[2]; ++z)
    for (uint32_t y = 0; y < box.size[1]; ++y)
      for (uint32_t x = 0; x < box.size[0]; ++x) {
        size_t i = x + y * sx + z * sxy;
        if (skip && skip[i]) continue;
        int64_t v = symbols[k++];
        if (prediction == ArrayPrediction::kNeighbour) v = clampArrayValue(v + predictNeighbour(values, box, x, y, z));
        values[i] = v;
      }
  return {};
}

}  // namespace mrsv
