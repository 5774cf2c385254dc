// spec: 11.4 samples, 11.6 reduced resolution. A whole decode of a tiled grid
// handed over a row of tiles at a time (DecodeOptions::tile_rows).
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <new>

#include "common/parallel_for.h"
#include "tiles/tile_decode.h"

namespace mrsv {

namespace {

// Rows of tiles decoded at once. The threads take the tiles in file order
// across the end of a row, so that no thread waits for a row's slowest tile
// (a barrier per row held 2 threads to 1.68x on rows of 16 small bricks). The
// memory is these rows' buffers and what options.tile_rows holds (the tool's
// writer: one row queued, one being written).
constexpr uint64_t kRowsInFlight = 2;

// The output of one row of tiles while its tiles decode.
struct RowSlot {
  uint64_t row = UINT64_MAX;  // the row it holds
  uint64_t tiles_done = 0;
  std::vector<uint8_t> samples;
};

}  // namespace

// The same checks, samples and error as decodeTiles() over every tile: the
// first error in file order is the smallest offset over the tiles (at MEND the
// lowest tile's). Rows after an error still decode, for their errors only.
Error decodeTileRows(const TileGrid& tiles, const std::vector<TileJob>& jobs, uint64_t end_offset,
                     const GridRegion& whole, const DecodeOptions& options, DecodedGrid* out) {
  const int levels = options.reduce_levels;
  if (Error e = reducedLatticeError(tiles, levels); !e.ok()) return e;
  const size_t sample_bytes = sampleSize(tiles.grid.sample_type);
  uint32_t out_size[3];
  regionOutputSize(whole, levels, out_size);
  // Rows of tiles along the last axis with more than one tile or more than one
  // output position: every axis above it has one tile and one position at
  // most, so that a row is a contiguous run of tile numbers and of output
  // samples (one tile along it: one row of every tile; a row reduced to no
  // position along it hands over nothing).
  int axis = 0;
  for (int a = 0; a < 3; ++a)
    if (tiles.count[a] > 1 || out_size[a] > 1) axis = a;
  uint64_t per_row = 1;
  for (int a = 0; a < axis; ++a) per_row *= tiles.count[a];
  const uint64_t out_bytes = uint64_t{out_size[0]} * out_size[1] * out_size[2] * sample_bytes;
  const bool all_have_bands = everyTileHasABand(jobs);
  if (all_have_bands)
    if (Error e = outputLimitError(jobs, out_bytes, options); !e.ok()) return e;
  // Row r: the box of the whole region between its tiles' planes along the axis.
  auto rowRegion = [&](uint64_t r) {
    GridRegion region = whole;
    region.lo[axis] = static_cast<uint32_t>(r * tiles.tiling.tile_size[axis]);
    region.hi[axis] = std::min<uint64_t>(whole.hi[axis], uint64_t{region.lo[axis]} + tiles.tiling.tile_size[axis]);
    return region;
  };
  DecodeOptions tile_options = options;
  tile_options.threads = 1;
  tile_options.tile_rows = nullptr;

  std::mutex lock;
  std::condition_variable moved;  // a row handed over, or the work stopped
  std::vector<Error> errors(jobs.size());
  RowSlot slots[kRowsInFlight];
  uint64_t next = 0, handed = 0;  // the next tile to take, the rows handed over
  bool handing = false, any_error = false, has_samples = all_have_bands, write_failed = false, stop = false;
  bool out_of_memory = false;
  std::exception_ptr failure;

  const uint64_t rows = tiles.count[axis];  // every axis above has one tile: rows x per_row = all tiles
  // A slot takes row r once row r - kRowsInFlight is handed over; its samples
  // are sized outside the lock (the first rows' before the threads start).
  auto sizeSlot = [&](RowSlot& slot, uint64_t r) {
    if (!all_have_bands) return;
    uint32_t size[3];
    regionOutputSize(rowRegion(r), levels, size);
    slot.samples.resize(uint64_t{size[0]} * size[1] * size[2] * sample_bytes);
  };
  try {
    for (uint64_t r = 0; r < std::min(rows, kRowsInFlight); ++r) {
      slots[r].row = r;
      sizeSlot(slots[r], r);
    }
  } catch (const std::bad_alloc&) {
    const ChunkView& last = jobs.back().chunks.back();
    return Error{Status::kResourceLimit, last.offset, last.chunk_type.str(), "out of memory for the rows of tiles"};
  }

  // Called with `held` locked by the thread that completed a tile: hands over
  // every complete row in order, one thread at a time, the lock released
  // while options.tile_rows writes.
  auto handOver = [&](std::unique_lock<std::mutex>& held) {
    if (handing) return;
    handing = true;
    for (;;) {
      RowSlot& slot = slots[handed % kRowsInFlight];
      if (stop || handed == rows || slot.tiles_done < per_row) break;
      const uint64_t reuse = handed + kRowsInFlight;  // the row the slot takes next
      const bool hand = has_samples && !any_error;
      held.unlock();
      bool written = true;
      if (hand) {
        const GridRegion region = rowRegion(handed);
        const uint64_t step = uint64_t{1} << levels;
        const uint32_t first = static_cast<uint32_t>((uint64_t{region.lo[axis]} + step - 1) / step);
        uint32_t size[3];
        regionOutputSize(region, levels, size);
        if (size[axis] > 0) written = options.tile_rows(axis, first, size[axis], slot.samples);
      }
      if (reuse < rows) sizeSlot(slot, reuse);
      held.lock();
      if (!written) write_failed = stop = true;
      slot.row = reuse;
      slot.tiles_done = 0;
      ++handed;
      moved.notify_all();  // the next row's tiles may start while this thread hands over more
    }
    handing = false;
    moved.notify_all();
  };

  auto work = [&] {
    std::unique_lock<std::mutex> held(lock);
    try {
      for (;;) {
        moved.wait(held, [&] { return stop || next >= jobs.size() || next / per_row < handed + kRowsInFlight; });
        if (stop || next >= jobs.size()) return;
        const uint64_t j = next++;
        const uint64_t r = j / per_row;
        RowSlot& slot = slots[r % kRowsInFlight];  // slot.row == r: the window
        uint8_t* row_samples = slot.samples.data();
        held.unlock();
        DecodedGrid tile;
        const Error e = decodeTileJob(tiles, jobs[j], true, end_offset, tile_options, &tile);
        if (e.ok() && all_have_bands && tile.has_samples) {
          uint32_t origin[3], size[3], row_size[3];
          const GridRegion region = rowRegion(r);
          regionOutputSize(region, levels, row_size);
          tiles.box(jobs[j].tile, origin, size);
          placeTile(tile, origin, region, levels, row_size, sample_bytes, row_samples);
        }
        held.lock();
        errors[j] = e;
        any_error = any_error || !e.ok();
        has_samples = has_samples && tile.has_samples;
        out->bands_decoded += tile.bands_decoded;
        out->bands_total += tile.bands_total;
        out->tiles_with_samples += tile.has_samples;
        if (j == 0) out->wavelet = tile.wavelet;
        ++slot.tiles_done;
        handOver(held);
      }
    } catch (const std::bad_alloc&) {  // the other threads stop at their next tile
      if (!held.owns_lock()) held.lock();
      out_of_memory = stop = true;
      handing = false;
      moved.notify_all();
    } catch (...) {
      if (!held.owns_lock()) held.lock();
      if (!failure) failure = std::current_exception();
      stop = true;
      handing = false;
      moved.notify_all();
    }
  };
  out->tiles_with_samples = 0;
  parallelFor(std::min<uint64_t>(jobs.size(), static_cast<uint64_t>(std::max(options.threads, 1))), options.threads,
              [&](uint64_t) { work(); });
  if (failure) std::rethrow_exception(failure);
  out->samples.clear();
  // A failed write stops the decode, so the tiles' errors after it are not all
  // known: it is the answer, as when rows were decoded one after another.
  if (write_failed) return Error{Status::kIoError, 0, "output", "the decoded rows could not be written"};
  if (out_of_memory) {
    const ChunkView& last = jobs.back().chunks.back();
    return Error{Status::kResourceLimit, last.offset, last.chunk_type.str(), "out of memory for the rows of tiles"};
  }
  const Error* first = nullptr;
  for (const Error& e : errors)
    if (!e.ok() && (first == nullptr || e.offset < first->offset)) first = &e;
  if (first != nullptr) return *first;
  out->has_samples = has_samples;
  if (has_samples) std::copy(out_size, out_size + 3, out->output_size);
  return {};
}

}  // namespace mrsv
