// The framing rules of spec 2.2-2.5 as steps over units that arrive one at a
// time: the file header, then each chunk, first its 8-byte header (type and
// length) and then the whole chunk (checksum and the order rules). readContainer()
// runs them over a whole buffer; the streaming decoder (stream_decoder.h) runs
// them as bytes arrive, so both frame a stream the same way.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mrsv/container.h"

namespace mrsv {

class ContainerFramer {
 public:
  explicit ContainerFramer(const ContainerOptions& options) : options_(options) {}

  // spec 2.2: the stream's first min(size, 12) bytes. size < 12 only when the
  // stream ends there (always an error then).
  Error fileHeader(const uint8_t* data, size_t size, Container* out);
  // spec 2.3: the 8-byte chunk header at file offset `pos`: type syntax and
  // length limit. Fills chunk_type, chunk_length and offset.
  Error chunkHeader(const uint8_t* header, uint64_t pos, ChunkView* chunk);
  // The whole chunk, `bytes` from its header to its CRC (chunk->endOffset() -
  // chunk->offset bytes): checksum, chunk count, MEND and the order rules of
  // 2.4 and 2.5. Appends it to out->chunks, or for MEND sets out->complete.
  // Sets chunk->payload into `bytes`.
  Error wholeChunk(const uint8_t* bytes, ChunkView* chunk, Container* out);
  // The stream ends at `pos` + `remaining`, inside the chunk starting at `pos`
  // (remaining > 0; its header already accepted when remaining >= 8): an error,
  // or with allow_partial_tail the bytes are ignored.
  Error endsInsideChunk(uint64_t pos, uint64_t remaining, const ChunkView& chunk, Container* out) const;
  // The stream ends `extra` bytes after the MEND chunk (extra > 0).
  static Error trailingBytes(const Container& c, uint64_t extra);
  // From now on endsInsideChunk() ignores the incomplete chunk.
  void allowPartialTail() { options_.allow_partial_tail = true; }

 private:
  ContainerOptions options_;
  bool seen_meta_ = false;
  uint32_t count_ = 0;
};

}  // namespace mrsv
