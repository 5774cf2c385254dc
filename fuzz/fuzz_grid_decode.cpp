// Fuzz target: the whole grid decode path that 'mrsv check' and 'mrsv decode'
// run (spec 2 and 3), with a small output limit so that a header may not
// make the fuzzer allocate gigabytes. A stream that decodes is also decoded
// by region (spec 11.5), which must give the same samples as the whole.
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "fuzz_params.h"
#include "mrsv/grid.h"
#include "mrsv/tiled_grid.h"

namespace {

// A box drawn from the input's bytes, checked against the whole decode.
void checkRegion(const uint8_t* data, size_t size, const mrsv::DecodeOptions& options,
                 const mrsv::DecodedGrid& whole) {
  const mrsv::GridHeader& h = whole.header;
  const uint32_t sizes[3] = {h.size_x, h.size_y, h.size_z};
  uint64_t seed = size;
  for (size_t i = 0; i < size && i < 64; ++i) seed = seed * 131 + data[size - 1 - i];
  mrsv::GridRegion r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = static_cast<uint32_t>(seed % sizes[a]);
    seed /= sizes[a] + 1;
    r.hi[a] = r.lo[a] + 1 + static_cast<uint32_t>(seed % (sizes[a] - r.lo[a]));
    seed /= sizes[a] + 1;
  }
  mrsv::MemoryByteSource source(data, size);
  mrsv::DecodedGrid region;
  mrsv::Error e = mrsv::decodeGridRegion(source, r, options, &region);
  // A prefix whose tiles do not all have a band has no samples as a whole,
  // but a region of tiles that do has.
  if (!e.ok() || (whole.has_samples && !region.has_samples)) std::abort();
  if (!whole.has_samples) return;
  const size_t bytes = mrsv::sampleSize(h.sample_type);
  size_t k = 0;
  for (uint32_t z = r.lo[2]; z < r.hi[2]; ++z)
    for (uint32_t y = r.lo[1]; y < r.hi[1]; ++y)
      for (uint32_t x = r.lo[0]; x < r.hi[0]; ++x, k += bytes)
        if (std::memcmp(region.samples.data() + k,
                        whole.samples.data() + ((uint64_t{z} * sizes[1] + y) * sizes[0] + x) * bytes, bytes) != 0)
          std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsv::DecodeOptions options;
  options.container = mrsv::fuzz::containerOptionsFromTail(data, size);
  options.max_output_bytes = 64u << 20;
  mrsv::DecodedGrid grid;
  mrsv::Error e = mrsv::decodeGrid(data, size, options, &grid);
  if (!e.ok() && (e.offset > size || e.message.empty())) std::abort();
  if (e.ok()) {
    if (grid.has_samples &&
        grid.samples.size() != grid.header.sampleCount() * mrsv::sampleSize(grid.header.sample_type))
      std::abort();
    (void)mrsv::canonicalGridOutput(grid);
    if (grid.header.num_dims > 0 && grid.header.sampleCount() <= (1u << 20)) checkRegion(data, size, options, grid);
  }
  return 0;
}
