// What the in-memory and the out-of-core tiled encoders share (spec 11.7):
// coding one tile, and the error figures of the whole grid.
#pragma once

#include <functional>
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

// A tile at a given step (rate and PSNR targets): the full pyramid and 2 and
// 1 levels are tried, and the one with the least sse + lambda * bits is kept,
// lambda = (ln 2 / 6) step^2, the slope of D(R) = sigma^2 2^-2R at D = step^2 / 12.
// A small tile pays for each band's cold context models and chunk framing,
// so it often does best with fewer levels (decision D77).
TileResult encodeTileSamplesAtStep(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& tile_samples,
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

// What coding every tile at one step gave: framed bytes and chunk count of
// the tile chunks, and the sum of squared errors.
struct StepTrial {
  uint64_t bytes = 0, chunks = 0;
  double sse = 0;
};

// spec 11.7: a rate or PSNR target (options.bits_per_sample or psnr) met with
// one step for every tile, found by bisection on its logarithm (a larger step
// gives fewer bytes and a lower PSNR). `trial` codes every tile with the
// options it is given (a step, no target); `keep` is called after a trial
// that meets the target, the best so far. `tally` holds the samples' figures
// (addSamples done); `metadata` is the caller's, for the meta chunk's room in
// the budget. Both tiled encoders use it, so that their streams agree.
Error searchTileStep(const GridHeader& grid, uint64_t tiles, const Metadata& metadata, const ErrorTally& tally,
                     const WaveletEncodeOptions& options,
                     const std::function<Error(const WaveletEncodeOptions&, StepTrial*)>& trial,
                     const std::function<void()>& keep, int* iterations);

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
