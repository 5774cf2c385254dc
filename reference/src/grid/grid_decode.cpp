// spec: 3.2, 3.3 decoding a grid stream; 3.4 canonical output.
#include <new>
#include <string>

#include "mrsv/grid.h"
#include "grid/wavelet_decode.h"
#include "tiles/tile_decode.h"

namespace mrsv {

Error decodeGrid(const uint8_t* data, size_t size, const DecodeOptions& options,
                 DecodedGrid* out) {
  return decodeGridKeepingCoefficients(data, size, options, out, nullptr);
}

Error decodeGridKeepingCoefficients(const uint8_t* data, size_t size, const DecodeOptions& options,
                                    DecodedGrid* out, WaveletCoefficients* coefficients) {
  *out = DecodedGrid{};
  if (Error e = readContainer(data, size, options.container, &out->container); !e.ok()) return e;
  const Container& c = out->container;
  if (c.chunks.empty()) return {};  // a prefix that ends before the content header

  // readContainer guarantees the first chunk is a content header; a grid
  // decoder reads the grid profile only (spec 1.6).
  if (c.chunks[0].chunk_type != kChunkGridHeader)
    return Error{Status::kUnsupportedProfile, c.chunks[0].offset, c.chunks[0].chunk_type.str(),
                 "not a grid stream (the content header is not GHDR; spec 1.6)"};
  if (Error e = parseGridHeader(c.chunks[0], &out->header); !e.ok()) return e;
  const GridHeader& h = out->header;
  const uint64_t expected_bytes = h.sampleCount() * sampleSize(h.sample_type);

  // Metadata, whatever the coding (spec 2.6).
  for (size_t i = 1; i < c.chunks.size(); ++i) {
    const ChunkView& chunk = c.chunks[i];
    if (chunk.chunk_type == kChunkMeta) {
      if (Error e = parseMetadata(chunk.payload, chunk.chunk_length, chunk.payloadOffset(),
                                  &out->metadata);
          !e.ok())
        return e;
    }
  }
  if (h.coding == GridCoding::kWavelet) return decodeWaveletGrid(options, out, coefficients);
  if (h.coding == GridCoding::kTiled) return decodeTiledGrid(options, out);

  bool seen_stored = false;
  for (size_t i = 1; i < c.chunks.size(); ++i) {
    const ChunkView& chunk = c.chunks[i];
    if (chunk.chunk_type == kChunkGridStored) {
      // spec: 3.3 GRAW: exactly the grid's samples, once.
      if (seen_stored)
        return Error{Status::kChunkOrder, chunk.offset, "GRAW", "more than one GRAW chunk"};
      seen_stored = true;
      if (chunk.chunk_length != expected_bytes)
        return Error{Status::kSampleDataMismatch, chunk.offset + 4, "GRAW.chunk_length",
                     "GRAW holds " + std::to_string(chunk.chunk_length) +
                         " bytes but the grid needs " + std::to_string(expected_bytes)};
      if (expected_bytes > options.max_output_bytes)
        return Error{Status::kResourceLimit, chunk.offset, "GRAW",
                     "grid of " + std::to_string(expected_bytes) +
                         " bytes exceeds the decoder's output limit"};
      // The API never throws (Annex A.3): a failed allocation is a resource limit.
      try {
        out->samples.assign(chunk.payload, chunk.payload + chunk.chunk_length);
      } catch (const std::bad_alloc&) {
        return Error{Status::kResourceLimit, chunk.offset, "GRAW",
                     "cannot allocate " + std::to_string(expected_bytes) + " bytes"};
      }
      out->has_samples = true;
      out->output_size[0] = h.size_x;
      out->output_size[1] = h.size_y;
      out->output_size[2] = h.size_z;
    } else if (chunk.chunk_type.critical()) {
      return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(),
                   chunk.chunk_type.str() + " in a stored grid"};
    }
    // Unknown ancillary chunks are skipped (spec 2.4).
  }
  if (c.complete && !seen_stored)
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
