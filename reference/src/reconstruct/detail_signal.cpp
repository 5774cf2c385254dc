// spec: 9.2 the detail signal of each level.
#include "reconstruct/detail_signal.h"

#include <algorithm>

#include "common/large_array.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv {

bool detailSignals(const WaveletCoefficients& coefficients, int frac_bits, uint32_t size_x,
                   uint32_t size_y, QuadtreeDetails* out, std::string* error) {
  *out = QuadtreeDetails{};
  const wavelet::GridPlan& plan = coefficients.plan;
  if (plan.num_dims != 2 || coefficients.values.size() != plan.paddedCount()) {
    if (error) *error = "the detail signals need the coefficients of a 2-D grid";
    return false;
  }
  out->size[0] = size_x, out->size[1] = size_y;
  out->frac_bits = frac_bits;
  const int levels = std::min(plan.axis[0].levels, plan.axis[1].levels);
  const std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
  const size_t px = plan.axis[0].size(0);
  // Synthesis from the coarsest level to level m-1 reads and writes only the
  // low-pass box of level m-1, so each pass copies just that box.
  auto with = makeLargeArray<int64_t>(plan.paddedCount());
  auto without = makeLargeArray<int64_t>(plan.paddedCount());
  if (!with || !without) {
    if (error) *error = "no memory for the detail signals";
    return false;
  }
  out->detail.resize(levels);
  for (int m = 1; m <= levels; ++m) {
    const uint32_t bx = plan.axis[0].size(m - 1), by = plan.axis[1].size(m - 1);
    for (uint32_t y = 0; y < by; ++y) {
      const int64_t* src = coefficients.values.data() + y * px;
      std::copy(src, src + bx, with.get() + y * px);
      std::copy(src, src + bx, without.get() + y * px);
    }
    for (const wavelet::Band& band : bands) {
      if (band.level != m || band.mask == 0) continue;
      for (uint32_t y = 0; y < band.size[1]; ++y) {
        int64_t* row = without.get() + (band.offset[1] + y) * px + band.offset[0];
        std::fill(row, row + band.size[0], 0);
      }
    }
    wavelet::synthesizeFixed(plan, with.get(), m - 1);
    wavelet::synthesizeFixed(plan, without.get(), m - 1);
    const uint32_t w = out->width(m), h = out->height(m);
    std::vector<int64_t>& d = out->detail[m - 1];
    d.assign(size_t{w} * h, 0);
    for (uint32_t j = 0; j < h && j < by; ++j)
      for (uint32_t i = 0; i < w && i < bx; ++i)
        d[size_t{j} * w + i] = with[j * px + i] - without[j * px + i];
  }
  return true;
}

bool quadtreeDetailsFromStream(const uint8_t* data, size_t size, const DecodeOptions& options,
                               SampleField* field, QuadtreeDetails* details, std::string* error) {
  DecodeOptions o = options;
  o.whole_array_synthesis = true;  // the coefficients are kept only then
  o.void_values = true;
  o.reduce_levels = 0;
  DecodedGrid grid;
  WaveletCoefficients coefficients;
  if (Error e = decodeGridKeepingCoefficients(data, size, o, &grid, &coefficients); !e.ok()) {
    if (error) *error = e.message;
    return false;
  }
  if (!sampleFieldFromGrid(grid, field, error)) return false;
  if (grid.header.coding != GridCoding::kWavelet || coefficients.values.empty()) {
    if (error) *error = "the wavelet criterion needs a wavelet-coded grid (not stored, not tiled)";
    return false;
  }
  return detailSignals(coefficients, grid.wavelet.frac_bits, grid.header.size_x, grid.header.size_y,
                       details, error);
}

}  // namespace mrsv
