// spec: 11.2 tiling_header() (TINF), 11.3 tile_index() (TIDX) and the order
// of tile chunks; the tile boxes; byte sources for region decoding.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "common/byte_reader.h"
#include "common/byte_writer.h"
#include "mrsv/tiled_grid.h"

namespace mrsv {

namespace {
const char* const kAxisNames[3] = {"x", "y", "z"};
}  // namespace

std::string tilingProblem(const TilingHeader& tiling, const GridHeader& grid) {
  uint64_t tiles = 1;
  const uint32_t sizes[3] = {grid.size_x, grid.size_y, grid.size_z};
  for (int a = 0; a < 3; ++a) {
    const uint32_t t = tiling.tile_size[a];
    std::string name = std::string("tile_size_") + kAxisNames[a];
    if (a < grid.num_dims && (t < 1 || t > kMaxGridAxis))
      return name + " must be 1 to " + std::to_string(kMaxGridAxis);
    if (a >= grid.num_dims && t != 1) return name + " must be 1 beyond num_dims";
    tiles *= (sizes[a] + uint64_t{t} - 1) / t;
  }
  if (tiles > kMaxTiles)
    return "the tiling makes " + std::to_string(tiles) + " tiles, above the limit of " +
           std::to_string(kMaxTiles);
  return {};
}

Error parseTilingHeader(const ChunkView& chunk, const GridHeader& grid, TilingHeader* out) {
  const uint64_t q = chunk.payloadOffset();
  if (chunk.chunk_length != kTilingHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "TINF.chunk_length",
                 "TINF must be 16 bytes, not " + std::to_string(chunk.chunk_length)};
  ByteReader r(chunk.payload, chunk.chunk_length);
  TilingHeader t;
  for (uint32_t& size : t.tile_size) size = r.u32();
  const uint32_t reserved = r.u32();
  // Rules 2 and 3 of spec 11.2, axis by axis, then the tile count.
  for (int a = 0; a < 3; ++a) {
    const bool inside = a < grid.num_dims;
    if ((inside && (t.tile_size[a] < 1 || t.tile_size[a] > kMaxGridAxis)) ||
        (!inside && t.tile_size[a] != 1))
      return Error{Status::kBadTiling, q + 4 * a, std::string("TINF.tile_size_") + kAxisNames[a],
                   inside ? "a tile size must be 1 to " + std::to_string(kMaxGridAxis)
                          : std::string("a tile size must be 1 beyond num_dims")};
  }
  if (reserved != 0)
    return Error{Status::kReservedNonZero, q + 12, "TINF.reserved", "reserved bytes must be 0"};
  if (std::string problem = tilingProblem(t, grid); !problem.empty())
    return Error{Status::kBadTiling, q, "TINF", problem};
  *out = t;
  return {};
}

std::vector<uint8_t> serializeTilingHeader(const TilingHeader& tiling) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  for (uint32_t size : tiling.tile_size) w.u32(size);
  w.u32(0);
  return out;
}

TileGrid TileGrid::make(const GridHeader& grid, const TilingHeader& tiling) {
  TileGrid g;
  g.grid = grid;
  g.tiling = tiling;
  const uint32_t sizes[3] = {grid.size_x, grid.size_y, grid.size_z};
  for (int a = 0; a < 3; ++a)
    g.count[a] = static_cast<uint32_t>((sizes[a] + uint64_t{tiling.tile_size[a]} - 1) / tiling.tile_size[a]);
  return g;
}

void TileGrid::box(uint64_t tile, uint32_t origin[3], uint32_t size[3]) const {
  const uint32_t sizes[3] = {grid.size_x, grid.size_y, grid.size_z};
  uint64_t rest = tile;
  for (int a = 0; a < 3; ++a) {
    const uint32_t i = static_cast<uint32_t>(rest % count[a]);
    rest /= count[a];
    origin[a] = i * tiling.tile_size[a];
    size[a] = std::min(tiling.tile_size[a], sizes[a] - origin[a]);
  }
}

GridHeader TileGrid::tileHeader(uint64_t tile) const {
  uint32_t origin[3], size[3];
  box(tile, origin, size);
  GridHeader h = grid;
  h.coding = GridCoding::kWavelet;
  h.size_x = size[0];
  h.size_y = size[1];
  h.size_z = size[2];
  return h;
}

std::vector<std::pair<uint32_t, uint8_t>> tileChunkOrder(const std::vector<uint8_t>& chunk_count) {
  // Round r holds the r-th chunk of every tile that has more than r, in tile
  // order; the tiles still in play shrink round by round, so this is linear
  // in the number of chunks plus rounds.
  std::vector<std::pair<uint32_t, uint8_t>> order;
  std::vector<uint32_t> active(chunk_count.size());
  for (uint32_t t = 0; t < active.size(); ++t) active[t] = t;
  for (unsigned r = 0; !active.empty(); ++r) {
    size_t kept = 0;
    for (uint32_t t : active) {
      if (chunk_count[t] <= r) continue;
      order.emplace_back(t, static_cast<uint8_t>(r));
      active[kept++] = t;
    }
    active.resize(kept);
  }
  return order;
}

Error parseTileIndex(const ChunkView& chunk, uint64_t tiles, TileIndex* out) {
  const uint64_t q = chunk.payloadOffset();
  auto fail = [&](uint64_t at, std::string field, std::string message) {
    return Error{Status::kBadTileIndex, at, "TIDX." + field, std::move(message)};
  };
  if (chunk.chunk_length < tiles)
    return fail(chunk.offset + 4, "chunk_length",
                "TIDX needs at least one byte per tile (" + std::to_string(tiles) + " tiles)");
  TileIndex index;
  index.chunk_count.assign(chunk.payload, chunk.payload + tiles);
  index.first.resize(tiles + 1);
  uint64_t total = 0;
  for (uint64_t t = 0; t < tiles; ++t) {
    if (index.chunk_count[t] == 0)
      return fail(q + t, "chunk_count", "tile " + std::to_string(t) + " has no chunk (it needs its WHDR)");
    index.first[t] = total;
    total += index.chunk_count[t];
  }
  index.first[tiles] = total;
  if (chunk.chunk_length != tiles + 4 * total)
    return fail(chunk.offset + 4, "chunk_length",
                "TIDX must be " + std::to_string(tiles + 4 * total) + " bytes for " +
                    std::to_string(total) + " tile chunks, not " + std::to_string(chunk.chunk_length));
  ByteReader r(chunk.payload + tiles, chunk.chunk_length - tiles);
  index.chunk_length.resize(total);
  for (uint64_t i = 0; i < total; ++i) {
    index.chunk_length[i] = r.u32();
    if (index.chunk_length[i] > kMaxChunkPayload)
      return fail(q + tiles + 4 * i, "chunk_length[" + std::to_string(i) + "]",
                  "a tile chunk length above the limit of " + std::to_string(kMaxChunkPayload));
  }
  // Offsets in file order (spec 11.3): tile chunks follow TIDX back to back.
  index.chunk_offset.resize(total);
  index.position.resize(total);
  index.schedule.reserve(total);
  uint64_t pos = chunk.endOffset();
  for (const auto& [tile, nth] : tileChunkOrder(index.chunk_count)) {
    const uint64_t entry = index.first[tile] + nth;
    index.position[entry] = index.schedule.size();
    index.schedule.push_back(entry);
    index.chunk_offset[entry] = pos;
    pos += kChunkHeaderSize + uint64_t{index.chunk_length[entry]} + kChunkCrcSize;
  }
  index.end_offset = pos;
  *out = std::move(index);
  return {};
}

std::vector<uint8_t> serializeTileIndex(const std::vector<std::vector<uint32_t>>& lengths) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  for (const auto& tile : lengths) w.u8(static_cast<uint8_t>(tile.size()));
  for (const auto& tile : lengths)
    for (uint32_t length : tile) w.u32(length);
  return out;
}

std::string regionProblem(const GridRegion& region, const GridHeader& grid) {
  const uint32_t sizes[3] = {grid.size_x, grid.size_y, grid.size_z};
  for (int a = 0; a < 3; ++a) {
    if (region.lo[a] >= region.hi[a])
      return std::string("the region is empty along ") + kAxisNames[a];
    if (region.hi[a] > sizes[a])
      return std::string("the region ends at ") + kAxisNames[a] + " = " + std::to_string(region.hi[a]) +
             ", beyond the grid's " + std::to_string(sizes[a]) + " samples";
  }
  return {};
}

bool ByteSource::read(uint64_t offset, size_t n, uint8_t* out) {
  if (offset > size() || n > size() - offset) return false;
  if (!readAt(offset, n, out)) return false;
  bytes_read_ += n;
  return true;
}

bool MemoryByteSource::readAt(uint64_t offset, size_t n, uint8_t* out) {
  if (n > 0) std::memcpy(out, data_ + offset, n);
  return true;
}

namespace {
class FileByteSource : public ByteSource {
 public:
  FileByteSource(int fd, uint64_t size) : fd_(fd), size_(size) {}
  ~FileByteSource() override { ::close(fd_); }
  uint64_t size() const override { return size_; }

 protected:
  bool readAt(uint64_t offset, size_t n, uint8_t* out) override {
    while (n > 0) {
      ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      out += got;
      offset += static_cast<uint64_t>(got);
      n -= static_cast<size_t>(got);
    }
    return true;
  }

 private:
  int fd_;
  uint64_t size_;
};
}  // namespace

std::unique_ptr<ByteSource> openFileByteSource(const std::string& path, std::string* error) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *error = std::strerror(errno);
    return nullptr;
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    *error = "not a regular file";
    ::close(fd);
    return nullptr;
  }
  return std::make_unique<FileByteSource>(fd, static_cast<uint64_t>(st.st_size));
}

}  // namespace mrsv
