// Decoding the tiles of a tiled grid (spec 11), shared by the whole-grid
// decode (decodeGrid) and the region decode (decodeGridRegion).
#pragma once

#include <vector>

#include "mrsv/tiled_grid.h"

namespace mrsv {

// One tile to decode and the chunks of it that are present, in file order.
struct TileJob {
  uint64_t tile = 0;
  std::vector<ChunkView> chunks;
};

// Checks the tile chunks' framing against the index (spec 11.1 rules 5 and 6)
// for the chunks at container positions [first, end): `chunks[first + k]` is
// the k-th tile chunk of the file. Returns the first broken rule; `*present`
// is how many tile chunks pass it.
Error checkTileChunk(const ChunkView& chunk, const TileIndex& index, uint64_t k);

// The output lattice of a decode of `region` reduced by `levels` (spec 11.6):
// the samples g of the region with g a multiple of 2^levels on every axis.
void regionOutputSize(const GridRegion& region, int levels, uint32_t size[3]);

// The samples of `region` on its 2^levels lattice (spec 11.6) out of a grid
// decoded whole with reduce_levels = `levels`.
void cropWhole(const DecodedGrid& grid, const GridRegion& region, int levels, std::vector<uint8_t>* samples);

// spec 11.6: a decode reduced by `levels` needs tile sizes that are multiples
// of 2^levels on every axis with more than one tile; the error, or none.
Error reducedLatticeError(const TileGrid& tiles, int levels);

// Every tile has at least one band chunk, so that a decode gives samples.
bool everyTileHasABand(const std::vector<TileJob>& jobs);

// A whole decode refuses an output above the decoder's limit before decoding
// (at the last tile chunk), whether it gathers the output or hands it over by rows.
Error outputLimitError(const std::vector<TileJob>& jobs, uint64_t out_bytes, const DecodeOptions& options);

// Decodes one tile of `job` (one thread: options.threads is not read) into `tile`.
Error decodeTileJob(const TileGrid& tiles, const TileJob& job, bool complete, uint64_t end_offset,
                    const DecodeOptions& options, DecodedGrid* tile);

// Copies the part of a decoded tile at `origin` inside `region` to the output
// lattice (regionOutputSize(region, levels) = out_size).
void placeTile(const DecodedGrid& tile, const uint32_t origin[3], const GridRegion& region, int levels,
               const uint32_t out_size[3], size_t sample_bytes, uint8_t* out);

// Decodes the jobs (tiles in increasing order) with options.threads threads
// and copies the samples that fall in `region` into out->samples, laid out as
// regionOutputSize() says. `complete`: the stream ended with MEND at
// `end_offset` and every tile chunk is present, so each tile's end rules
// (spec 5.1 rules 11-13) apply. The first broken rule in file order is
// returned (at MEND, the lowest tile's). Sets out->has_samples, output_size,
// bands_decoded/total and tiles_with_samples.
Error decodeTiles(const TileGrid& tiles, const std::vector<TileJob>& jobs, bool complete,
                  uint64_t end_offset, const GridRegion& region, const DecodeOptions& options,
                  DecodedGrid* out);

// decodeTiles() over every tile of a complete stream with the samples handed
// over to options.tile_rows a row of tiles at a time, in order (tile_rows_decode.cpp).
Error decodeTileRows(const TileGrid& tiles, const std::vector<TileJob>& jobs, uint64_t end_offset,
                     const GridRegion& whole, const DecodeOptions& options, DecodedGrid* out);

// decodeGrid() for coding 2, once the container is framed, GHDR and meta read.
Error decodeTiledGrid(const DecodeOptions& options, DecodedGrid* out);

}  // namespace mrsv
