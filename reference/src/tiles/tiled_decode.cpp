// spec: 11.1 the chunks of a tiled grid and their checks, 11.4 samples,
// 11.6 reduced resolution.
#include <algorithm>
#include <cstring>
#include <limits>
#include <new>

#include "common/parallel_for.h"
#include "grid/wavelet_decode.h"
#include "tiles/tile_decode.h"

namespace mrsv {

namespace {

Error orderError(const ChunkView& chunk, std::string message) {
  return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(), std::move(message)};
}

bool hasBand(const TileJob& job) {
  for (const ChunkView& c : job.chunks)
    if (c.chunk_type == kChunkBand) return true;
  return false;
}

}  // namespace

bool everyTileHasABand(const std::vector<TileJob>& jobs) {
  bool all = !jobs.empty();
  for (const TileJob& job : jobs) all = all && hasBand(job);
  return all;
}

Error outputLimitError(const std::vector<TileJob>& jobs, uint64_t out_bytes, const DecodeOptions& options) {
  if (out_bytes <= options.max_output_bytes) return {};
  const ChunkView& last = jobs.back().chunks.back();
  return Error{Status::kResourceLimit, last.offset, last.chunk_type.str(),
               "the output of " + std::to_string(out_bytes) + " bytes exceeds the decoder's limit"};
}

void placeTile(const DecodedGrid& tile, const uint32_t origin[3], const GridRegion& region, int levels,
               const uint32_t out_size[3], size_t sample_bytes, uint8_t* out) {
  const uint32_t tile_size[3] = {tile.header.size_x, tile.header.size_y, tile.header.size_z};
  const uint32_t step = 1u << levels;
  // Per axis: the lattice points g in the tile and the region, their output
  // index and the tile's output index that stands for g (5.8.3: position j of
  // a tile reduced by K_a stands for its sample j * 2^K_a).
  uint32_t first[3], count[3], out_first[3], shift[3];
  for (int a = 0; a < 3; ++a) {
    const uint64_t lo = std::max<uint64_t>(region.lo[a], origin[a]);
    const uint64_t hi = std::min<uint64_t>(region.hi[a], uint64_t{origin[a]} + tile_size[a]);
    const uint64_t g0 = (lo + step - 1) / step * step;
    const uint64_t region_g0 = (uint64_t{region.lo[a]} + step - 1) / step * step;
    count[a] = g0 < hi ? static_cast<uint32_t>((hi - g0 + step - 1) / step) : 0;
    first[a] = static_cast<uint32_t>(g0 - origin[a]);
    out_first[a] = static_cast<uint32_t>((g0 - region_g0) / step);
    shift[a] = static_cast<uint32_t>(std::min<int>(levels, a < tile.header.num_dims ? tile.wavelet.levels[a] : 0));
  }
  if (count[0] == 0 || count[1] == 0 || count[2] == 0) return;
  const uint32_t* in_size = tile.output_size;
  for (uint32_t k = 0; k < count[2]; ++k) {
    const uint64_t tz = (first[2] + uint64_t{k} * step) >> shift[2];
    for (uint32_t j = 0; j < count[1]; ++j) {
      const uint64_t ty = (first[1] + uint64_t{j} * step) >> shift[1];
      const uint8_t* src = tile.samples.data() + (tz * in_size[1] + ty) * in_size[0] * sample_bytes;
      uint8_t* dst = out + ((uint64_t{out_first[2] + k} * out_size[1] + out_first[1] + j) * out_size[0] +
                            out_first[0]) * sample_bytes;
      if (levels == 0) {
        std::memcpy(dst, src + uint64_t{first[0]} * sample_bytes, uint64_t{count[0]} * sample_bytes);
        continue;
      }
      for (uint32_t i = 0; i < count[0]; ++i) {
        const uint64_t tx = (first[0] + uint64_t{i} * step) >> shift[0];
        std::memcpy(dst + uint64_t{i} * sample_bytes, src + tx * sample_bytes, sample_bytes);
      }
    }
  }
}

Error decodeTileJob(const TileGrid& tiles, const TileJob& job, bool complete, uint64_t end_offset,
                    const DecodeOptions& options, DecodedGrid* tile) {
  tile->header = tiles.tileHeader(job.tile);
  // decodeWaveletGrid reads the chunks after the first (the GHDR's place).
  tile->container.chunks.reserve(job.chunks.size() + 1);
  tile->container.chunks.push_back(ChunkView{kChunkGridHeader, 0, 0, 0, nullptr});
  tile->container.chunks.insert(tile->container.chunks.end(), job.chunks.begin(), job.chunks.end());
  tile->container.complete = complete;
  tile->container.end_chunk_offset = end_offset;
  return decodeWaveletGrid(options, tile);
}

Error reducedLatticeError(const TileGrid& tiles, int levels) {
  // spec 11.6: a reduced decode takes every 2^K-th sample of the grid, which
  // each tile can supply only when its origin is on that lattice.
  for (int a = 0; a < tiles.grid.num_dims && levels > 0; ++a) {
    if (tiles.count[a] > 1 && (levels >= 31 || tiles.tiling.tile_size[a] % (1u << levels) != 0))
      return Error{Status::kInvalidArgument, 0, "reduce_levels",
                   "a tiled grid reduced by " + std::to_string(levels) +
                       " levels needs tile sizes that are multiples of 2^" + std::to_string(levels)};
  }
  return {};
}

Error checkTileChunk(const ChunkView& chunk, const TileIndex& index, uint64_t k) {
  if (chunk.chunk_type == kChunkMeta || !chunk.chunk_type.critical())
    return orderError(chunk, "tile chunk " + std::to_string(k) + " of " + std::to_string(index.totalChunks()) +
                                 " expected here; no other chunk may stand among the tile chunks");
  const uint64_t entry = index.schedule[k];
  if (chunk.chunk_length != index.chunk_length[entry])
    return Error{Status::kBadTileIndex, chunk.offset + 4, chunk.chunk_type.str() + ".chunk_length",
                 "the chunk is " + std::to_string(chunk.chunk_length) + " bytes but TIDX says " +
                     std::to_string(index.chunk_length[entry])};
  return {};
}

void regionOutputSize(const GridRegion& region, int levels, uint32_t size[3]) {
  const uint64_t step = uint64_t{1} << levels;
  for (int a = 0; a < 3; ++a) {
    const uint64_t g0 = (uint64_t{region.lo[a]} + step - 1) / step * step;
    size[a] = g0 < region.hi[a] ? static_cast<uint32_t>((region.hi[a] - g0 + step - 1) / step) : 0;
  }
}

Error decodeTiles(const TileGrid& tiles, const std::vector<TileJob>& jobs, bool complete,
                  uint64_t end_offset, const GridRegion& region, const DecodeOptions& options,
                  DecodedGrid* out) {
  const int levels = options.reduce_levels;
  if (Error e = reducedLatticeError(tiles, levels); !e.ok()) return e;
  const size_t sample_bytes = sampleSize(tiles.grid.sample_type);
  const bool all_have_bands = everyTileHasABand(jobs);
  uint32_t out_size[3];
  regionOutputSize(region, levels, out_size);
  const uint64_t out_bytes = uint64_t{out_size[0]} * out_size[1] * out_size[2] * sample_bytes;
  if (all_have_bands) {
    if (Error e = outputLimitError(jobs, out_bytes, options); !e.ok()) return e;
    const ChunkView& last = jobs.back().chunks.back();
    try {
      out->samples.assign(out_bytes, 0);
    } catch (const std::bad_alloc&) {
      return Error{Status::kResourceLimit, last.offset, last.chunk_type.str(),
                   "cannot allocate " + std::to_string(out_bytes) + " bytes"};
    }
  }
  DecodeOptions tile_options = options;
  tile_options.threads = 1;
  std::vector<Error> errors(jobs.size());
  std::vector<uint32_t> bands_decoded(jobs.size()), bands_total(jobs.size());
  std::vector<uint8_t> has_samples(jobs.size());
  std::vector<WaveletHeader> wavelet(jobs.size());
  parallelFor(jobs.size(), options.threads, [&](uint64_t j) {
    DecodedGrid tile;
    errors[j] = decodeTileJob(tiles, jobs[j], complete, end_offset, tile_options, &tile);
    bands_decoded[j] = tile.bands_decoded;
    bands_total[j] = tile.bands_total;
    has_samples[j] = tile.has_samples;
    wavelet[j] = tile.wavelet;
    if (errors[j].ok() && all_have_bands && tile.has_samples) {
      uint32_t origin[3], size[3];
      tiles.box(jobs[j].tile, origin, size);
      placeTile(tile, origin, region, levels, out_size, sample_bytes, out->samples.data());
    }
  });
  // The first broken rule in file order: chunks of different tiles never
  // overlap, so the smallest offset; at MEND the lowest tile (jobs are in
  // tile order).
  const Error* first = nullptr;
  for (const Error& e : errors)
    if (!e.ok() && (first == nullptr || e.offset < first->offset)) first = &e;
  out->tiles_with_samples = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    out->bands_decoded += bands_decoded[j];
    out->bands_total += bands_total[j];
    out->tiles_with_samples += has_samples[j];
  }
  if (!jobs.empty()) out->wavelet = wavelet.front();
  if (first != nullptr) {
    out->samples.clear();
    return *first;
  }
  out->has_samples = all_have_bands && out->tiles_with_samples == jobs.size();
  if (!out->has_samples) {
    out->samples.clear();
    return {};
  }
  std::copy(out_size, out_size + 3, out->output_size);
  return {};
}

Error decodeTiledGrid(const DecodeOptions& options, DecodedGrid* out) {
  const Container& c = out->container;
  const ChunkView end{kChunkEnd, 0, 0, c.end_chunk_offset, nullptr};
  // spec 11.1 rule 1: TINF is the first critical chunk after GHDR.
  size_t i = 1;
  while (i < c.chunks.size() && (c.chunks[i].chunk_type == kChunkMeta || !c.chunks[i].chunk_type.critical())) ++i;
  if (i == c.chunks.size())
    return c.complete ? orderError(end, "a tiled grid needs a TINF chunk") : Error{};
  if (c.chunks[i].chunk_type != kChunkTiling)
    return orderError(c.chunks[i], "TINF must be the first critical chunk of a tiled grid, not " +
                                       c.chunks[i].chunk_type.str());
  TilingHeader tiling;
  if (Error e = parseTilingHeader(c.chunks[i], out->header, &tiling); !e.ok()) return e;
  const TileGrid tiles = TileGrid::make(out->header, tiling);
  std::copy(tiling.tile_size, tiling.tile_size + 3, out->tile_size);
  out->tiles_total = tiles.tileCount();
  // Rule 2: TIDX right after TINF.
  if (++i == c.chunks.size()) return c.complete ? orderError(end, "TIDX must follow TINF") : Error{};
  if (c.chunks[i].chunk_type != kChunkTileIndex)
    return orderError(c.chunks[i], "TIDX must follow TINF, not " + c.chunks[i].chunk_type.str());
  TileIndex index;
  if (Error e = parseTileIndex(c.chunks[i], tiles.tileCount(), &index); !e.ok()) return e;
  ++i;
  // Rules 5 to 7 in file order; the first failure ends the tile chunks the
  // tiles are decoded with, so that an error in an earlier tile chunk wins.
  std::vector<TileJob> jobs(tiles.tileCount());
  for (uint64_t t = 0; t < jobs.size(); ++t) jobs[t].tile = t;
  Error structural;
  uint64_t present = 0;
  for (; i < c.chunks.size() && present < index.totalChunks(); ++i, ++present) {
    const ChunkView& chunk = c.chunks[i];
    if (Error e = checkTileChunk(chunk, index, present); !e.ok()) {
      structural = e;
      break;
    }
    const uint64_t entry = index.schedule[present];
    const uint64_t tile = std::upper_bound(index.first.begin(), index.first.end(), entry) - index.first.begin() - 1;
    jobs[tile].chunks.push_back(chunk);
  }
  if (structural.ok()) {
    for (; i < c.chunks.size(); ++i) {
      const ChunkView& chunk = c.chunks[i];
      if (chunk.chunk_type.critical()) {
        structural = orderError(chunk, chunk.chunk_type.str() + " after the last tile chunk");
        break;
      }
    }
  }
  const bool all_present = present == index.totalChunks();
  const bool complete = c.complete && structural.ok() && all_present;
  GridRegion whole;
  whole.hi[0] = out->header.size_x;
  whole.hi[1] = out->header.size_y;
  whole.hi[2] = out->header.size_z;
  const bool by_rows = options.tile_rows && complete;
  if (Error e = by_rows ? decodeTileRows(tiles, jobs, c.end_chunk_offset, whole, options, out)
                        : decodeTiles(tiles, jobs, complete, c.end_chunk_offset, whole, options, out);
      !e.ok())
    return e;
  if (!structural.ok()) return structural;
  if (c.complete && !all_present)
    return orderError(end, "the stream ends after " + std::to_string(present) + " of " +
                               std::to_string(index.totalChunks()) + " tile chunks");
  return {};
}

}  // namespace mrsv
