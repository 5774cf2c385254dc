// The decoding of a grid stream (spec 3.2, 3.3) as steps over its chunks,
// taken one whole chunk at a time as the stream arrives. The streaming decoder
// (stream/stream_decoder.cpp) drives them; decodeGrid() is that decoder fed
// all the bytes at once.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "grid/wavelet_decode.h"
#include "mrsv/grid.h"

namespace mrsv {

class GridSteps {
 public:
  GridSteps(const DecodeOptions& options, DecodedGrid* out, WaveletCoefficients* keep = nullptr)
      : options_(options), out_(out), keep_(keep) {}

  // GHDR, the stream's first chunk.
  Error header(const ChunkView& chunk);
  // Any later whole chunk but MEND, in stream order.
  Error chunk(const ChunkView& chunk);
  // The stream ends, at MEND (c.complete) or as a prefix.
  Error end(const Container& c);
  // The wavelet steps of a wavelet-coded grid once GHDR is read, else null.
  WaveletGridSteps* wavelet() { return wavelet_.get(); }
  // The chunks' bytes stay where they were given until end() (the one-shot
  // decoders): a tiled grid's need not be copied.
  void bytesOutliveSteps() { bytes_outlive_steps_ = true; }

 private:
  DecodeOptions options_;
  DecodedGrid* out_;
  WaveletCoefficients* keep_;
  std::unique_ptr<WaveletGridSteps> wavelet_;
  bool seen_stored_ = false;
  // Tiled grids (coding 2, spec 11) are decoded by end(), on every tile at
  // once (decodeTiledGrid): the chunks' payloads are kept until then, copied
  // unless the caller keeps them. Per-tile incremental decoding is left to the
  // tile layer.
  void keepPayload(const ChunkView& chunk);
  bool tiled_ = false;
  bool bytes_outlive_steps_ = false;
  std::vector<const uint8_t*> payloads_;    // by chunk position
  std::deque<std::vector<uint8_t>> copies_;
};

}  // namespace mrsv
