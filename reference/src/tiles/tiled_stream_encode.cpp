// spec: 11.7 (informative) out-of-core tiled encoding: the grid read a row of
// tiles at a time, the coded tiles kept in a temporary file, the stream
// written in round order at the end. Memory: one row of tiles, the tiles in
// flight, the index; the stream is byte-identical to encodeTiledGrid()'s.
#include <cstdio>
#include <cstring>
#include <memory>

#include "common/crc32c.h"
#include "common/parallel_for.h"
#include "mrsv/encode.h"
#include "tiles/tile_encoding.h"

namespace mrsv {

namespace {

Error invalid(std::string field, std::string message) {
  return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
}
Error ioFailure(std::string what) { return Error{Status::kIoError, 0, "file", std::move(what)}; }

bool writeChunk(ByteSink& out, const ChunkType& type, const std::vector<uint8_t>& payload) {
  const std::vector<uint8_t> bytes = framedChunk(type, payload.data(), static_cast<uint32_t>(payload.size()));
  return out.write(bytes.data(), bytes.size());
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// Where one coded tile chunk waits in the spill file.
struct SpilledChunk {
  ChunkType type;
  uint64_t offset;
  uint32_t length;
};

}  // namespace

Error tileIndexPayload(const std::vector<std::vector<uint32_t>>& lengths, std::vector<uint8_t>* index,
                       std::vector<uint8_t>* counts) {
  uint64_t chunks = 0;
  counts->resize(lengths.size());
  for (size_t t = 0; t < lengths.size(); ++t) {
    if (lengths[t].size() > 255) return invalid("tile", "tile " + std::to_string(t) + " has more than 255 chunks");
    (*counts)[t] = static_cast<uint8_t>(lengths[t].size());
    chunks += lengths[t].size();
  }
  *index = serializeTileIndex(lengths);
  if (index->size() > kMaxChunkPayload) return invalid("tile_size", "the tile index exceeds the chunk limit");
  if (chunks + 6 > kMaxChunks)
    return invalid("tile_size", "the tiles make " + std::to_string(chunks) + " chunks, above the limit of " +
                                    std::to_string(kMaxChunks) + " (use larger tiles)");
  return {};
}

std::vector<uint8_t> framedChunk(const ChunkType& type, const uint8_t* payload, uint32_t length) {
  std::vector<uint8_t> out(kChunkHeaderSize + size_t{length} + kChunkCrcSize);
  for (int i = 0; i < 4; ++i) out[i] = static_cast<uint8_t>(type.c[i]);
  for (int i = 0; i < 4; ++i) out[4 + i] = static_cast<uint8_t>(length >> (8 * i));
  if (length > 0) std::memcpy(out.data() + kChunkHeaderSize, payload, length);
  const uint32_t crc = crc32c(0, out.data(), kChunkHeaderSize + size_t{length});
  for (int i = 0; i < 4; ++i) out[kChunkHeaderSize + length + i] = static_cast<uint8_t>(crc >> (8 * i));
  return out;
}

std::vector<uint8_t> tiledStreamHead(const GridHeader& grid, const Metadata& recorded, const TilingHeader& tiling,
                                     const std::vector<uint8_t>& index) {
  ContainerWriter out;  // the file header, then each chunk framed
  out.addChunk(kChunkGridHeader, serializeGridHeader(grid));
  out.addChunk(kChunkMeta, serializeMetadata(recorded));
  out.addChunk(kChunkTiling, serializeTilingHeader(tiling));
  out.addChunk(kChunkTileIndex, index);
  return out.image();
}

namespace {

// Reads the box of the row of tiles (ty, tz): the grid's whole width.
Error readRowOfTiles(const TileGrid& tiles, GridBoxReader& reader, uint32_t ty, uint32_t tz, uint32_t origin[3],
                     uint32_t size[3], std::vector<uint8_t>* box) {
  tiles.box((uint64_t{tz} * tiles.count[1] + ty) * tiles.count[0], origin, size);
  origin[0] = 0;
  size[0] = tiles.grid.size_x;
  box->resize(uint64_t{size[0]} * size[1] * size[2] * sampleSize(tiles.grid.sample_type));
  std::string error;
  if (!reader.read(origin, size, box->data(), &error)) return ioFailure("reading the grid: " + error);
  return {};
}

// One pass over the grid, a row of tiles at a time: every tile coded with
// `options` (at_step: the levels chosen as a rate search does), its chunks
// appended to `spill`. Also the samples' figures into `samples` unless null.
struct Pass {
  std::unique_ptr<std::FILE, FileCloser> spill;
  std::vector<std::vector<SpilledChunk>> spilled;  // per tile
  std::vector<TileResult> stats;                   // per tile, without chunks
  StepTrial totals;
};

Error codePass(const TileGrid& tiles, GridBoxReader& reader, const WaveletEncodeOptions& options, bool at_step,
               const TiledEncodeOptions& tiled, ErrorTally* samples, Pass* pass) {
  const GridHeader& h = tiles.grid;
  pass->spill.reset(std::tmpfile());
  if (!pass->spill) return ioFailure("cannot create a temporary file for the coded tiles");
  pass->spilled.assign(tiles.tileCount(), {});
  pass->stats.assign(tiles.tileCount(), {});
  pass->totals = StepTrial{};
  uint64_t spill_end = 0, done = 0;
  // Row by row of tiles (along x), slab by slab (z): the box of one row.
  for (uint32_t tz = 0; tz < tiles.count[2]; ++tz) {
    for (uint32_t ty = 0; ty < tiles.count[1]; ++ty) {
      const uint64_t first = (uint64_t{tz} * tiles.count[1] + ty) * tiles.count[0];
      uint32_t origin[3], size[3];
      std::vector<uint8_t> box;
      if (Error e = readRowOfTiles(tiles, reader, ty, tz, origin, size, &box); !e.ok()) return e;
      if (samples) samples->addSamples(h, box.data(), box.size());
      std::vector<TileResult> row(tiles.count[0]);
      parallelFor(row.size(), tiled.threads, [&](uint64_t i) {
        std::vector<uint8_t> tile_samples = tileSamplesFrom(tiles, first + i, box.data(), origin, size);
        row[i] = at_step ? encodeTileSamplesAtStep(tiles, first + i, tile_samples, options)
                         : encodeTileSamples(tiles, first + i, tile_samples, options);
      });
      for (uint64_t i = 0; i < row.size(); ++i) {
        TileResult& r = row[i];
        if (!r.error.ok()) return r.error;
        for (const auto& [type, payload] : r.chunks) {
          if (std::fwrite(payload.data(), 1, payload.size(), pass->spill.get()) != payload.size())
            return ioFailure("cannot write the temporary file of coded tiles (disk full?)");
          pass->spilled[first + i].push_back({type, spill_end, static_cast<uint32_t>(payload.size())});
          spill_end += payload.size();
        }
        pass->totals.bytes += r.bytes;
        pass->totals.chunks += r.chunks.size();
        pass->totals.sse += r.sse;
        r.chunks.clear();
        pass->stats[first + i] = std::move(r);
      }
      done += row.size();
      if (tiled.progress) tiled.progress(done, tiles.tileCount());
    }
  }
  if (std::fflush(pass->spill.get()) != 0) return ioFailure("cannot write the temporary file of coded tiles");
  return {};
}

// The samples' figures alone (a rate or PSNR search needs their range first).
Error tallySamples(const TileGrid& tiles, GridBoxReader& reader, ErrorTally* tally) {
  for (uint32_t tz = 0; tz < tiles.count[2]; ++tz)
    for (uint32_t ty = 0; ty < tiles.count[1]; ++ty) {
      uint32_t origin[3], size[3];
      std::vector<uint8_t> box;
      if (Error e = readRowOfTiles(tiles, reader, ty, tz, origin, size, &box); !e.ok()) return e;
      tally->addSamples(tiles.grid, box.data(), box.size());
    }
  return {};
}

}  // namespace

Error encodeTiledGridFromReader(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                                const WaveletEncodeOptions& options, const TiledEncodeOptions& tiled,
                                ByteSink& out, WaveletEncodeReport* report) {
  GridHeader h = header;
  h.coding = GridCoding::kTiled;
  if (std::string problem = gridHeaderProblem(h); !problem.empty()) return invalid("grid_header", problem);
  TilingHeader tiling;
  for (int a = 0; a < 3; ++a) tiling.tile_size[a] = a < h.num_dims ? tiled.tile_size[a] : 1;
  if (std::string problem = tilingProblem(tiling, h); !problem.empty()) return invalid("tile_size", problem);
  if (options.has_roi) return invalid("roi", "a region of interest is not supported with tiles in this version");
  const TileGrid tiles = TileGrid::make(h, tiling);
  ErrorTally tally;
  WaveletEncodeReport rep;
  Pass pass;
  if (options.bits_per_sample > 0 || options.psnr > 0) {
    // A pass over the grid per step tried (about 10 to 20), each into its own
    // spill file; the best one that meets the target is kept (as
    // encodeTiledGrid() keeps its best tiles, so the streams agree).
    if (Error e = tallySamples(tiles, reader, &tally); !e.ok()) return e;
    Pass trying;
    auto trial = [&](const WaveletEncodeOptions& o, StepTrial* t) -> Error {
      if (Error e = codePass(tiles, reader, o, options.step == 0, tiled, nullptr, &trying); !e.ok()) return e;
      *t = trying.totals;
      return {};
    };
    auto keep = [&]() { std::swap(pass, trying); };
    if (Error e = searchTileStep(h, tiles.tileCount(), metadata, tally, options, trial, keep, &rep.iterations);
        !e.ok())
      return e;
  } else {
    if (Error e = codePass(tiles, reader, options, false, tiled, &tally, &pass); !e.ok()) return e;
    rep.iterations = 1;
  }
  for (const TileResult& r : pass.stats) tally.addTile(r);
  std::unique_ptr<std::FILE, FileCloser>& spill = pass.spill;
  const std::vector<std::vector<SpilledChunk>>& spilled = pass.spilled;
  // The stream, as encodeTiledGrid() writes it.
  std::vector<std::vector<uint32_t>> lengths(spilled.size());
  for (size_t t = 0; t < spilled.size(); ++t)
    for (const SpilledChunk& c : spilled[t]) lengths[t].push_back(c.length);
  std::vector<uint8_t> index, counts;
  if (Error e = tileIndexPayload(lengths, &index, &counts); !e.ok()) return e;
  const Metadata recorded = tally.record(metadata, options, &rep);
  const std::vector<uint8_t> head = tiledStreamHead(h, recorded, tiling, index);
  uint64_t written = head.size();
  if (!out.write(head.data(), head.size())) return ioFailure("cannot write the stream");
  std::vector<uint8_t> payload;
  for (const auto& [tile, nth] : tileChunkOrder(counts)) {
    const SpilledChunk& c = spilled[tile][nth];
    payload.resize(c.length);
    if (std::fseek(spill.get(), static_cast<long>(c.offset), SEEK_SET) != 0 ||
        std::fread(payload.data(), 1, c.length, spill.get()) != c.length)
      return ioFailure("cannot read back the temporary file of coded tiles");
    if (!writeChunk(out, c.type, payload)) return ioFailure("cannot write the stream");
    written += kChunkHeaderSize + uint64_t{c.length} + kChunkCrcSize;
  }
  if (!writeChunk(out, kChunkEnd, {})) return ioFailure("cannot write the stream");
  written += kChunkHeaderSize + kChunkCrcSize;
  rep.bytes = written;
  rep.bits_per_sample = 8.0 * static_cast<double>(written) / static_cast<double>(h.sampleCount());
  if (report) *report = rep;
  return {};
}

}  // namespace mrsv
