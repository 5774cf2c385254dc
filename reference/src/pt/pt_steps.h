// The decoding of a PT stream (spec 7.1) as steps over its chunks, taken one
// whole chunk at a time as the stream arrives: each batch of splits is applied
// to the mesh when its TSPL chunk is complete. The streaming decoder
// (stream/stream_decoder.cpp) drives them; decodeProgressiveTetMesh() is that
// decoder fed all the bytes at once.
#pragma once

#include <memory>

#include "mrsv/progressive_tet_mesh.h"

namespace mrsv {
namespace pt {
struct PtContexts;
}

class PtSteps {
 public:
  PtSteps(const DecodeOptions& options, DecodedTetMesh* out);
  ~PtSteps();
  PtSteps(const PtSteps&) = delete;
  PtSteps& operator=(const PtSteps&) = delete;

  // THDR, the stream's first chunk.
  Error header(const ChunkView& chunk);
  // The memory the header announces against DecodeOptions::max_output_bytes
  // (spec 6.2, 7.2), checked after the meta chunk (Annex A.2), wherever it is.
  Error memory(const ChunkView& chunk) const;
  // Any later whole chunk but MEND, in stream order. After DecodeOptions' stop
  // (out->stopped_early) chunks are passed over.
  Error chunk(const ChunkView& chunk);
  // The stream ends, at MEND (c.complete) or as a prefix.
  Error end(const Container& c);

 private:
  Error base(const ChunkView& chunk);
  Error batch(const ChunkView& chunk);

  DecodeOptions options_;
  DecodedTetMesh* out_;
  std::unique_ptr<pt::PtContexts> ctx_;
  bool seen_base_ = false;
};

}  // namespace mrsv
