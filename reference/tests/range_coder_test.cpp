#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "bitstream/range_decoder.h"
#include "bitstream/range_encoder.h"

namespace mrsv {
namespace {

// spec 5.6: the initial cum of a symbol model, as the table there gives it.
constexpr uint32_t kSpecInitialCum[16] = {0,     16352, 24528, 28616, 30660, 31682, 32193, 32448,
                                          32576, 32640, 32672, 32688, 32696, 32700, 32702, 32703};

enum class Kind { kBit, kDirect, kSymbol };
struct Op {
  Kind kind;
  int context;   // model index, or bit count for direct
  uint32_t value;
};

// Random mixtures of skewed adaptive bits, direct bits and 16-ary symbols,
// with carries forced by long runs of likely bits and symbols: what is decoded
// equals what was coded, and the decoder consumes exactly the payload.
TEST(RangeCoder, RoundTripsAndConsumesExactlyThePayload) {
  std::mt19937 rng(20261122);
  for (int trial = 0; trial < 200; ++trial) {
    int count = 1 + static_cast<int>(rng() % 5000);
    std::vector<Op> ops;
    std::vector<double> p_one(8);
    for (double& p : p_one) p = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    p_one[0] = 0.001;  // nearly always 0: long runs stress the carry path
    p_one[1] = 0.999;
    // Symbol model 0 nearly always sees 0 and model 1 nearly always 15 (the
    // other symbols then sit at the floor width); the others are geometric.
    std::vector<double> ratio(4);
    for (double& r : ratio) r = std::uniform_real_distribution<double>(0.2, 0.95)(rng);
    auto drawSymbol = [&](int c) {
      if (c < 2 && rng() % 500 != 0) return c == 0 ? 0u : 15u;
      if (c < 2) return static_cast<uint32_t>(rng() % 16);
      uint32_t v = 0;
      while (v < 15 && std::bernoulli_distribution(ratio[c])(rng)) ++v;
      return v;
    };
    for (int i = 0; i < count; ++i) {
      const uint32_t pick = rng() % 7;
      if (pick == 0) {
        int n = 1 + static_cast<int>(rng() % 24);
        ops.push_back({Kind::kDirect, n, static_cast<uint32_t>(rng()) & ((1u << n) - 1)});
      } else if (pick < 3) {
        int c = static_cast<int>(rng() % 4);
        ops.push_back({Kind::kSymbol, c, drawSymbol(c)});
      } else {
        int c = static_cast<int>(rng() % 8);
        ops.push_back({Kind::kBit, c, std::bernoulli_distribution(p_one[c])(rng) ? 1u : 0u});
      }
    }
    std::vector<uint8_t> bytes;
    RangeEncoder enc(&bytes);
    std::vector<BitModel> models(8);
    std::vector<SymbolModel> symbols(4);
    for (const Op& op : ops) {
      if (op.kind == Kind::kDirect) enc.direct(op.value, op.context);
      else if (op.kind == Kind::kSymbol) enc.symbol(&symbols[op.context], static_cast<int>(op.value));
      else enc.bit(&models[op.context], static_cast<int>(op.value));
    }
    enc.finish();
    ASSERT_FALSE(bytes.empty());
    EXPECT_EQ(bytes[0], 0);
    RangeDecoder dec(bytes.data(), bytes.size());
    EXPECT_TRUE(dec.validStart());
    std::vector<BitModel> dmodels(8);
    std::vector<SymbolModel> dsymbols(4);
    for (size_t i = 0; i < ops.size(); ++i) {
      const Op& op = ops[i];
      uint32_t got = op.kind == Kind::kDirect   ? dec.direct(op.context)
                     : op.kind == Kind::kSymbol ? static_cast<uint32_t>(dec.symbol(&dsymbols[op.context]))
                                                : static_cast<uint32_t>(dec.bit(&dmodels[op.context]));
      ASSERT_EQ(got, op.value) << "trial " << trial << " op " << i;
    }
    EXPECT_EQ(dec.overrun(), 0u) << trial;
    EXPECT_EQ(dec.consumed(), bytes.size()) << trial;
  }
}

TEST(RangeCoder, SkewedBitsCostLittle) {
  std::vector<uint8_t> bytes;
  RangeEncoder enc(&bytes);
  BitModel m;
  for (int i = 0; i < 100000; ++i) enc.bit(&m, 0);
  enc.finish();
  // The probability saturates at 1 - 31/2048, so a certain bit still costs
  // about 0.022 bits: 100000 of them take about 275 bytes.
  EXPECT_LT(bytes.size(), 300u);
}

TEST(RangeCoder, GarbageDecodesWithoutHarm) {
  std::vector<uint8_t> garbage = {0x00, 0xFF, 0x13, 0x37};
  RangeDecoder dec(garbage.data(), garbage.size());
  BitModel m;
  for (int i = 0; i < 1000; ++i) dec.bit(&m);
  EXPECT_GT(dec.overrun(), 0u);
}

// spec 5.6 written out with the products of the text (no division): init,
// normalise, decode_bit and decode_symbol. On random bytes, RangeDecoder must
// give the same bits and symbols and read the same bytes.
class SpecDecoder {
 public:
  explicit SpecDecoder(const std::vector<uint8_t>& bytes) : bytes_(bytes) {
    next();
    for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next();
  }
  int bit(uint16_t* p0) {
    const uint32_t bound = (range_ >> 11) * *p0;
    int b;
    if (code_ < bound) {
      range_ = bound;
      *p0 = static_cast<uint16_t>(*p0 + ((2048 - *p0) >> 5));
      b = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      *p0 = static_cast<uint16_t>(*p0 - (*p0 >> 5));
      b = 1;
    }
    normalise();
    return b;
  }
  int symbol(uint32_t* cum, uint32_t* count) {
    auto start = [&](int i) { return i == 16 ? 32768u : cum[i] + 4u * i; };
    const uint32_t r = range_ >> 15;
    int s = 0;
    for (int i = 0; i < 16; ++i)
      if (start(i) * r <= code_) s = i;
    const uint32_t low = start(s) * r;
    code_ -= low;
    range_ = s < 15 ? (start(s + 1) - start(s)) * r : range_ - low;
    const int w = *count < 64 ? 5 : 7;
    for (int i = 1; i < 16; ++i) cum[i] = i > s ? cum[i] + ((32704 - cum[i]) >> w) : cum[i] - (cum[i] >> w);
    *count = std::min(*count + 1, 64u);
    normalise();
    return s;
  }
  size_t consumed() const { return std::min(pos_, bytes_.size()); }

 private:
  uint32_t next() { return pos_ < bytes_.size() ? bytes_[pos_++] : (++pos_, 0u); }
  void normalise() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
  }
  const std::vector<uint8_t>& bytes_;
  size_t pos_ = 0;
  uint32_t range_ = 0xFFFFFFFFu, code_ = 0;
};

// A string no encoder writes starts with code = range = 2^32 - 1: every start
// is at most code, so decode_symbol gives 15; what follows (code and range
// wrap around modulo 2^32 as they are shifted) still follows the specification.
TEST(RangeCoder, GarbageSymbolsFollowTheSpecification) {
  std::vector<uint8_t> garbage = {0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x80};
  RangeDecoder dec(garbage.data(), garbage.size());
  SpecDecoder spec(garbage);
  SymbolModel m;
  uint32_t cum[16], count = 0;
  for (int i = 0; i < 16; ++i) cum[i] = kSpecInitialCum[i];
  EXPECT_EQ(dec.symbol(&m), 15);
  EXPECT_EQ(spec.symbol(cum, &count), 15);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(dec.symbol(&m), spec.symbol(cum, &count)) << i;
  EXPECT_GT(dec.overrun(), 0u);
}

TEST(RangeCoder, SymbolsAndBitsOfRandomBytesFollowTheSpecification) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes(1 + rng() % 300);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    if (trial % 3 == 0) bytes[0] = 0;
    RangeDecoder dec(bytes.data(), bytes.size());
    SpecDecoder spec(bytes);
    SymbolModel models[3];
    uint32_t cum[3][16], count[3] = {0, 0, 0};
    for (auto& c : cum) std::copy(kSpecInitialCum, kSpecInitialCum + 16, c);
    BitModel bits[2];
    uint16_t p0[2] = {1024, 1024};
    for (int op = 0; op < 400; ++op) {
      const int k = static_cast<int>(rng() % 5);
      if (k < 3) {
        ASSERT_EQ(dec.symbol(&models[k]), spec.symbol(cum[k], &count[k])) << trial << " " << op;
      } else {
        ASSERT_EQ(dec.bit(&bits[k - 3]), spec.bit(&p0[k - 3])) << trial << " " << op;
      }
    }
    EXPECT_EQ(dec.consumed(), spec.consumed()) << trial;
  }
}

// spec 5.6 written out plainly: start(i), the largest i with start(i) <= q,
// and the adaptation rule. SymbolModel's plain and vectorised (where SSE2 is
// available) paths must agree with it after any history, and keep every width
// at least 4.
TEST(SymbolModel, MatchesTheSpecificationAfterAnyHistory) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    SymbolModel model, plain;
    uint32_t cum[16], count = 0;
    for (int i = 0; i < 16; ++i) cum[i] = kSpecInitialCum[i];
    const int favourite = static_cast<int>(rng() % 16);
    for (int step = 0; step < 3000; ++step) {
      for (int i = 0; i < 16; ++i) ASSERT_EQ(model.cum[i], cum[i]) << trial << " " << step;
      for (int i = 0; i < 16; ++i) ASSERT_EQ(plain.cum[i], cum[i]) << trial << " " << step;
      auto start = [&](int i) { return i == 16 ? 32768u : cum[i] + 4u * i; };
      for (int i = 0; i < 16; ++i) ASSERT_GE(start(i + 1) - start(i), 4u);
      for (uint32_t q : {0u, 1u, 32767u, 32768u, 32831u, static_cast<uint32_t>(rng() % 32832),
                         start(static_cast<int>(rng() % 16)), start(static_cast<int>(rng() % 16)) - 1}) {
        int expected = 0;
        for (int i = 1; i < 16; ++i)
          if (start(i) <= q) expected = i;
        ASSERT_EQ(model.find(q), expected) << "q " << q;
        ASSERT_EQ(model.findPlain(q), expected) << "q " << q;
      }
      // Long runs of one symbol squeeze the others to the floor; then the
      // extremes alternate, and random symbols.
      const int phase = step / 500 % 3;
      const int s = phase == 0 ? (rng() % 4 != 0 ? favourite : static_cast<int>(rng() % 16))
                    : phase == 1 ? (step % 2 ? 0 : 15)
                                 : static_cast<int>(rng() % 16);
      const int k = count < 64 ? 5 : 7;
      count = std::min(count + 1, 64u);
      for (int i = 1; i < 16; ++i) cum[i] = i > s ? cum[i] + ((32704 - cum[i]) >> k) : cum[i] - (cum[i] >> k);
      model.adapt(s);
      plain.adaptPlain(s);
      ASSERT_EQ(model.count, count);
      ASSERT_EQ(plain.count, count);
    }
  }
}

}  // namespace
}  // namespace mrsv
