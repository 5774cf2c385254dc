// spec: 5.8.2 the integer sample mapping of the decoder's runs
// (grid/sample_runs.h) against the formula, for every sample type, scale and
// values up to the saturation bound. Fixed seeds.
#include "grid/sample_runs.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace mrsv {
namespace {

constexpr int64_t kValueLimit = (int64_t{1} << 35) - 1;

template <class T>
void check(std::mt19937_64& rng) {
  for (int w = 0; w <= 24; ++w) {
    for (int64_t offset : {int64_t{0}, int64_t{-32768}, int64_t{255}, int64_t{1} << 40,
                           -(int64_t{1} << 40), int64_t{12345}}) {
      for (size_t n : {size_t{0}, size_t{1}, size_t{7}, size_t{8}, size_t{33}, size_t{300}}) {
        std::vector<int64_t> values(n);
        for (int64_t& v : values) {
          switch (rng() % 4) {
            case 0: v = static_cast<int64_t>(rng() % (2 * static_cast<uint64_t>(kValueLimit) + 1)) - kValueLimit; break;
            case 1: v = (rng() & 1) ? kValueLimit : -kValueLimit; break;
            case 2: v = static_cast<int64_t>(rng() % 4096) - 2048; break;
            default: v = (static_cast<int64_t>(rng() % 70000) - 35000) * (int64_t{1} << w) + static_cast<int64_t>(rng() % 3) - 1;
          }
        }
        std::vector<uint8_t> got(n * sizeof(T) + 1, 0xAB);
        integerSampleRun<T>(values.data(), got.data(), n, w, offset);
        for (size_t i = 0; i < n; ++i) {
          // floor((v + 2^(w-1)) / 2^w) by division, then clamp_T.
          const int64_t t = values[i] + (w == 0 ? 0 : int64_t{1} << (w - 1));
          const int64_t d = int64_t{1} << w;
          const int64_t floor_div = t / d - ((t % d != 0) && (t < 0));
          int64_t y = floor_div + offset;
          y = std::max<int64_t>(std::numeric_limits<T>::min(), std::min<int64_t>(std::numeric_limits<T>::max(), y));
          T sample;
          std::memcpy(&sample, got.data() + i * sizeof(T), sizeof(T));
          ASSERT_EQ(static_cast<int64_t>(sample), y) << "w=" << w << " offset=" << offset << " i=" << i;
        }
        ASSERT_EQ(got[n * sizeof(T)], 0xAB);  // nothing past the run
      }
    }
  }
}

TEST(SampleRuns, IntegerSamplesFollowTheFormula) {
  std::mt19937_64 rng(582);
  check<uint8_t>(rng);
  check<int16_t>(rng);
  check<uint16_t>(rng);
  check<int32_t>(rng);
}

}  // namespace
}  // namespace mrsv
