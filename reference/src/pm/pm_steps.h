// The decoding of a PM stream (spec 6.1) as steps over its chunks, taken one
// whole chunk at a time as the stream arrives: each batch of splits is applied
// to the mesh when its PSPL chunk is complete. The streaming decoder
// (stream/stream_decoder.cpp) drives them; decodeProgressiveMesh() is that
// decoder fed all the bytes at once.
#pragma once

#include <memory>

#include "mrsv/progressive_mesh.h"

namespace mrsv {
namespace pm {
struct PmContexts;
}

class PmSteps {
 public:
  PmSteps(const DecodeOptions& options, DecodedMesh* out);
  ~PmSteps();
  PmSteps(const PmSteps&) = delete;
  PmSteps& operator=(const PmSteps&) = delete;

  // PHDR, the stream's first chunk.
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
  DecodedMesh* out_;
  std::unique_ptr<pm::PmContexts> ctx_;
  bool seen_base_ = false;
  uint64_t coded_split_bytes_ = 0;  // PSPL payload bytes so far
  uint64_t reserved_splits_ = 0;
};

}  // namespace mrsv
