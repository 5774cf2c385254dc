// spec: 11.7 (informative) the reference encoder of tiled grids: each tile
// coded as a wavelet grid of its own, in parallel; a rate or PSNR target met
// with one quantiser step for the whole grid, so that bits go where the
// detail is, as in an untiled stream.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>

#include "common/parallel_for.h"
#include "mrsv/encode.h"
#include "mrsv/tiled_grid.h"
#include "tiles/tile_encoding.h"

namespace mrsv {

namespace {

Error invalid(std::string field, std::string message) {
  return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
}

}  // namespace

std::vector<uint8_t> tileSamplesFrom(const TileGrid& tiles, uint64_t tile, const uint8_t* box,
                                     const uint32_t box_origin[3], const uint32_t box_size[3]) {
  uint32_t origin[3], size[3];
  tiles.box(tile, origin, size);
  const size_t bytes = sampleSize(tiles.grid.sample_type);
  const uint64_t row = uint64_t{size[0]} * bytes;
  std::vector<uint8_t> out(row * size[1] * size[2]);
  uint8_t* dst = out.data();
  for (uint32_t z = 0; z < size[2]; ++z)
    for (uint32_t y = 0; y < size[1]; ++y, dst += row) {
      const uint64_t at = ((uint64_t{origin[2] + z - box_origin[2]} * box_size[1] + origin[1] + y - box_origin[1]) *
                               box_size[0] + origin[0] - box_origin[0]) * bytes;
      std::memcpy(dst, box + at, row);
    }
  return out;
}

namespace {

std::vector<uint8_t> tileSamples(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& samples) {
  const uint32_t origin[3] = {0, 0, 0};
  const uint32_t size[3] = {tiles.grid.size_x, tiles.grid.size_y, tiles.grid.size_z};
  return tileSamplesFrom(tiles, tile, samples.data(), origin, size);
}

}  // namespace

TileResult encodeTileSamples(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& tile_samples,
                             const WaveletEncodeOptions& options) {
  TileResult r;
  std::vector<uint8_t> stream;
  WaveletEncodeReport report;
  r.error = encodeWaveletGrid(tiles.tileHeader(tile), tile_samples, Metadata{}, options, &stream, &report);
  if (!r.error.ok()) {
    r.error.message = "tile " + std::to_string(tile) + ": " + r.error.message;
    return r;
  }
  Container c;
  if (Error e = readContainer(stream.data(), stream.size(), ContainerOptions{}, &c); !e.ok()) {
    r.error = e;
    return r;
  }
  for (size_t i = 1; i < c.chunks.size(); ++i) {
    const ChunkView& chunk = c.chunks[i];
    if (chunk.chunk_type == kChunkMeta) continue;
    r.chunks.emplace_back(chunk.chunk_type, std::vector<uint8_t>(chunk.payload, chunk.payload + chunk.chunk_length));
    r.bytes += kChunkHeaderSize + uint64_t{chunk.chunk_length} + kChunkCrcSize;
  }
  r.sse = report.sum_squared_error;
  r.max_abs = report.max_abs_error;
  r.levels = report.levels;
  return r;
}

TileResult encodeTileSamplesAtStep(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& tile_samples,
                                   const WaveletEncodeOptions& options) {
  TileResult best = encodeTileSamples(tiles, tile, tile_samples, options);
  if (!best.error.ok() || options.progressive) return best;
  const double lambda = std::log(2.0) / 6 * options.step * options.step;
  auto cost = [&](const TileResult& r) { return r.sse + lambda * 8 * static_cast<double>(r.bytes); };
  for (int levels : {2, 1}) {
    if (levels >= best.levels || levels > options.max_levels) continue;
    WaveletEncodeOptions fewer = options;
    fewer.max_levels = levels;
    TileResult r = encodeTileSamples(tiles, tile, tile_samples, fewer);
    if (r.error.ok() && cost(r) < cost(best)) best = std::move(r);
  }
  return best;
}

Error searchTileStep(const GridHeader& grid, uint64_t tiles, const Metadata& metadata, const ErrorTally& tally,
                     const WaveletEncodeOptions& options,
                     const std::function<Error(const WaveletEncodeOptions&, StepTrial*)>& trial,
                     const std::function<void()>& keep, int* iterations) {
  // The framed bytes of everything but the tile chunks: header, GHDR, TINF,
  // TIDX, MEND, and the meta chunk with its recorded error figures.
  const Metadata probe = ErrorTally::probe(metadata);
  auto overhead = [&](uint64_t tile_chunks) {
    return double(kFileHeaderSize + 3 * (kChunkHeaderSize + kChunkCrcSize) + kGridHeaderSize +
                  kTilingHeaderSize + (kChunkHeaderSize + kChunkCrcSize) + tiles + 4 * tile_chunks +
                  serializeMetadata(probe).size() + kChunkHeaderSize + kChunkCrcSize);
  };
  const bool by_rate = options.bits_per_sample > 0;
  const double range = std::max(tally.hi - tally.lo, 1e-300);
  const double target_bits = options.bits_per_sample * static_cast<double>(grid.sampleCount());
  double lo_log = std::log2(range) - 30, hi_log = std::log2(range) + 2;
  bool found = false;
  WaveletEncodeOptions step_options = options;
  step_options.bits_per_sample = 0;
  step_options.psnr = 0;
  for (int it = 0; it < 40 && hi_log - lo_log > 1e-3; ++it) {
    const double mid = 0.5 * (lo_log + hi_log);
    step_options.step = std::exp2(mid);
    StepTrial t;
    if (Error e = trial(step_options, &t); !e.ok()) return e;
    ++*iterations;
    const double total_bits = 8 * (static_cast<double>(t.bytes) + overhead(t.chunks));
    const double mse = tally.valid ? t.sse / static_cast<double>(tally.valid) : 0;
    const bool meets = by_rate ? total_bits <= target_bits
                               : (mse == 0 || 10 * std::log10(range * range / mse) >= options.psnr);
    if (meets) {
      keep();
      found = true;
      (by_rate ? hi_log : lo_log) = mid;
      if (by_rate && total_bits >= 0.999 * target_bits) break;
    } else {
      (by_rate ? lo_log : hi_log) = mid;
    }
  }
  if (!found)
    return invalid(by_rate ? "bits_per_sample" : "psnr",
                   by_rate ? "the rate is too low for even the coarsest approximation of every tile"
                           : "the PSNR target cannot be met");
  return {};
}

namespace {

TileResult encodeTile(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& samples,
                      const WaveletEncodeOptions& options) {
  return encodeTileSamples(tiles, tile, tileSamples(tiles, tile, samples), options);
}

TileResult encodeTileAtStep(const TileGrid& tiles, uint64_t tile, const std::vector<uint8_t>& samples,
                            const WaveletEncodeOptions& options) {
  return encodeTileSamplesAtStep(tiles, tile, tileSamples(tiles, tile, samples), options);
}

}  // namespace

void ErrorTally::addSamples(const GridHeader& h, const uint8_t* samples, size_t size) {
  const size_t bytes = sampleSize(h.sample_type);
  for (size_t i = 0; i < size; i += bytes) {
    if (h.hasNodata() && std::memcmp(samples + i, &h.nodata_bits, bytes) == 0) continue;
    const double v = sampleValue(samples + i, h.sample_type);
    ++valid;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

void ErrorTally::addTile(const TileResult& r) {
  sse += r.sse;
  max_abs = std::max(max_abs, r.max_abs);
  levels = std::max(levels, r.levels);
}

Metadata ErrorTally::record(const Metadata& metadata, const WaveletEncodeOptions& options,
                            WaveletEncodeReport* report) const {
  auto text = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return std::string(buf);
  };
  const double mse = valid ? sse / static_cast<double>(valid) : 0;
  const double range = valid ? hi - lo : 0;
  report->sum_squared_error = sse;
  report->max_abs_error = max_abs;
  report->levels = levels;
  report->psnr = mse > 0 ? 10 * std::log10(range * range / mse) : std::numeric_limits<double>::infinity();
  Metadata recorded = metadata;
  if (options.max_error >= 0) recorded.set("error_bound", text(std::floor(options.max_error)));
  recorded.set("error_max_abs", text(max_abs));
  recorded.set("error_psnr_db", std::isinf(report->psnr) ? "inf" : text(report->psnr));
  recorded.set("error_rmse", text(std::sqrt(mse)));
  return recorded;
}

Metadata ErrorTally::probe(const Metadata& metadata) {
  Metadata probe = metadata;
  for (const char* key : {"error_bound", "error_max_abs", "error_psnr_db", "error_rmse"})
    probe.set(key, "-1.23457e+300");
  return probe;
}

Error encodeTiledGrid(const GridHeader& header, const std::vector<uint8_t>& samples, const Metadata& metadata,
                      const WaveletEncodeOptions& options, const TiledEncodeOptions& tiled,
                      std::vector<uint8_t>* out, WaveletEncodeReport* report) {
  GridHeader h = header;
  h.coding = GridCoding::kTiled;
  if (std::string problem = gridHeaderProblem(h); !problem.empty()) return invalid("grid_header", problem);
  if (samples.size() != h.sampleCount() * sampleSize(h.sample_type))
    return invalid("samples", "got " + std::to_string(samples.size()) + " bytes, the grid needs " +
                                  std::to_string(h.sampleCount() * sampleSize(h.sample_type)));
  TilingHeader tiling;
  for (int a = 0; a < 3; ++a) tiling.tile_size[a] = a < h.num_dims ? tiled.tile_size[a] : 1;
  if (std::string problem = tilingProblem(tiling, h); !problem.empty()) return invalid("tile_size", problem);
  if (options.has_roi)
    return invalid("roi", "a region of interest is not supported with tiles in this version");
  const TileGrid tiles = TileGrid::make(h, tiling);
  const uint64_t n_tiles = tiles.tileCount();
  std::vector<TileResult> results(n_tiles);
  std::atomic<uint64_t> done{0};
  std::mutex progress_lock;
  auto encodeAll = [&](const WaveletEncodeOptions& o) -> Error {
    results.resize(n_tiles);  // empty after a swap with the best so far
    parallelFor(n_tiles, tiled.threads, [&](uint64_t t) {
      results[t] = o.step > 0 && options.step == 0 ? encodeTileAtStep(tiles, t, samples, o)
                                                   : encodeTile(tiles, t, samples, o);
      if (tiled.progress) {
        std::lock_guard<std::mutex> lock(progress_lock);
        tiled.progress(++done, n_tiles);
      }
    });
    for (const TileResult& r : results)
      if (!r.error.ok()) return r.error;
    return {};
  };
  WaveletEncodeReport rep;
  ErrorTally tally;
  tally.addSamples(h, samples.data(), samples.size());
  if (options.bits_per_sample > 0 || options.psnr > 0) {
    std::vector<TileResult> best;
    auto trial = [&](const WaveletEncodeOptions& o, StepTrial* t) -> Error {
      done = 0;
      if (Error e = encodeAll(o); !e.ok()) return e;
      for (const TileResult& r : results) {
        t->bytes += r.bytes;
        t->chunks += r.chunks.size();
        t->sse += r.sse;
      }
      return {};
    };
    auto keep = [&]() { best.swap(results); };  // results is all written again by the next step tried
    if (Error e = searchTileStep(h, n_tiles, metadata, tally, options, trial, keep, &rep.iterations); !e.ok())
      return e;
    results.swap(best);
  } else {
    if (Error e = encodeAll(options); !e.ok()) return e;
    rep.iterations = 1;
  }
  // The stream: GHDR, meta, TINF, TIDX, then the tile chunks round by round.
  for (const TileResult& r : results) tally.addTile(r);
  const Metadata recorded = tally.record(metadata, options, &rep);
  std::vector<std::vector<uint32_t>> lengths(n_tiles);
  for (uint64_t t = 0; t < n_tiles; ++t)
    for (const auto& chunk : results[t].chunks) lengths[t].push_back(static_cast<uint32_t>(chunk.second.size()));
  std::vector<uint8_t> index, counts;
  if (Error e = tileIndexPayload(lengths, &index, &counts); !e.ok()) return e;
  std::vector<uint8_t> stream = tiledStreamHead(h, recorded, tiling, index);
  for (const auto& [tile, nth] : tileChunkOrder(counts)) {
    auto& chunk = results[tile].chunks[nth];
    const std::vector<uint8_t> framed =
        framedChunk(chunk.first, chunk.second.data(), static_cast<uint32_t>(chunk.second.size()));
    stream.insert(stream.end(), framed.begin(), framed.end());
    std::vector<uint8_t>().swap(chunk.second);  // written: free it
  }
  const std::vector<uint8_t> end = framedChunk(kChunkEnd, nullptr, 0);
  stream.insert(stream.end(), end.begin(), end.end());
  *out = std::move(stream);
  rep.bytes = out->size();
  rep.bits_per_sample = 8.0 * static_cast<double>(out->size()) / static_cast<double>(h.sampleCount());
  if (report) *report = rep;
  return {};
}

}  // namespace mrsv
