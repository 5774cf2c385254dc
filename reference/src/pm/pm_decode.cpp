// spec: 6.1 decoding a PM stream: PHDR, PBAS, then PSPL batches.
#include <algorithm>
#include <new>
#include <string>

#include "bitstream/coded_payload.h"
#include "common/byte_reader.h"
#include "pm/pm_records.h"
#include "pm/pm_steps.h"

namespace mrsv {

bool isProgressiveMeshStream(const uint8_t* data, size_t size) {
  // The first chunk's type follows the 12-byte file header (spec 2.2, 2.3).
  return size >= kFileHeaderSize + 4 && data[12] == 'P' && data[13] == 'H' && data[14] == 'D' &&
         data[15] == 'R';
}

namespace {

// spec 6.3 and Annex B.5: what a decoder allocates for the whole stream.
uint64_t memoryNeeded(const PmHeader& h) {
  const uint64_t splits = h.splitCount();
  const uint64_t triangles = uint64_t{h.base_triangle_count} + 2 * splits;
  // Per vertex: position, corner, lock mark, flag context.
  return uint64_t{h.vertex_count} * (sizeof(std::array<int32_t, 3>) + 4 + 4 + 1) + triangles * 3 * 8 +
         splits * sizeof(SplitRecord);
}

// How many splits to make room for: what PHDR announces, but no more than
// kSplitsPerCodedByte per byte of coded splits actually present so far, so
// that a short hostile file cannot make the decoder allocate its whole memory
// limit up front. A split of an interior vertex codes at least one
// equiprobable bit (truncated(d), d >= 3), so real streams stay well below
// this; a stream beyond it only makes the arrays grow as they go. The room
// grows at least twofold each time, so that a stream arriving batch by batch
// moves its arrays a few times only.
constexpr uint64_t kSplitsPerCodedByte = 8;

}  // namespace

PmSteps::PmSteps(const DecodeOptions& options, DecodedMesh* out)
    : options_(options), out_(out), ctx_(new pm::PmContexts) {}

PmSteps::~PmSteps() = default;

Error PmSteps::header(const ChunkView& chunk) {
  if (Error e = parsePmHeader(chunk, &out_->header); !e.ok()) return e;
  out_->mesh.state().header = out_->header;
  return {};
}

Error PmSteps::memory(const ChunkView& chunk) const {
  const uint64_t need = memoryNeeded(out_->header);
  if (need > options_.max_output_bytes)
    return Error{Status::kResourceLimit, chunk.offset, "PHDR",
                 "the mesh needs about " + std::to_string(need) + " bytes, above the decoder's limit"};
  return {};
}

Error PmSteps::chunk(const ChunkView& chunk) {
  if (out_->stopped_early) return {};
  if (chunk.chunk_type == kChunkMeta)
    return parseMetadata(chunk.payload, chunk.chunk_length, chunk.payloadOffset(), &out_->metadata);
  try {
    if (chunk.chunk_type == kChunkBaseMesh) return base(chunk);
    if (chunk.chunk_type == kChunkSplits) return batch(chunk);
  } catch (const std::bad_alloc&) {
    return Error{Status::kResourceLimit, out_->container.chunks[0].offset, "PHDR", "out of memory"};
  }
  if (chunk.chunk_type.critical())
    return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(),
                 chunk.chunk_type.str() + " in a progressive mesh stream"};
  return {};  // unknown ancillary chunks are skipped (spec 2.4)
}

// spec 6.4 base_mesh()
Error PmSteps::base(const ChunkView& chunk) {
  ProgressiveMesh::Impl& s = out_->mesh.state();
  const PmHeader& h = s.header;
  const uint64_t at = chunk.payloadOffset();
  if (seen_base_) return Error{Status::kChunkOrder, chunk.offset, "PBAS", "more than one PBAS chunk"};
  seen_base_ = true;
  RangeDecoder rc(chunk.payload, chunk.chunk_length);
  if (!rc.validStart())
    return Error{Status::kBadEntropyPayload, at, "PBAS", "coded data must start with a 0 byte"};
  DecodingCoder coder{&rc};
  std::vector<std::array<uint32_t, 3>> triangles;
  std::string problem = pm::codeBaseMesh(coder, *ctx_, s, &triangles);
  if (!problem.empty()) {
    Status status = rc.overrun() ? Status::kBadEntropyPayload : Status::kBadBaseMesh;
    return Error{status, at, "PBAS", problem};
  }
  if (Error e = checkPayloadEnd(rc, chunk.chunk_length, at, "PBAS"); !e.ok()) return e;
  problem = s.table.build(h.base_vertex_count, triangles);
  if (!problem.empty()) return Error{Status::kBadBaseMesh, at, "PBAS", "the base mesh: " + problem};
  out_->has_mesh = true;
  if (stopsAt(options_, out_->mesh.triangleCount(), out_->mesh.vertexCount())) out_->stopped_early = true;
  return {};
}

// spec 6.7 batch(): split_count u32, then the coded splits.
Error PmSteps::batch(const ChunkView& chunk) {
  ProgressiveMesh::Impl& s = out_->mesh.state();
  const PmHeader& h = s.header;
  const uint64_t at = chunk.payloadOffset();
  if (!seen_base_) return Error{Status::kChunkOrder, chunk.offset, "PSPL", "PSPL before PBAS"};
  ByteReader r(chunk.payload, chunk.chunk_length);
  const uint32_t split_count = r.u32();
  if (r.overrun())
    return Error{Status::kBadChunkLength, chunk.offset + 4, "PSPL.chunk_length",
                 "PSPL payload shorter than its 4-byte split_count"};
  const uint32_t remaining = h.splitCount() - static_cast<uint32_t>(s.splits.size());
  if (out_->batches_decoded == h.batch_count)
    return Error{Status::kSplitCountMismatch, chunk.offset, "PSPL", "more PSPL chunks than batch_count"};
  if (split_count == 0 || split_count > remaining)
    return Error{Status::kSplitCountMismatch, at, "PSPL.split_count",
                 "split_count " + std::to_string(split_count) + " must be 1 to the " +
                     std::to_string(remaining) + " splits left"};
  coded_split_bytes_ += chunk.chunk_length;
  const uint64_t want = std::min<uint64_t>(h.splitCount(), kSplitsPerCodedByte * coded_split_bytes_);
  if (want > reserved_splits_) {
    reserved_splits_ = std::min<uint64_t>(h.splitCount(), std::max(want, 2 * reserved_splits_));
    s.reserveForSplits(reserved_splits_);
  }
  RangeDecoder rc(chunk.payload + 4, chunk.chunk_length - 4);
  if (!rc.validStart())
    return Error{Status::kBadEntropyPayload, at + 4, "PSPL", "coded data must start with a 0 byte"};
  DecodingCoder coder{&rc};
  BatchCursor cursor = s.beginBatch();
  for (uint32_t k = 0; k < split_count; ++k) {
    SplitRecord record;
    std::string problem = pm::codeSplit(coder, *ctx_, s, &cursor, &record);
    if (!problem.empty()) {
      Status status = rc.overrun() ? Status::kBadEntropyPayload : Status::kBadVertexSplit;
      return Error{status, at + 4, "PSPL.vertex_split",
                   "split " + std::to_string(k) + " of batch " + std::to_string(out_->batches_decoded) +
                       ": " + problem};
    }
    s.splits.push_back(record);
    s.applySplit(s.ring);
  }
  if (Error e = checkPayloadEnd(rc, chunk.chunk_length - 4, at + 4, "PSPL"); !e.ok()) return e;
  ++out_->batches_decoded;
  if (stopsAt(options_, out_->mesh.triangleCount(), out_->mesh.vertexCount())) out_->stopped_early = true;
  return {};
}

Error PmSteps::end(const Container& c) {
  if (out_->stopped_early) return {};
  const ProgressiveMesh::Impl& s = out_->mesh.state();
  const PmHeader& h = s.header;
  if (c.complete) {
    if (!seen_base_)
      return Error{Status::kChunkOrder, c.end_chunk_offset, "MEND", "a PM stream needs PBAS before MEND"};
    if (out_->batches_decoded != h.batch_count || s.splits.size() != h.splitCount())
      return Error{Status::kSplitCountMismatch, c.end_chunk_offset, "MEND",
                   std::to_string(out_->batches_decoded) + " batches with " + std::to_string(s.splits.size()) +
                       " splits, but PHDR announces " + std::to_string(h.batch_count) + " with " +
                       std::to_string(h.splitCount())};
  }
  return {};
}

}  // namespace mrsv
