// The self-correcting weighted predictor of arrays coded with prediction 2
// (spec 5.7.5): eight sub-predictors over the decoded neighbours of a value,
// blended with weights inversely proportional to each one's recent absolute
// error, some of them corrected by the recent errors of the blend itself.
//
// All arithmetic is exact in int64. Values are within +-(2^40 - 1) (the decoder
// clamps them, spec 5.7.4), so eighths are below 2^43, sub-predictions are
// clamped to +-2^44, errors stay below 2^45, error sums below 2^48 and the
// weighted sum below 8 * 2^14 * 2^44 = 2^61.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace mrsv {

static_assert((int64_t{-9} >> 3) == -2, "floor division by shifting needs an arithmetic right shift");

// max(1, floor(2^14 / (s + 1))) for every error sum s below 2^14 (above, the
// weight is 1): a table instead of eight divisions per value.
struct WeightTable {
  static constexpr uint64_t kSize = uint64_t{1} << 14;
  uint16_t weight[kSize];
  constexpr WeightTable() : weight() {
    for (uint64_t s = 0; s < kSize; ++s) {
      const uint64_t w = kSize / (s + 1);
      weight[s] = static_cast<uint16_t>(w == 0 ? 1 : w);
    }
  }
};
inline constexpr WeightTable kWeightTable{};

class WeightedPredictor {
 public:
  static constexpr int kSubPredictors = 8;
  static constexpr int64_t kSubLimit = int64_t{1} << 44;
  static constexpr int kWeightBits = 14;
  // Memory per value of a row: two rows of one blend error and eight sub-errors.
  static constexpr uint64_t kBytesPerColumn = 2 * (1 + kSubPredictors) * 8;

  // Allocates the two rows of errors for rows of `size_x` values; false when
  // memory runs out.
  bool init(uint32_t size_x) {
    size_x_ = size_x;
    try {
      for (int r = 0; r < 2; ++r) {
        true_error_[r].assign(size_x, 0);
        sub_error_[r].assign(size_t{size_x} * kSubPredictors, 0);
      }
    } catch (const std::bad_alloc&) {
      return false;
    }
    return true;
  }

  // spec: 5.7.5 the prediction of value x of a row. `row` holds the values
  // of the current row (decoded below x), `up` and `up2` the rows y - 1 and
  // y - 2 of the same slice, null when outside it. Call record() with the
  // value before predicting the next one.
  int64_t predict(const int64_t* row, const int64_t* up, const int64_t* up2, uint32_t x) {
    const bool has_w = x > 0, has_ne = up && x + 1 < size_x_;
    const int64_t w = has_w ? row[x - 1] : up ? up[x] : 0;
    const int64_t n = up ? up[x] : w;
    const int64_t nw = has_w && up ? up[x - 1] : n;
    const int64_t ne = has_ne ? up[x + 1] : n;
    const int64_t ww = x > 1 ? row[x - 2] : w;
    const int64_t nn = up2 ? up2[x] : n;
    const int64_t* te_up = true_error_[up_].data();
    const int64_t* te_cur = true_error_[1 - up_].data();
    const int64_t e_w = has_w ? te_cur[x - 1] : 0;
    const int64_t e_n = up ? te_up[x] : 0;
    const int64_t e_nw = has_w && up ? te_up[x - 1] : e_n;
    const int64_t e_ne = has_ne ? te_up[x + 1] : e_n;
    const int64_t w8 = 8 * w, n8 = 8 * n, nw8 = 8 * nw, ne8 = 8 * ne;
    // Floor divisions by powers of two are arithmetic shifts (C++20 defines
    // >> on negative values so; every compiler we build with did before).
    const int64_t correction = (e_w + e_n + e_ne) >> 1;
    sub_[0] = w8 + ne8 - n8;
    sub_[1] = n8 - correction;
    sub_[2] = w8 - ((10 * (e_w + e_n + e_nw)) >> 5);
    sub_[3] = n8 - ((7 * (e_nw + e_n + e_ne)) >> 5);
    sub_[4] = w8 + n8 - nw8;
    sub_[5] = 2 * n8 - 8 * nn;
    sub_[6] = 2 * w8 - 8 * ww;
    sub_[7] = w8 + ne8 - n8 - correction;
    // Each sub-predictor's absolute errors at N, W, NW, WW and NE (those in
    // the slice) weigh it: w_i = max(1, floor(2^14 / (sum + 1))).
    const uint64_t* se_up = sub_error_[up_].data();
    const uint64_t* se_cur = sub_error_[1 - up_].data();
    // The five neighbours' errors, or zeros where a neighbour does not exist.
    const uint64_t* at_n = up ? se_up + size_t{x} * kSubPredictors : kNoErrors;
    const uint64_t* at_w = has_w ? se_cur + size_t{x - 1} * kSubPredictors : kNoErrors;
    const uint64_t* at_nw = has_w && up ? se_up + size_t{x - 1} * kSubPredictors : kNoErrors;
    const uint64_t* at_ww = x > 1 ? se_cur + size_t{x - 2} * kSubPredictors : kNoErrors;
    const uint64_t* at_ne = has_ne ? se_up + size_t{x + 1} * kSubPredictors : kNoErrors;
    int64_t weight_sum = 0, weighted = 0;
    for (int i = 0; i < kSubPredictors; ++i) {
      if (sub_[i] > kSubLimit) sub_[i] = kSubLimit;
      if (sub_[i] < -kSubLimit) sub_[i] = -kSubLimit;
      const uint64_t sum = at_n[i] + at_w[i] + at_nw[i] + at_ww[i] + at_ne[i];
      static_assert(WeightTable::kSize == uint64_t{1} << kWeightBits, "one weight per sum below 2^14");
      const uint64_t weight = sum < WeightTable::kSize ? kWeightTable.weight[sum] : 1;
      weight_sum += static_cast<int64_t>(weight);
      weighted += static_cast<int64_t>(weight) * sub_[i];
    }
    blend_ = floorDiv(weighted + weight_sum / 2, weight_sum);
    bias_ = e_w + e_n;
    return (blend_ + 4) >> 3;
  }

  // The sign context of the symbol just predicted (spec 5.7.5): the sign of
  // the sum of the blend's errors at W and N.
  int signContext() const { return bias_ == 0 ? 0 : bias_ > 0 ? 1 : 2; }

  // Records the decoded value at x of the current row.
  void record(uint32_t x, int64_t value) {
    const int64_t v8 = 8 * value;
    true_error_[1 - up_][x] = blend_ - v8;
    uint64_t* se = sub_error_[1 - up_].data() + size_t{x} * kSubPredictors;
    for (int i = 0; i < kSubPredictors; ++i) {
      const int64_t d = sub_[i] - v8;
      se[i] = d < 0 ? static_cast<uint64_t>(-d) : static_cast<uint64_t>(d);
    }
  }

  // The current row becomes the row above.
  void nextRow() { up_ = 1 - up_; }

 private:
  static int64_t floorDiv(int64_t a, int64_t b) {  // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
  }

  static constexpr uint64_t kNoErrors[kSubPredictors] = {};
  uint32_t size_x_ = 0;
  int up_ = 0;  // which of the two rows holds the row above
  std::vector<int64_t> true_error_[2];   // blend - 8 * value, in eighths
  std::vector<uint64_t> sub_error_[2];   // |sub-prediction - 8 * value|
  int64_t sub_[kSubPredictors] = {};
  int64_t blend_ = 0;
  int64_t bias_ = 0;
};

}  // namespace mrsv
