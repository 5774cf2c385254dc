// Fuzz target: the whole grid decode path that 'mrsv check' and 'mrsv decode'
// run (spec 2 and 3), with a small output limit so that a header may not
// make the fuzzer allocate gigabytes.
#include <cstdint>
#include <cstdlib>

#include "fuzz_params.h"
#include "mrsv/grid.h"

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
  }
  return 0;
}
