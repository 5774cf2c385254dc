// spec: 7.1 decoding a PT stream: THDR, TBAS, then TSPL batches.
#include <algorithm>
#include <new>
#include <string>

#include "bitstream/coded_payload.h"
#include "common/byte_reader.h"
#include "pt/pt_coding.h"
#include "pt/pt_state.h"
#include "pt/pt_steps.h"

namespace mrsv {

bool isProgressiveTetStream(const uint8_t* data, size_t size) {
  return size >= kFileHeaderSize + 4 && data[12] == 'T' && data[13] == 'H' && data[14] == 'D' && data[15] == 'R';
}

namespace {

// spec Annex B.6: what a decoder holds for the whole stream, estimated from
// THDR before anything is allocated, as startFromBase() reserves it: per
// vertex its position, values, list record and link tag; per tet its corners
// and the room of eight list entries; per split its record, its tet count
// and 12 moved tets and 6 cut vertices.
uint64_t memoryNeeded(const PtHeader& h) {
  return uint64_t{h.vertex_count} * (12 + 4 * h.fields.size() + 24) + uint64_t{h.tet_count} * (16 + 32) +
         uint64_t{h.splitCount()} * (sizeof(PtSplitRecord) + 4 + 48 + 24);
}

// spec 7.7 one split record: the cut, then vt's position and values.
std::string decodeSplit(DecodingCoder& coder, pt::PtContexts& ctx, ProgressiveTetMesh::Impl& s, uint32_t vs) {
  const PtHeader& h = s.header;
  if (s.mesh.incident.size(vs) > 3 * size_t{kMaxSplitLinkVertices})
    return "the star of vs has more tets than a link of " + std::to_string(kMaxSplitLinkVertices) + " vertices can hold";
  s.star_link.build(s.mesh, vs);
  if (s.star_link.vertices.size() > kMaxSplitLinkVertices)
    return "the link of vs has " + std::to_string(s.star_link.vertices.size()) + " vertices, more than " +
           std::to_string(kMaxSplitLinkVertices);
  bool closed = false;
  std::string problem = pt::codeCut(coder, ctx, s.star_link, &s.scratch, &s.walk_local, &closed);
  if (!problem.empty()) return problem;
  s.walk_global.clear();
  for (uint32_t local : s.walk_local) s.walk_global.push_back(s.star_link.vertices[local]);
  Point3i position{0, 0, 0};
  int32_t values[kMaxTetFields] = {};
  problem = pt::codeSplitValues(coder, ctx, h, s.mesh, vs, s.walk_global.data(),
                                static_cast<uint32_t>(s.walk_global.size()), &position, values);
  if (!problem.empty()) return problem;
  s.mesh.positions.push_back(position);
  s.mesh.scalars.insert(s.mesh.scalars.end(), values, values + h.fields.size());
  if (s.mesh.tets.size() + cutEdgeCount(static_cast<uint32_t>(s.walk_global.size()), closed) > h.tet_count)
    problem = "the split would make more tets than tet_count";
  else
    problem = s.applyDecodedSplit(vs, closed);
  if (!problem.empty()) {
    s.mesh.positions.pop_back();
    s.mesh.scalars.resize(s.mesh.scalars.size() - h.fields.size());
  }
  return problem;
}

}  // namespace

PtSteps::PtSteps(const DecodeOptions& options, DecodedTetMesh* out)
    : options_(options), out_(out), ctx_(new pt::PtContexts) {}

PtSteps::~PtSteps() = default;

Error PtSteps::header(const ChunkView& chunk) {
  if (Error e = parsePtHeader(chunk, &out_->header); !e.ok()) return e;
  out_->mesh.state().header = out_->header;
  return {};
}

Error PtSteps::memory(const ChunkView& chunk) const {
  const uint64_t need = memoryNeeded(out_->header);
  if (need > options_.max_output_bytes)
    return Error{Status::kResourceLimit, chunk.offset, "THDR",
                 "the mesh needs about " + std::to_string(need) + " bytes, above the decoder's limit"};
  return {};
}

Error PtSteps::chunk(const ChunkView& chunk) {
  if (out_->stopped_early) return {};
  if (chunk.chunk_type == kChunkMeta)
    return parseMetadata(chunk.payload, chunk.chunk_length, chunk.payloadOffset(), &out_->metadata);
  try {
    if (chunk.chunk_type == kChunkTetBase) return base(chunk);
    if (chunk.chunk_type == kChunkTetSplits) return batch(chunk);
  } catch (const std::bad_alloc&) {
    return Error{Status::kResourceLimit, out_->container.chunks[0].offset, "THDR", "out of memory"};
  }
  if (chunk.chunk_type.critical())
    return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(),
                 chunk.chunk_type.str() + " in a progressive tet mesh stream"};
  return {};  // unknown ancillary chunks are skipped (spec 2.4)
}

// spec 7.4 base_mesh()
Error PtSteps::base(const ChunkView& chunk) {
  ProgressiveTetMesh::Impl& s = out_->mesh.state();
  const PtHeader& h = s.header;
  const uint64_t at = chunk.payloadOffset();
  if (seen_base_) return Error{Status::kChunkOrder, chunk.offset, "TBAS", "more than one TBAS chunk"};
  seen_base_ = true;
  RangeDecoder rc(chunk.payload, chunk.chunk_length);
  if (!rc.validStart()) return Error{Status::kBadEntropyPayload, at, "TBAS", "coded data must start with a 0 byte"};
  DecodingCoder coder{&rc};
  std::string problem = pt::codeBaseMesh(coder, *ctx_, h, &s.mesh);
  if (!problem.empty()) {
    const Status status = rc.overrun() ? Status::kBadEntropyPayload : Status::kBadBaseMesh;
    return Error{status, at, "TBAS", problem};
  }
  if (Error e = checkPayloadEnd(rc, chunk.chunk_length, at, "TBAS"); !e.ok()) return e;
  problem = s.startFromBase();
  if (!problem.empty()) return Error{Status::kBadBaseMesh, at, "TBAS", "the base mesh: " + problem};
  out_->has_mesh = true;
  if (stopsAt(options_, out_->mesh.tetCount(), out_->mesh.vertexCount())) out_->stopped_early = true;
  return {};
}

// spec 7.7 batch(): split_count u32, then the coded flags and splits.
Error PtSteps::batch(const ChunkView& chunk) {
  ProgressiveTetMesh::Impl& s = out_->mesh.state();
  const PtHeader& h = s.header;
  const uint64_t at = chunk.payloadOffset();
  pt::PtContexts& ctx = *ctx_;
  if (!seen_base_) return Error{Status::kChunkOrder, chunk.offset, "TSPL", "TSPL before TBAS"};
  if (out_->batches_decoded == h.batch_count)
    return Error{Status::kSplitCountMismatch, chunk.offset, "TSPL", "more TSPL chunks than batch_count"};
  ByteReader r(chunk.payload, chunk.chunk_length);
  const uint32_t split_count = r.u32();
  if (r.overrun())
    return Error{Status::kBadChunkLength, chunk.offset + 4, "TSPL.chunk_length",
                 "TSPL payload shorter than its 4-byte split_count"};
  const uint32_t remaining = h.splitCount() - static_cast<uint32_t>(s.splits.size());
  if (split_count == 0 || split_count > remaining)
    return Error{Status::kSplitCountMismatch, at, "TSPL.split_count",
                 "split_count " + std::to_string(split_count) + " must be 1 to the " + std::to_string(remaining) +
                     " splits left"};
  RangeDecoder rc(chunk.payload + 4, chunk.chunk_length - 4);
  if (!rc.validStart())
    return Error{Status::kBadEntropyPayload, at + 4, "TSPL", "coded data must start with a 0 byte"};
  DecodingCoder coder{&rc};
  // A batch applies to the finest level decoded (7.7): a caller of the
  // streaming decoder may have moved to a coarser one between chunks.
  out_->mesh.setLevel(out_->mesh.splitsDecoded());
  const uint32_t vertices = s.mesh.vertexCount();
  uint32_t done = 0, v = 0;
  // Made once, not per flag: the flag loop runs about 30 times per split.
  auto fail = [&](const std::string& problem) {
    const Status status = rc.overrun() ? Status::kBadEntropyPayload : Status::kBadVertexSplit;
    return Error{status, at + 4, "TSPL.vertex_split",
                 "batch " + std::to_string(out_->batches_decoded) + ", split " + std::to_string(done) +
                     " (vertex " + std::to_string(v) + "): " + problem};
  };
  // 7.7.1: a group flag per kSplitGroup vertices; in a group whose flag is
  // 1, the flags up to the next 1 are one run of the range decoder (the
  // context is read as each flag is decoded; the run stops before the split
  // that changes the counts), and the group's last flag is implied when no
  // flag of the group was 1 before it.
  const IncidenceLists& incident = s.mesh.incident;
  static_assert(2 * (pt::kFlagContexts - 1) < 255, "the contexts are told apart below 255 tets");
  auto context = [&](uint32_t u) { return std::min<uint32_t>(incident.sizeUpTo255(u) / 2, pt::kFlagContexts - 1); };
  int previous_group = 0;
  while (done < split_count) {
    if (v == vertices) return fail("the flags end before split_count splits");
    const uint32_t group_end = std::min(v + pt::kSplitGroup, vertices);
    previous_group = rc.bit(&ctx.group_flag[previous_group]);
    if (previous_group == 0) {
      v = group_end;
      continue;
    }
    // Until the group's first split its last flag is implied, so the run ends one before it.
    uint32_t run_end = group_end - 1;
    while (done < split_count) {
      v = rc.firstOne(ctx.split_flag, v, run_end, context);
      if (v == run_end && run_end == group_end) break;  // no more splits in the group
      if (std::string problem = decodeSplit(coder, ctx, s, v); !problem.empty()) return fail(problem);
      ++done;
      ++v;
      run_end = group_end;
    }
    v = group_end;
  }
  if (Error e = checkPayloadEnd(rc, chunk.chunk_length - 4, at + 4, "TSPL"); !e.ok()) return e;
  ++out_->batches_decoded;
  if (stopsAt(options_, out_->mesh.tetCount(), out_->mesh.vertexCount())) out_->stopped_early = true;
  return {};
}

Error PtSteps::end(const Container& c) {
  if (out_->stopped_early) return {};
  const ProgressiveTetMesh::Impl& s = out_->mesh.state();
  const PtHeader& h = s.header;
  if (c.complete) {
    if (!seen_base_)
      return Error{Status::kChunkOrder, c.end_chunk_offset, "MEND", "a PT stream needs TBAS before MEND"};
    // The finest level's tets, whatever level a streaming caller moved to.
    const uint32_t tets = out_->mesh.tetCountAt(out_->mesh.splitsDecoded());
    if (out_->batches_decoded != h.batch_count || s.splits.size() != h.splitCount() || tets != h.tet_count)
      return Error{Status::kSplitCountMismatch, c.end_chunk_offset, "MEND",
                   std::to_string(out_->batches_decoded) + " batches with " + std::to_string(s.splits.size()) +
                       " splits and " + std::to_string(tets) + " tets, but THDR announces " +
                       std::to_string(h.batch_count) + " with " + std::to_string(h.splitCount()) + " and " +
                       std::to_string(h.tet_count)};
  }
  return {};
}

}  // namespace mrsv
