// spec: 3.2, 3.3 decoding a grid stream; 3.4 canonical output.
#include <new>
#include <string>

#include "mrsv/grid.h"
#include "grid/grid_steps.h"
#include "tiles/tile_decode.h"

namespace mrsv {

Error GridSteps::header(const ChunkView& chunk) {
  if (Error e = parseGridHeader(chunk, &out_->header); !e.ok()) return e;
  if (out_->header.coding == GridCoding::kWavelet)
    wavelet_ = std::make_unique<WaveletGridSteps>(options_, out_, keep_);
  tiled_ = out_->header.coding == GridCoding::kTiled;
  keepPayload(chunk);
  return {};
}

void GridSteps::keepPayload(const ChunkView& chunk) {
  if (!tiled_) return;
  if (bytes_outlive_steps_) {
    payloads_.push_back(chunk.payload);
  } else {
    copies_.emplace_back(chunk.payload, chunk.payload + chunk.chunk_length);
    payloads_.push_back(copies_.back().data());
  }
}

Error GridSteps::chunk(const ChunkView& chunk) {
  keepPayload(chunk);
  // Metadata, whatever the coding (spec 2.6).
  if (chunk.chunk_type == kChunkMeta)
    return parseMetadata(chunk.payload, chunk.chunk_length, chunk.payloadOffset(), &out_->metadata);
  if (wavelet_) return wavelet_->chunk(chunk);
  if (tiled_) return {};  // decoded at the end (below)
  const GridHeader& h = out_->header;
  const uint64_t expected_bytes = h.sampleCount() * sampleSize(h.sample_type);
  if (chunk.chunk_type == kChunkGridStored) {
    // spec: 3.3 GRAW: exactly the grid's samples, once.
    if (seen_stored_)
      return Error{Status::kChunkOrder, chunk.offset, "GRAW", "more than one GRAW chunk"};
    seen_stored_ = true;
    if (chunk.chunk_length != expected_bytes)
      return Error{Status::kSampleDataMismatch, chunk.offset + 4, "GRAW.chunk_length",
                   "GRAW holds " + std::to_string(chunk.chunk_length) +
                       " bytes but the grid needs " + std::to_string(expected_bytes)};
    if (expected_bytes > options_.max_output_bytes)
      return Error{Status::kResourceLimit, chunk.offset, "GRAW",
                   "grid of " + std::to_string(expected_bytes) +
                       " bytes exceeds the decoder's output limit"};
    // The API never throws (Annex A.3): a failed allocation is a resource limit.
    try {
      out_->samples.assign(chunk.payload, chunk.payload + chunk.chunk_length);
    } catch (const std::bad_alloc&) {
      return Error{Status::kResourceLimit, chunk.offset, "GRAW",
                   "cannot allocate " + std::to_string(expected_bytes) + " bytes"};
    }
    out_->has_samples = true;
    out_->output_size[0] = h.size_x;
    out_->output_size[1] = h.size_y;
    out_->output_size[2] = h.size_z;
  } else if (chunk.chunk_type.critical()) {
    return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(),
                 chunk.chunk_type.str() + " in a stored grid"};
  }
  // Unknown ancillary chunks are skipped (spec 2.4).
  return {};
}

Error GridSteps::end(const Container& c) {
  if (wavelet_) return wavelet_->end(c);
  if (tiled_) {
    // The tile decode (spec 11) reads the chunks of the container, with
    // their bytes, as kept above.
    std::vector<const uint8_t*> before;
    for (size_t i = 0; i < out_->container.chunks.size() && i < payloads_.size(); ++i) {
      before.push_back(out_->container.chunks[i].payload);
      out_->container.chunks[i].payload = payloads_[i];
    }
    Error e = decodeTiledGrid(options_, out_);
    for (size_t i = 0; i < before.size(); ++i) out_->container.chunks[i].payload = before[i];
    return e;
  }
  if (c.complete && !seen_stored_)
    return Error{Status::kChunkOrder, c.end_chunk_offset, "MEND",
                 "a stored grid needs one GRAW chunk before MEND"};
  return {};
}

namespace {
// "-" without a no-data value, else nodata_bits as 16 lowercase hex digits.
std::string nodataField(const GridHeader& h) {
  if (!h.hasNodata()) return "-";
  static const char kHex[] = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 0; i < 16; ++i) s[15 - i] = kHex[(h.nodata_bits >> (4 * i)) & 15];
  return s;
}
}  // namespace

std::vector<uint8_t> canonicalGridOutput(const DecodedGrid& grid) {
  const GridHeader& h = grid.header;
  std::string line = "mrsv-canonical-grid 1 " + std::string(sampleTypeName(h.sample_type)) + " " +
                     std::to_string(h.num_dims) + " " + std::to_string(h.size_x) + " " +
                     std::to_string(h.size_y) + " " + std::to_string(h.size_z) + " " +
                     std::to_string(grid.has_samples ? h.sampleCount() : 0) + " " +
                     nodataField(h) + "\n";
  if (grid.container.chunks.empty()) line = "mrsv-canonical-empty 1\n";
  std::vector<uint8_t> out(line.begin(), line.end());
  out.insert(out.end(), grid.samples.begin(), grid.samples.end());
  return out;
}

}  // namespace mrsv
