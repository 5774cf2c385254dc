// Decoding of wavelet-coded grids (coding 1). spec: 5.
#pragma once

#include <memory>
#include <vector>

#include "mrsv/grid.h"
#include "wavelet/axis_plan.h"

namespace mrsv {

// The dequantised coefficients of a wavelet-coded grid as synthesis reads them:
// the padded array of `plan` in the Mallat layout, the bands not (yet) in the
// stream zero. For the quadtree's detail signals (spec 9.2), which synthesise
// each level twice.
struct WaveletCoefficients {
  wavelet::GridPlan plan;
  std::vector<int64_t> values;
};

struct WaveletState;

// The decoding of a wavelet-coded grid as steps over its chunks (spec 5.1),
// taken once GHDR is parsed (into `out`), one whole chunk at a time as the
// stream arrives: each band is decoded into the coefficient array when its
// chunk is complete, and nothing is decoded twice. With `keep`, end() also
// copies the coefficients there before synthesis; only done when the whole
// array is synthesised at once (DecodeOptions::whole_array_synthesis, or float
// samples, or reduce_levels), else left empty.
class WaveletGridSteps {
 public:
  WaveletGridSteps(const DecodeOptions& options, DecodedGrid* out, WaveletCoefficients* keep);
  ~WaveletGridSteps();
  WaveletGridSteps(const WaveletGridSteps&) = delete;
  WaveletGridSteps& operator=(const WaveletGridSteps&) = delete;

  // A whole chunk after GHDR, in stream order: WHDR, GMSK, GBND, GRES and
  // their order rules; meta and ancillary chunks are passed over.
  Error chunk(const ChunkView& chunk);
  // The stream ends, at MEND (c.complete) or as a prefix: the rules of MEND,
  // then synthesis and samples (spec 5.8) at DecodeOptions::reduce_levels.
  Error end(const Container& c);

  // Levels as they complete. completeLevel(): the finest level r (spec 5.8.3,
  // r levels above the finest) whose samples the chunks read so far fix, that
  // is every band of the levels above r is in (and for r = 0 the residual);
  // -1 before the first band. levelSamples(r), r >= 1: those samples, made by
  // synthesising in place from the last level made down to r (never from the
  // coarsest again); each r at most once, finest last. They equal a one-shot
  // decode with reduce_levels r. Needs DecodeOptions::whole_array_synthesis
  // for integer samples (else kInvalidArgument).
  int completeLevel() const;
  int maxLevels() const;
  Error levelSamples(int level, const ChunkView& last, uint32_t size[3], std::vector<uint8_t>* samples);

 private:
  DecodeOptions options_;
  DecodedGrid* out_;
  std::unique_ptr<WaveletState> s_;
};

// The steps over the chunks after the first of out->container (GHDR parsed
// into out->header), then its end: what a tile of a tiled grid decodes with
// (tiles/tiled_decode.cpp).
Error decodeWaveletGrid(const DecodeOptions& options, DecodedGrid* out,
                        WaveletCoefficients* coefficients = nullptr);

// decodeGrid() that also hands out the coefficients of a wavelet-coded grid
// (WaveletGridSteps' `keep`); defined in stream/stream_decoder.cpp.
Error decodeGridKeepingCoefficients(const uint8_t* data, size_t size, const DecodeOptions& options,
                                    DecodedGrid* out, WaveletCoefficients* coefficients);

}  // namespace mrsv
