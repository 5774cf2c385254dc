// Tiled grids (GHDR coding 2): a grid cut into tiles (bricks in 3-D), each a
// wavelet-coded grid of its own, with an index that locates every tile's
// chunks so that a reader decodes a region from the byte ranges it needs.
// spec: 11.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/grid.h"
#include "mrsv/status.h"

namespace mrsv {

// spec: 11.2 tiling_header(), the TINF payload.
constexpr size_t kTilingHeaderSize = 16;
// Annex B.3: tiles in one grid.
constexpr uint32_t kMaxTiles = 1u << 20;

struct TilingHeader {
  uint32_t tile_size[3] = {1, 1, 1};
};

Error parseTilingHeader(const ChunkView& chunk, const GridHeader& grid, TilingHeader* out);
std::vector<uint8_t> serializeTilingHeader(const TilingHeader& tiling);
// Empty when `tiling` obeys spec 11.2 for `grid`, otherwise the rule broken.
std::string tilingProblem(const TilingHeader& tiling, const GridHeader& grid);

// The tiles of a grid (spec 11.2): ceil(size / tile_size) along each axis,
// numbered x fastest; the last tile of an axis holds what remains.
struct TileGrid {
  GridHeader grid;  // the whole grid
  TilingHeader tiling;
  uint32_t count[3] = {1, 1, 1};

  static TileGrid make(const GridHeader& grid, const TilingHeader& tiling);
  uint64_t tileCount() const { return uint64_t{count[0]} * count[1] * count[2]; }
  // The tile's box in grid samples.
  void box(uint64_t tile, uint32_t origin[3], uint32_t size[3]) const;
  // The grid header a tile is decoded with (spec 11.4): the grid's, with the
  // tile's sizes and coding 1.
  GridHeader tileHeader(uint64_t tile) const;
};

// spec: 11.3 tile_index(), the TIDX payload, and the order of tile chunks.
struct TileIndex {
  std::vector<uint8_t> chunk_count;     // per tile
  std::vector<uint64_t> first;          // per tile + 1: start of its entries in the arrays below
  std::vector<uint32_t> chunk_length;   // per tile chunk, tile by tile: payload length
  std::vector<uint64_t> chunk_offset;   // per tile chunk, tile by tile: offset in the file
  std::vector<uint64_t> schedule;       // file order of tile chunks: entry numbers of the arrays above
  std::vector<uint64_t> position;       // per entry: its place in the schedule
  uint64_t end_offset = 0;              // where the last tile chunk ends

  uint64_t totalChunks() const { return chunk_length.size(); }
};

// Parses TIDX for `tiles` tiles; the first tile chunk starts at the end of the
// TIDX chunk. Fills every array of TileIndex.
Error parseTileIndex(const ChunkView& chunk, uint64_t tiles, TileIndex* out);
// The TIDX payload of per-tile chunk payload lengths, in tile order.
std::vector<uint8_t> serializeTileIndex(const std::vector<std::vector<uint32_t>>& lengths);
// spec 11.3: the round order, as (tile, chunk number) pairs.
std::vector<std::pair<uint32_t, uint8_t>> tileChunkOrder(const std::vector<uint8_t>& chunk_count);

// A half-open box of grid samples: [lo, hi) along each axis.
struct GridRegion {
  uint32_t lo[3] = {0, 0, 0};
  uint32_t hi[3] = {1, 1, 1};
};
// Empty when `region` is a non-empty box inside `grid`, otherwise why not.
std::string regionProblem(const GridRegion& region, const GridHeader& grid);

// Where a region decoder reads bytes: a file read with pread, or memory.
// Counts what it reads, so that tests and tools can show that a region decode
// reads only what it needs.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual uint64_t size() const = 0;
  // Copies bytes [offset, offset + n) to `out`; false on an I/O error or a
  // range past the end.
  bool read(uint64_t offset, size_t n, uint8_t* out);
  uint64_t bytesRead() const { return bytes_read_; }

 protected:
  virtual bool readAt(uint64_t offset, size_t n, uint8_t* out) = 0;

 private:
  uint64_t bytes_read_ = 0;
};

class MemoryByteSource : public ByteSource {
 public:
  MemoryByteSource(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint64_t size() const override { return size_; }

 protected:
  bool readAt(uint64_t offset, size_t n, uint8_t* out) override;

 private:
  const uint8_t* data_;
  size_t size_;
};

// Opens `path` for reading; null with `error` set when it cannot be opened.
std::unique_ptr<ByteSource> openFileByteSource(const std::string& path, std::string* error);

// Where an encoder that does not hold the whole grid reads samples: a box at
// a time (spec 11.7, out-of-core tiled encoding).
class GridBoxReader {
 public:
  virtual ~GridBoxReader() = default;
  // Copies the samples of [origin, origin + size), little-endian, x fastest,
  // to `out`; false with `error` set when they cannot be read.
  virtual bool read(const uint32_t origin[3], const uint32_t size[3], uint8_t* out, std::string* error) = 0;
};

// Where an encoder writes a stream it does not hold whole.
class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual bool write(const uint8_t* data, size_t size) = 0;
};

// Decodes the samples of `region` (sample coordinates of the full grid).
// A tiled grid is read through its index: the file header, the chunks up to
// TIDX and the chunks of the tiles the region touches, nothing else; their
// chunks are checked as a full decode checks them (spec 11.5). Other grids are
// read whole and cropped. With options.reduce_levels = K the output holds the
// reduced-resolution positions (spec 11.6) that stand for samples inside the
// region. `out->output_size` is the region's output size; `out->samples` its
// samples, x fastest; `out->header` the whole grid's header;
// `out->container` the chunks read up to TIDX, without their payloads.
Error decodeGridRegion(ByteSource& source, const GridRegion& region, const DecodeOptions& options,
                       DecodedGrid* out);

// spec 11.5: the canonical output of a region decode, the bytes the
// conformance suite hashes: 3.4's line for a grid of the region's sizes, then
// its samples.
std::vector<uint8_t> canonicalRegionOutput(const DecodedGrid& grid);

}  // namespace mrsv
