// What the in-memory and the out-of-core tiled encoders share (spec 11.7):
// coding one tile, and the error figures of the whole grid.
#pragma once

#include <limits>
#include <vector>

#include "mrsv/encode.h"

namespace mrsv {

// One tile's stream as the tiled stream takes it: its chunks after GHDR
// (meta and MEND left out) and its measured error.
struct TileResult {
  std::vector<std::pair<ChunkType, std::vector<uint8_t>>> chunks;
  uint64_t bytes = 0;  // framed size of the chunks
  double sse = 0, max_abs = 0;
  int levels = 0;
  Error error;
};

TileResult encodeTileSamples(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& tile_samples,
                             const WaveletEncodeOptions& options);

// The samples of `tile` out of a buffer that holds the box [box_origin,
// box_origin + box_size) of the grid.
std::vector<uint8_t> tileSamplesFrom(const TileGrid& tiles, uint64_t tile, const uint8_t* box,
                                     const uint32_t box_origin[3], const uint32_t box_size[3]);

// The error figures of a whole tiled grid, gathered tile by tile: the valid
// samples' count and range (the PSNR's peak) and the tiles' errors.
struct ErrorTally {
  uint64_t valid = 0;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  double sse = 0, max_abs = 0;
  int levels = 0;

  void addSamples(const GridHeader& h, const uint8_t* samples, size_t size);
  void addTile(const TileResult& r);
  // `metadata` with the error_* entries of spec 2.6; fills the report's figures.
  Metadata record(const Metadata& metadata, const WaveletEncodeOptions& options, WaveletEncodeReport* report) const;
  // `metadata` with error entries of the longest text: their room in a rate budget.
  static Metadata probe(const Metadata& metadata);
};

// The TIDX payload for these per-tile chunk payload lengths and each tile's
// chunk count; refuses an index or a chunk count beyond the limits of Annex B.1.
Error tileIndexPayload(const std::vector<std::vector<uint32_t>>& lengths, std::vector<uint8_t>* index,
                       std::vector<uint8_t>* counts);

// spec 2.3: the framed bytes of a chunk (type, length, payload, CRC-32C).
std::vector<uint8_t> framedChunk(const ChunkType& type, const uint8_t* payload, uint32_t length);

// The bytes before the tile chunks of a tiled stream: file header, GHDR, meta
// (with the recorded error figures), TINF and TIDX.
std::vector<uint8_t> tiledStreamHead(const GridHeader& grid, const Metadata& recorded, const TilingHeader& tiling,
                                     const std::vector<uint8_t>& index);

}  // namespace mrsv
