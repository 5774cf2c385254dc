// Fuzz target: the container reader (spec 2) and the meta chunk parser (2.6).
#include <cstdint>
#include <cstdlib>

#include "fuzz_params.h"
#include "mrsv/container.h"
#include "mrsv/metadata.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsv::ContainerOptions options = mrsv::fuzz::containerOptionsFromTail(data, size);
  mrsv::Container container;
  mrsv::Error e = mrsv::readContainer(data, size, options, &container);
  uint64_t end = mrsv::kFileHeaderSize;
  for (const mrsv::ChunkView& chunk : container.chunks) {
    // Invariants of a framed chunk: inside the input, in order, not overlapping.
    if (chunk.offset < end || chunk.endOffset() > size) std::abort();
    end = chunk.endOffset();
    if (chunk.chunk_type == mrsv::kChunkMeta) {
      mrsv::Metadata metadata;
      (void)mrsv::parseMetadata(chunk.payload, chunk.chunk_length, chunk.payloadOffset(), &metadata);
    }
  }
  if (!e.ok() && (e.status == mrsv::Status::kOk || e.offset > size || e.message.empty())) std::abort();
  if (e.ok() && container.complete && container.end_chunk_offset + 12 != size) std::abort();
  return 0;
}
