#include "grid/last_level_bands.h"

#include <algorithm>
#include <cstring>

namespace mrsv {

std::unique_ptr<LastLevelBands> LastLevelBands::make(const wavelet::GridPlan& plan) {
  // Up to nine slices are in flight (cdf97.h): a thinner grid needs less
  // memory as one padded array.
  if (!wavelet::lastLevelBySlicesCdf97(plan) || plan.axis[2].size(0) < kMinDepth) return nullptr;
  auto store = std::unique_ptr<LastLevelBands>(new LastLevelBands);
  uint32_t samples[3];
  int levels[3];
  for (int a = 0; a < 3; ++a) {
    store->low_size_[a] = plan.axis[a].size(1);
    store->high_size_[a] = plan.axis[a].size(0) - plan.axis[a].size(1);
    samples[a] = store->low_size_[a];
    levels[a] = plan.axis[a].levels - 1;
  }
  if (!wavelet::makeGridPlan(3, samples, wavelet::kOrderCdf97, levels, &store->upper_))
    return nullptr;
  // The upper plan's bands must be the whole plan's bands of level 2 and above,
  // box for box (4.11.1 halves with ceil, so they are); should they ever not
  // be, the whole padded array is used instead.
  const std::vector<wavelet::Band> whole = wavelet::bandsOf(plan), upper = wavelet::bandsOf(store->upper_);
  if (upper.size() + 7 != whole.size()) return nullptr;
  for (size_t b = 0; b < upper.size(); ++b) {
    if (upper[b].mask != whole[b].mask) return nullptr;
    for (int a = 0; a < 3; ++a)
      if (upper[b].offset[a] != whole[b].offset[a] || upper[b].size[a] != whole[b].size[a])
        return nullptr;
  }
  for (size_t b = upper.size(); b < whole.size(); ++b)
    if (whole[b].level != 1 || whole[b].mask != static_cast<int>(b - upper.size()) + 1)
      return nullptr;
  return store;
}

int16_t* LastLevelBands::narrow(int mask, uint64_t count, uint64_t step) {
  Band& band = bands_[mask];
  band.wide.reset();
  band.narrow = makeLargeArray<int16_t>(count);
  band.step = step;
  return band.narrow.get();
}

int64_t* LastLevelBands::wide(int mask, uint64_t count) {
  Band& band = bands_[mask];
  band.narrow.reset();
  band.wide = makeLargeArray<int64_t>(count);
  return band.wide.get();
}

wavelet::MallatRows LastLevelBands::rows(const int64_t* low) {
  low_ = low;
  return {&LastLevelBands::row, this};
}

// Row (y, z) of level 1 in the Mallat layout (4.4): along each axis the
// low-pass part first, then the wavelet part; the x part of the row with
// mask bit 0 comes from the band of mask (y part, z part) or the low-pass
// block, the rest from the band with mask bit 0 set.
void LastLevelBands::row(void* self, size_t y, size_t z, int64_t* values) {
  const LastLevelBands& s = *static_cast<const LastLevelBands*>(self);
  const bool high_y = y >= s.low_size_[1], high_z = z >= s.low_size_[2];
  const size_t by = high_y ? y - s.low_size_[1] : y, bz = high_z ? z - s.low_size_[2] : z;
  const size_t ny = high_y ? s.high_size_[1] : s.low_size_[1];
  for (int high_x = 0; high_x < 2; ++high_x) {
    const int mask = high_x | (high_y ? 2 : 0) | (high_z ? 4 : 0);
    const size_t nx = high_x ? s.high_size_[0] : s.low_size_[0];
    int64_t* out = values + (high_x ? s.low_size_[0] : 0);
    const size_t at = (by + bz * ny) * nx;  // position of the row in its box
    if (mask == 0) {
      std::memcpy(out, s.low_ + at, nx * sizeof(int64_t));
      continue;
    }
    const Band& band = s.bands_[mask];
    if (band.narrow) {
      // |q| < 2^15 and step < 2^35: the product is exact; the synthesis
      // saturates it as it reads it, which makes it dequantizeSymbol(q, step).
      const int16_t* q = band.narrow.get() + at;
      const int64_t step = static_cast<int64_t>(band.step);
      for (size_t i = 0; i < nx; ++i) out[i] = q[i] * step;
    } else if (band.wide) {
      std::memcpy(out, band.wide.get() + at, nx * sizeof(int64_t));
    } else {
      std::fill(out, out + nx, 0);
    }
  }
}

}  // namespace mrsv
