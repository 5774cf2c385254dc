// Incremental decoding: a decoder fed the bytes of a stream as they arrive (a
// network, a pipe) in pieces of any size, that decodes each chunk once, as
// soon as the chunk is complete, and hands out each unit then: for grids each
// band (and, on request, each resolution level's samples), for progressive
// meshes each batch of splits applied to the mesh. Tiled grids (spec 11) are
// framed as they arrive and their tiles decoded by finish(). spec: 2.7
// (informative).
//
// Whatever the pieces, the result, errors included, is that of the one-shot
// decoders (decodeGrid, decodeProgressiveMesh, decodeProgressiveTetMesh),
// which are this decoder fed all the bytes at once: the same status, offset,
// field and message, the error Annex A.2 ranks first. A rule broken is seen
// when the chunk breaking it is complete: problem() then holds it and nothing
// after it is decoded or handed out. Framing errors (2.2, 2.3, 2.5) come first
// in A.2 and the first of them is final: feed() returns it. Any other error
// may still be outranked by a later chunk's framing (or, for payloads, by the
// meta chunk), so finish() reports it; the rules that need the end of the
// stream (MEND, a truncated chunk, bytes after MEND) are finish()'s too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/status.h"

namespace mrsv {

// What the content header (the first chunk, spec 2.5) says the stream holds.
enum class StreamContent { kUnknown, kGrid, kMesh, kTetMesh };

// A chunk decoded, in stream order.
struct StreamUnit {
  ChunkType chunk_type{};
  uint64_t offset = 0;      // of the chunk in the stream
  uint64_t end_offset = 0;  // just past its CRC
  // GBND: the band's number; PSPL, TSPL: the batch's number (from 0).
  uint32_t index = 0;
  // Grids: the finest resolution level whose samples are complete after this
  // chunk (StreamDecoder::gridCompleteLevel()), -1 if none yet.
  int complete_level = -1;
};

class StreamDecoder {
 public:
  // `expect` kUnknown takes any content; otherwise another content header is
  // kUnsupportedProfile, as the one-shot decoder of `expect` says.
  explicit StreamDecoder(const DecodeOptions& options = DecodeOptions{},
                         StreamContent expect = StreamContent::kUnknown);
  ~StreamDecoder();
  StreamDecoder(StreamDecoder&&) noexcept;
  StreamDecoder& operator=(StreamDecoder&&) noexcept;

  // The next `size` bytes of the stream. The bytes of a chunk that is not yet
  // complete are copied; complete chunks are decoded straight from `data`,
  // which need not outlive the call. Returns framing errors (final: every
  // later call returns it too).
  Error feed(const uint8_t* data, size_t size);
  // The stream ends: the rules of its end (spec 2.3, 2.5, and each profile's),
  // then the final outputs (a grid's samples). With
  // ContainerOptions::allow_partial_tail an incomplete last chunk is ignored,
  // as a one-shot decode of the same bytes ignores it. Once only.
  Error finish();
  // finish() for a stream cut short on purpose (a byte budget, mrsv decode
  // --bytes): an incomplete last chunk is ignored, as with allow_partial_tail.
  Error finishPrefix();

  // The final error (from feed() or finish()), and the first rule broken in
  // stream order so far (see above).
  const Error& error() const;
  const Error& problem() const;
  bool finished() const;
  uint64_t bytesFed() const;
  StreamContent content() const;
  // The units decoded since the last call.
  std::vector<StreamUnit> takeUnits();

  // The results so far (the one of content()); after finish() those of the
  // one-shot decoders. Chunk views in `container` have a null payload (the
  // bytes are not kept).
  DecodedGrid& grid();
  DecodedMesh& mesh();
  DecodedTetMesh& tetMesh();

  // Grids, wavelet-coded: the finest level r (r levels above the finest, spec
  // 5.8.3) whose samples the bands read so far fix; -1 when none (stored
  // grids: -1 until finish()). gridLevelSamples(r), for 1 <= r <=
  // gridCompleteLevel() and r >= DecodeOptions::reduce_levels: the samples of
  // level r, equal to a one-shot decode of these bytes with reduce_levels r,
  // made by synthesising in place from the last level asked down to r: ask
  // each level at most once, coarse to fine. The finest level comes from
  // finish(). Needs DecodeOptions::whole_array_synthesis (which decodes the
  // same samples) for integer grids, else kInvalidArgument.
  int gridCompleteLevel() const;
  Error gridLevelSamples(int level, uint32_t size[3], std::vector<uint8_t>* samples);

  struct Impl;

 private:
  friend struct OneShotAccess;  // the one-shot decoders (stream_decoder.cpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrsv
