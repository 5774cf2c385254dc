// spec: 11.5 region decoding: the file header, the chunks up to TIDX and the
// chunks of the tiles a region touches, read by offset; nothing else.
#include <algorithm>
#include <cstring>
#include <new>

#include "common/byte_reader.h"
#include "bitstream/container_framer.h"
#include "grid/precinct_region.h"
#include "tiles/tile_decode.h"

namespace mrsv {

namespace {

Error ioError(uint64_t offset, const std::string& what) {
  return Error{Status::kIoError, offset, "file", "cannot read " + what};
}

// The whole file, when the region is decoded from a whole decode.
Error readAll(ByteSource& source, std::vector<uint8_t>* head) {
  const uint64_t size = source.size();
  head->resize(size);
  if (size > 0 && !source.read(0, size, head->data())) return ioError(0, "the file");
  return {};
}

// The bytes from the start of the file to the end of TIDX, or for a
// wavelet-coded grid in precincts to the end of WHDR (*precincts then set), read chunk by chunk so that readContainer frames
// them with the offsets of the file; otherwise (or when the header part is
// cut short) the whole file.
Error readHead(ByteSource& source, std::vector<uint8_t>* head, bool* whole_file, bool* precincts) {
  *whole_file = false;
  *precincts = false;
  const uint64_t size = source.size();
  uint64_t pos = std::min<uint64_t>(size, kFileHeaderSize);
  // The rest of the file after the chunks read so far (head holds [0, pos)).
  auto whole = [&]() -> Error {
    *whole_file = true;
    head->resize(size);
    if (size > pos && !source.read(pos, size - pos, head->data() + pos)) return ioError(pos, "the file");
    return {};
  };
  head->resize(pos);
  if (pos > 0 && !source.read(0, pos, head->data())) return ioError(0, "the file header");
  bool first = true, wavelet_grid = false;
  while (pos + kChunkHeaderSize <= size) {
    uint8_t chunk_header[kChunkHeaderSize];
    if (!source.read(pos, kChunkHeaderSize, chunk_header)) return ioError(pos, "a chunk header");
    ByteReader r(chunk_header + 4, 4);
    const uint64_t length = r.u32();
    const ChunkType type{{static_cast<char>(chunk_header[0]), static_cast<char>(chunk_header[1]),
                          static_cast<char>(chunk_header[2]), static_cast<char>(chunk_header[3])}};
    // Only the header part of a tiled grid, or of a wavelet-coded grid up to
    // its WHDR, is read this way: a first chunk other than GHDR, another
    // coding or a chunk of another kind means the whole file is needed
    // (readContainer says what is wrong).
    const bool header_part =
        type == kChunkGridHeader || type == kChunkMeta || !type.critical() ||
        (wavelet_grid ? type == kChunkWaveletHeader : type == kChunkTiling || type == kChunkTileIndex);
    if (!header_part || (first && type != kChunkGridHeader) || length > kMaxChunkPayload) return whole();
    const uint64_t end = pos + kChunkHeaderSize + length + kChunkCrcSize;
    if (end > size) return whole();
    head->resize(end);
    std::memcpy(head->data() + pos, chunk_header, kChunkHeaderSize);
    if (!source.read(pos + kChunkHeaderSize, length + kChunkCrcSize, head->data() + pos + kChunkHeaderSize))
      return ioError(pos, "a chunk");
    const uint8_t* payload = head->data() + pos + kChunkHeaderSize;
    if (first) {
      const uint8_t coding = length < 3 ? 0 : payload[2];
      wavelet_grid = coding == static_cast<uint8_t>(GridCoding::kWavelet);
      if (coding != static_cast<uint8_t>(GridCoding::kTiled) && !wavelet_grid) return whole();
    }
    first = false;
    pos = end;
    if (type == kChunkTileIndex) return {};
    if (type == kChunkWaveletHeader) {
      if (length != kWaveletHeaderSize || payload[7] == 0) return whole();
      *precincts = true;
      return {};
    }
  }
  return whole();
}

// spec 2.3 framing of one tile chunk read at its index offset, by the
// container's own framer: the checks readContainer makes, with the same codes
// and offsets. `bytes` holds the extent TIDX gives; a chunk_length other than
// that is 208 (11.1 rule 5), reported before the CRC, which cannot be read at
// the chunk's own length without reading past what the index locates.
Error frameChunk(const std::vector<uint8_t>& bytes, uint64_t offset, const ContainerOptions& options,
                 ChunkView* out) {
  ContainerFramer framer(options);
  ChunkView chunk;
  if (Error e = framer.chunkHeader(bytes.data(), offset, &chunk); !e.ok()) return e;
  if (uint64_t{kChunkHeaderSize} + chunk.chunk_length + kChunkCrcSize != bytes.size())
    return Error{Status::kBadTileIndex, offset + 4, chunk.chunk_type.str() + ".chunk_length",
                 "the chunk is " + std::to_string(chunk.chunk_length) + " bytes but TIDX says " +
                     std::to_string(bytes.size() - kChunkHeaderSize - kChunkCrcSize)};
  // A tile chunk follows the content header: the framer's order rules see one.
  Container seen;
  seen.chunks.push_back(ChunkView{kChunkGridHeader, 0, 0, 0, nullptr});
  if (Error e = framer.wholeChunk(bytes.data(), &chunk, &seen); !e.ok()) return e;
  *out = chunk;
  return {};
}

// The chunk views of a region decode point into buffers that die with the
// call: their offsets and lengths stay, their payloads are dropped.
void forgetPayloads(DecodedGrid* grid) {
  for (ChunkView& c : grid->container.chunks) c.payload = nullptr;
}

}  // namespace

void cropWhole(const DecodedGrid& grid, const GridRegion& region, int levels, std::vector<uint8_t>* samples) {
  // A grid decoded whole: its output position i stands for sample i * 2^K_a
  // (spec 5.8.3), so the region's lattice is a sub-box of it.
  const size_t bytes = sampleSize(grid.header.sample_type);
  uint32_t first[3], count[3], shift[3];
  regionOutputSize(region, levels, count);
  const uint64_t step = uint64_t{1} << levels;
  for (int a = 0; a < 3; ++a) {
    // A tiled grid decoded whole is already on the 2^K lattice (spec 11.6).
    const int native = grid.header.coding == GridCoding::kTiled ? levels
                       : a < grid.header.num_dims && grid.header.coding == GridCoding::kWavelet ? grid.wavelet.levels[a]
                                                                                                : 0;
    shift[a] = static_cast<uint32_t>(std::min<int>(levels, native));
    first[a] = static_cast<uint32_t>((uint64_t{region.lo[a]} + step - 1) / step * step);
  }
  samples->resize(uint64_t{count[0]} * count[1] * count[2] * bytes);
  const uint32_t* in = grid.output_size;
  uint8_t* dst = samples->data();
  for (uint32_t k = 0; k < count[2]; ++k)
    for (uint32_t j = 0; j < count[1]; ++j)
      for (uint32_t i = 0; i < count[0]; ++i, dst += bytes) {
        const uint64_t x = (first[0] + i * step) >> shift[0], y = (first[1] + j * step) >> shift[1],
                       z = (first[2] + k * step) >> shift[2];
        std::memcpy(dst, grid.samples.data() + ((z * in[1] + y) * in[0] + x) * bytes, bytes);
      }
}


Error decodeGridRegion(ByteSource& source, const GridRegion& region, const DecodeOptions& options,
                       DecodedGrid* out) {
  *out = DecodedGrid{};
  std::vector<uint8_t> head;
  bool whole_file = false, precincts = false;
  if (Error e = readHead(source, &head, &whole_file, &precincts); !e.ok()) return e;
  if (precincts) {
    // A wavelet-coded grid in precincts: the blocks the region reaches (spec
    // 5.7.6). Should that way not read the stream, the whole file is decoded.
    DecodeOptions head_options = options;
    head_options.container.allow_partial_tail = true;
    DecodedGrid parsed;
    Error io;
    bool decoded = false;
    try {
      decoded = decodeGrid(head.data(), head.size(), head_options, &parsed).ok() &&
                regionProblem(region, parsed.header).empty() &&
                decodePrecinctRegion(source, head.size(), parsed, region, options, out, &io);
    } catch (const std::bad_alloc&) {
      decoded = false;  // the whole decode says what the memory allows (901)
    }
    if (decoded) {
      forgetPayloads(out);
      return {};
    }
    if (!io.ok()) return io;
    if (Error e = readAll(source, &head); !e.ok()) return e;
    whole_file = true;
  }
  DecodeOptions head_options = options;
  if (!whole_file) head_options.container.allow_partial_tail = true;
  DecodedGrid parsed;
  if (Error e = decodeGrid(head.data(), head.size(), head_options, &parsed); !e.ok()) {
    *out = std::move(parsed);
    forgetPayloads(out);
    return e;
  }
  if (parsed.container.chunks.empty()) {
    *out = std::move(parsed);
    return {};
  }
  if (std::string problem = regionProblem(region, parsed.header); !problem.empty())
    return Error{Status::kInvalidArgument, 0, "region", problem};
  if (whole_file) {
    // Not tiled (or a tiled stream cut before its index): the grid decoded
    // whole, then cropped.
    std::vector<uint8_t> cropped;
    if (parsed.has_samples) cropWhole(parsed, region, options.reduce_levels, &cropped);
    *out = std::move(parsed);
    out->samples = std::move(cropped);
    regionOutputSize(region, options.reduce_levels, out->output_size);
    forgetPayloads(out);
    return {};
  }
  // A tiled grid: `parsed` holds GHDR, meta, TINF and TIDX (decodeTiledGrid
  // read them as a prefix). The index gives every tile chunk's place.
  const Container& c = parsed.container;
  const ChunkView& tidx = c.chunks.back();
  TilingHeader tiling;
  std::copy(parsed.tile_size, parsed.tile_size + 3, tiling.tile_size);
  const TileGrid tiles = TileGrid::make(parsed.header, tiling);
  TileIndex index;
  if (Error e = parseTileIndex(tidx, tiles.tileCount(), &index); !e.ok()) return e;
  // The stream is complete when MEND follows the tile chunks (meta and
  // ancillary chunks may stand between; they are read to find it).
  uint64_t end_offset = 0;
  bool complete = false;
  for (uint64_t pos = index.end_offset; pos + kChunkHeaderSize <= source.size();) {
    uint8_t h[kChunkHeaderSize];
    if (!source.read(pos, kChunkHeaderSize, h)) return ioError(pos, "a chunk header");
    ByteReader r(h + 4, 4);
    const uint32_t length = r.u32();
    if (std::memcmp(h, kChunkEnd.c, 4) == 0) {
      complete = pos + kChunkHeaderSize + kChunkCrcSize == source.size() && length == 0;
      end_offset = pos;
      break;
    }
    pos += uint64_t{kChunkHeaderSize} + length + kChunkCrcSize;
  }
  // The tiles the region touches, and their chunks in file order.
  uint32_t first[3], last[3];
  for (int a = 0; a < 3; ++a) {
    first[a] = region.lo[a] / tiling.tile_size[a];
    last[a] = (region.hi[a] - 1) / tiling.tile_size[a];
  }
  std::vector<TileJob> jobs;
  std::vector<std::vector<uint8_t>> buffers;
  std::vector<std::pair<uint64_t, std::pair<size_t, uint64_t>>> reads;  // offset, (job, entry)
  for (uint32_t z = first[2]; z <= last[2]; ++z)
    for (uint32_t y = first[1]; y <= last[1]; ++y)
      for (uint32_t x = first[0]; x <= last[0]; ++x) {
        TileJob job;
        job.tile = (uint64_t{z} * tiles.count[1] + y) * tiles.count[0] + x;
        for (uint64_t e = index.first[job.tile]; e < index.first[job.tile + 1]; ++e)
          reads.push_back({index.chunk_offset[e], {jobs.size(), e}});
        jobs.push_back(std::move(job));
      }
  std::sort(reads.begin(), reads.end());
  buffers.resize(reads.size());
  bool all_present = true;
  // As in a whole decode (spec 11.1), the first framing or index failure in
  // file order ends the chunks the tiles are decoded with: a payload error in
  // an earlier chunk is reported first.
  Error structural;
  for (size_t k = 0; k < reads.size(); ++k) {
    const uint64_t offset = reads[k].first;
    const uint64_t entry = reads[k].second.second;
    const uint64_t extent = kChunkHeaderSize + uint64_t{index.chunk_length[entry]} + kChunkCrcSize;
    if (offset + extent > source.size()) {
      all_present = false;  // a prefix: this tile chunk has not arrived
      continue;
    }
    buffers[k].resize(extent);
    if (!source.read(offset, extent, buffers[k].data())) return ioError(offset, "a tile chunk");
    ChunkView chunk;
    structural = frameChunk(buffers[k], offset, options.container, &chunk);
    if (structural.ok()) structural = checkTileChunk(chunk, index, index.position[entry]);
    if (!structural.ok()) break;
    jobs[reads[k].second.first].chunks.push_back(chunk);
  }
  // Chunks of a tile must be contiguous in its own order: a missing one cuts
  // the rest of that tile (a prefix ends in file order).
  for (TileJob& job : jobs) {
    size_t n = 0;
    for (; n < job.chunks.size(); ++n)
      if (job.chunks[n].offset != index.chunk_offset[index.first[job.tile] + n]) break;
    job.chunks.resize(n);
  }
  out->container = parsed.container;
  out->header = parsed.header;
  out->metadata = parsed.metadata;
  std::copy(parsed.tile_size, parsed.tile_size + 3, out->tile_size);
  out->tiles_total = parsed.tiles_total;
  Error e = decodeTiles(tiles, jobs, complete && all_present && structural.ok(), end_offset, region, options, out);
  regionOutputSize(region, options.reduce_levels, out->output_size);
  forgetPayloads(out);
  return e.ok() ? structural : e;
}

std::vector<uint8_t> canonicalRegionOutput(const DecodedGrid& grid) {
  DecodedGrid shaped;
  shaped.container.chunks = grid.container.chunks;
  shaped.header = grid.header;
  shaped.header.size_x = grid.output_size[0];
  shaped.header.size_y = grid.output_size[1];
  shaped.header.size_z = grid.output_size[2];
  shaped.has_samples = grid.has_samples;
  std::vector<uint8_t> out = canonicalGridOutput(shaped);
  out.insert(out.end(), grid.samples.begin(), grid.samples.end());
  return out;
}

}  // namespace mrsv
