// spec: 5.9 (informative) out-of-core encoding of a wavelet-coded grid in
// precincts (5.7.6, decision D91). The grid is scanned a box of precincts at a
// time; the 9/7 analysis runs level by level, a piece of each level at a time
// (a row of blocks, in 3-D cut again along y: wavelet/strip_analysis.h), each
// level's low-pass part kept in a temporary file for the next; every block of
// every band is quantised and coded as soon as its piece is analysed and kept
// in a temporary file. The stream is then written band by band, decoded a box
// of precincts at a time by region (the residual layer and the error
// figures), and finished. Memory: a few pieces and boxes, not the grid.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <unistd.h>

#include "common/byte_writer.h"
#include "common/crc32c.h"
#include "common/parallel_for.h"
#include "grid/array_encoding.h"
#include "grid/array_payload.h"
#include "grid/band_quantizer.h"
#include "grid/encoder_setup.h"
#include "grid/precincts.h"
#include "grid/void_fill.h"
#include "mrsv/encode.h"
#include "mrsv/encode_team.h"
#include "mrsv/tiled_grid.h"
#include "tiles/tile_encoding.h"
#include "wavelet/strip_analysis.h"

namespace mrsv {
namespace {

using wavelet::Band;

// An error bound's bands are quantised with a base step of max(4 s, 16)
// sample units for a residual step s (decision D91: the in-memory encoder
// tries s 2^k for k = -1 to 7 and keeps the smallest stream, a pass over the
// grid per try; on the SRTM terrains the best steps were 8 to 32 for
// lossless and 20 to 40 for s = 5).
double boundBaseStep(uint32_t residual_step) { return std::max(4.0 * residual_step, 16.0); }

Error invalid(std::string field, std::string message) {
  return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
}
Error ioFailure(std::string what) { return Error{Status::kIoError, 0, "file", std::move(what)}; }

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using TempFile = std::unique_ptr<std::FILE, FileCloser>;

// A temporary file written at its end or at offsets, read anywhere (pread):
// the scratch files of a team of one.
class Spill : public ByteSink, public SharedScratch {
 public:
  bool write(const uint8_t* data, size_t n) override { return append(data, n).ok(); }
  Error open() {
    file_.reset(std::tmpfile());
    return file_ ? Error{} : ioFailure("cannot create a temporary file");
  }
  uint64_t size() const { return end_; }
  Error append(const void* data, size_t n, uint64_t* offset = nullptr) {
    if (offset) *offset = end_;
    if (n && std::fwrite(data, 1, n, file_.get()) != n) return ioFailure("cannot write a temporary file");
    end_ += n;
    return {};
  }
  // Writes at `offset` (a file written this way only: no buffered appends).
  Error writeAt(uint64_t offset, const void* data, size_t n) override {
    const auto* p = static_cast<const uint8_t*>(data);
    end_ = std::max<uint64_t>(end_, offset + n);
    while (n > 0) {
      const ssize_t put = ::pwrite(fileno(file_.get()), p, n, static_cast<off_t>(offset));
      if (put <= 0) return ioFailure("cannot write a temporary file");
      p += put;
      offset += static_cast<uint64_t>(put);
      n -= static_cast<size_t>(put);
    }
    return {};
  }
  Error readAt(uint64_t offset, size_t n, void* out) override {
    if (std::fflush(file_.get()) != 0) return ioFailure("cannot write a temporary file");
    auto* p = static_cast<uint8_t*>(out);
    while (n > 0) {
      const ssize_t got = ::pread(fileno(file_.get()), p, n, static_cast<off_t>(offset));
      if (got <= 0) return ioFailure("cannot read back a temporary file");
      p += got;
      offset += static_cast<uint64_t>(got);
      n -= static_cast<size_t>(got);
    }
    return {};
  }
  Error sync() override { return {}; }

 private:
  TempFile file_;
  uint64_t end_ = 0;
};

// The team of one process.
class SoloTeam : public EncodeTeam {
 public:
  int member() const override { return 0; }
  int members() const override { return 1; }
  Error agree(const Error& mine) override { return mine; }
  void sum(std::vector<uint64_t>*) override {}
  void min(std::vector<double>*) override {}
  void max(std::vector<double>*) override {}
  std::unique_ptr<SharedScratch> scratch(Error* error) override {
    auto spill = std::make_unique<Spill>();
    *error = spill->open();
    return spill;
  }
  std::unique_ptr<WorkQueue> queue(uint64_t n) override { return std::make_unique<Counter>(n); }

 private:
  struct Counter : WorkQueue {
    explicit Counter(uint64_t n) : n(n) {}
    uint64_t take() override { return next < n ? next++ : n; }
    uint64_t n, next = 0;
  };
};

// A stream written by a team of one, in order, as the positioned writes of
// a shared file: each must start where the one before ended.
class InOrderScratch : public SharedScratch {
 public:
  explicit InOrderScratch(ByteSink* out) : out_(out) {}
  Error writeAt(uint64_t offset, const void* data, size_t n) override {
    if (offset != end_) return ioFailure("internal error: the stream is not written in order");
    end_ += n;
    return out_->write(static_cast<const uint8_t*>(data), n) ? Error{} : ioFailure("cannot write the stream");
  }
  Error readAt(uint64_t, size_t, void*) override { return ioFailure("internal error: the stream is write-only"); }
  Error sync() override { return {}; }

 private:
  ByteSink* out_;
  uint64_t end_ = 0;
};

// The first `size` bytes of a scratch file as a stream for the region decoder.
class ScratchSource : public ByteSource {
 public:
  ScratchSource(SharedScratch* scratch, uint64_t size) : scratch_(scratch), size_(size) {}
  uint64_t size() const override { return size_; }

 protected:
  bool readAt(uint64_t offset, size_t n, uint8_t* out) override {
    return offset + n <= size_ && scratch_->readAt(offset, n, out).ok();
  }

 private:
  SharedScratch* scratch_;
  uint64_t size_;
};

// One blocked array's blocks, coded and spilled: per block (index order) its
// length (0: all zeros, nothing spilled), its CRC-32C and, on the member that
// coded it, its place in that member's spill (elsewhere kElsewhere).
struct SpilledArray {
  static constexpr uint64_t kElsewhere = UINT64_MAX;
  std::vector<uint32_t> length, crc;
  std::vector<uint64_t> offset;
  // Room for the `n` blocks of the array's grid, the first time.
  void sized(uint64_t n) {
    if (!length.empty()) return;
    length.assign(n, 0);
    crc.assign(n, 0);
    offset.assign(n, kElsewhere);
  }
  bool anyCoded() const {
    return std::any_of(length.begin(), length.end(), [](uint32_t l) { return l != 0; });
  }
  uint64_t codedSize() const {
    uint64_t n = 4 * uint64_t{length.size()};
    for (uint32_t l : length) n += l;
    return n;
  }
  // Spills a block this member coded.
  Error put(uint64_t index, const std::vector<uint8_t>& bytes, Spill* spill) {
    length[index] = static_cast<uint32_t>(bytes.size());
    crc[index] = crc32c(0, bytes.data(), bytes.size());
    return spill->append(bytes.data(), bytes.size(), &offset[index]);
  }
  // Collective: every block's length and CRC on every member (each block
  // was coded by one member: the others add zeros); `blocks`: the array's.
  void share(EncodeTeam& team, uint64_t blocks) {
    sized(blocks);
    if (team.members() == 1) return;
    std::vector<uint64_t> both(2 * length.size());
    for (size_t i = 0; i < length.size(); ++i) {
      both[2 * i] = length[i];
      both[2 * i + 1] = crc[i];
    }
    team.sum(&both);
    for (size_t i = 0; i < length.size(); ++i) {
      length[i] = static_cast<uint32_t>(both[2 * i]);
      crc[i] = static_cast<uint32_t>(both[2 * i + 1]);
    }
  }
};

// Codes blocks of an array into a spill: the blocks whose indices lie in
// [first, last] along each axis, each copied from a source box (contiguous,
// x fastest) that holds them, at `origin` in the array.
class BlockCoder {
 public:
  BlockCoder(const WaveletHeader& wh, Spill* spill) : wh_(wh), spill_(spill) {}

  // The block grid of `array_box`.
  void grid(const ArrayBox& array_box, const int resolution[3], uint32_t edge[3], uint32_t count[3]) const {
    blockGrid(array_box, resolution, wh_.precinct_log2, edge, count);
  }

  // The coded blocks of a box of blocks, waiting to be stored in order.
  struct Coded {
    std::vector<uint64_t> index;
    std::vector<std::vector<uint8_t>> bytes;
  };

  // Codes the blocks whose indices lie in [first, last] along each axis,
  // `threads` at once. `quantize(local, q)`: fills a block's integers from
  // its box `local` (origin within the source box); false for a block of
  // zeros. `skip`: the source box's skip flags, or null.
  template <typename Quantize>
  Coded encode(const ArrayBox& array_box, const int resolution[3], const uint32_t first[3], const uint32_t last[3],
               const uint32_t origin[3], const ArrayBox& source, const uint8_t* skip, int threads,
               const Quantize& quantize) const {
    uint32_t edge[3], count[3];
    grid(array_box, resolution, edge, count);
    Coded out;
    std::vector<ArrayBlock> local;
    for (uint32_t k = first[2]; k <= last[2]; ++k)
      for (uint32_t j = first[1]; j <= last[1]; ++j)
        for (uint32_t i = first[0]; i <= last[0]; ++i) {
          const uint32_t at[3] = {i, j, k};
          ArrayBlock b = blockAt(array_box, edge, at);
          for (int a = 0; a < 3; ++a) b.origin[a] -= origin[a];
          local.push_back(b);
          out.index.push_back(i + uint64_t{count[0]} * (j + uint64_t{count[1]} * k));
        }
    out.bytes.resize(local.size());
    const size_t row = source.size[0], slice = row * source.size[1];
    parallelFor(local.size(), threads, [&](uint64_t i) {
      std::vector<int64_t> q(local[i].box.count());
      if (!quantize(local[i], q.data())) return;
      std::vector<uint8_t> block_skip;
      if (skip) {
        block_skip.resize(local[i].box.count());
        copyBlockOut(skip, row, slice, local[i], block_skip.data());
      }
      encodeArray(wh_.entropy_mode, q.data(), local[i].box, ArrayPrediction::kNone,
                  skip ? block_skip.data() : nullptr, &out.bytes[i]);
    });
    return out;
  }

  // Appends coded blocks to the spill, in their order, and notes their places.
  Error store(const ArrayBox& array_box, const int resolution[3], const Coded& coded, SpilledArray* out) {
    uint32_t edge[3], count[3];
    grid(array_box, resolution, edge, count);
    out->sized(uint64_t{count[0]} * count[1] * count[2]);
    for (size_t i = 0; i < coded.index.size(); ++i) {
      if (coded.bytes[i].empty()) continue;
      if (Error e = out->put(coded.index[i], coded.bytes[i], spill_); !e.ok()) return e;
    }
    return {};
  }

 private:
  const WaveletHeader& wh_;
  Spill* spill_;
};

// Lays a stream's chunks out one after another in a shared file: member 0
// writes the chunk headers, the fields before the blocks, the tables of
// lengths and the CRCs (the blocks' own CRCs combined); each member writes
// the blocks it coded. Every member computes the same offsets.
class StreamLayout {
 public:
  StreamLayout(EncodeTeam& team, SharedScratch* out, uint64_t at) : team_(team), out_(out), end_(at) {}
  uint64_t end() const { return end_; }

  // Bytes written as they are (member 0).
  Error raw(const std::vector<uint8_t>& bytes) {
    Error e = team_.member() == 0 ? out_->writeAt(end_, bytes.data(), bytes.size()) : Error{};
    end_ += bytes.size();
    return e;
  }
  Error chunk(const ChunkType& type, const std::vector<uint8_t>& payload) {
    return blockedChunk(type, payload, nullptr, nullptr);
  }
  // A blocked array's chunk: `head` (the chunk's own fields), the table of
  // lengths, the blocks (those of this member read from `blocks`). Without
  // `array`, a chunk of `head` alone.
  Error blockedChunk(const ChunkType& type, const std::vector<uint8_t>& head, const SpilledArray* array,
                     Spill* blocks) {
    const uint64_t length = head.size() + (array ? array->codedSize() : 0);
    if (length > kMaxChunkPayload)
      return invalid("precinct", "a " + std::string(type.c, 4) + " chunk would hold " + std::to_string(length) +
                                     " bytes, above the limit of " + std::to_string(kMaxChunkPayload) +
                                     " (use a larger step or a smaller grid)");
    std::vector<uint8_t> first;
    ByteWriter w(&first);
    for (int i = 0; i < 4; ++i) w.u8(static_cast<uint8_t>(type.c[i]));
    w.u32(static_cast<uint32_t>(length));
    first.insert(first.end(), head.begin(), head.end());
    if (array)
      for (uint32_t l : array->length) w.u32(l);
    uint32_t crc = crc32c(0, first.data(), first.size());  // the CRC covers the chunk header too (2.3)
    if (Error e = raw(first); !e.ok()) return e;
    std::vector<uint8_t> bytes;
    for (size_t b = 0; array && b < array->length.size(); ++b) {
      const uint32_t n = array->length[b];
      if (n == 0) continue;
      if (array->offset[b] != SpilledArray::kElsewhere) {
        bytes.resize(n);
        if (Error e = blocks->readAt(array->offset[b], n, bytes.data()); !e.ok()) return e;
        if (Error e = out_->writeAt(end_, bytes.data(), n); !e.ok()) return e;
      }
      crc = crc32cCombine(crc, array->crc[b], n);
      end_ += n;
    }
    std::vector<uint8_t> tail;
    ByteWriter(&tail).u32(crc);
    return raw(tail);
  }

 private:
  EncodeTeam& team_;
  SharedScratch* out_;
  uint64_t end_;
};

class PrecinctStreamEncoder {
 public:
  PrecinctStreamEncoder(const GridHeader& header, GridBoxReader& reader, const WaveletEncodeOptions& options,
                        const PrecinctStreamOptions& run, EncodeTeam& team)
      : header_(header), reader_(reader), options_(options), run_(run), team_(team) {}

  Error encode(const Metadata& metadata, SharedScratch& out, WaveletEncodeReport* report);

 private:
  // The bands coded at one base step.
  struct BandPass {
    double delta = 0;                   // the base step (x units)
    std::unique_ptr<Spill> blocks;      // the detail bands' coded blocks (this member's)
    std::vector<SpilledArray> bands;    // per band (detail bands)
    std::vector<uint8_t> coarsest;      // the coarsest band's chunk payload
    uint64_t bytes = 0;                 // framed size of the band chunks
  };
  // A precinct's edge at full resolution: 2^P samples.
  uint32_t stripRows() const { return 1u << options_.precinct_log2; }
  Error scan();
  // A box of a level's input (levelInput()).
  struct Piece {
    uint32_t lo[3] = {0, 0, 0}, n[3] = {1, 1, 1};
  };
  Error levelInput(int level, const Piece& piece, int threads, std::vector<double>* out);
  Error fillVoids(const uint32_t origin[3], const uint32_t box[3],
                  const std::function<double*(uint32_t, uint32_t)>& line);
  void refineTileFill(const uint32_t box[3], const std::vector<uint8_t>& valid, std::vector<double>* tile) const;
  Error analyzeLevel(int level, BandPass* pass);
  Error writeBody(const BandPass& pass, StreamLayout* stream);
  Error searchRate(const GridHeader& h, const Metadata& metadata);
  Error decodePass(SharedScratch* prefix, uint64_t prefix_size, uint32_t residual_step, ErrorTally* tally);
  void progress(double done) {
    if (run_.progress) run_.progress(std::min(done, 1.0));
  }
  uint64_t blockCount(size_t band) const;

  const GridHeader header_;
  GridBoxReader& reader_;
  const WaveletEncodeOptions options_;
  const PrecinctStreamOptions run_;
  EncodeTeam& team_;
  int num_dims_ = 1;
  uint32_t size_[3] = {1, 1, 1};
  size_t bytes_ = 1;          // per sample
  double c_min_ = 0, c_max_ = 0;
  uint64_t valid_count_ = 0;
  bool integer_ = true;
  WaveletSetup setup_;
  // Fill tiles (precincts at full resolution): which hold voids.
  uint32_t fill_count_[3] = {1, 1, 1};
  std::vector<uint8_t> tile_has_void_;
  Spill fills_;                         // the filled tiles' void values, in void order
  std::vector<uint64_t> fill_at_;       // per fill tile: where, or UINT64_MAX (not filled yet)
  std::vector<uint64_t> fill_count_of_; // per fill tile: how many voids
  std::mutex fill_lock_;                // over the three above
  Spill blocks_;                        // coded blocks of the mask and the residual (this member's)
  SpilledArray mask_, residual_;
  Error codeBands(double delta, BandPass* pass);
  BandPass pass_;                       // the bands the stream takes
  int iterations_ = 1;                  // passes over the grid (steps tried)
  std::vector<double> coarsest_;        // the coarsest band's coefficients
  std::unique_ptr<SharedScratch> level_low_;  // the low-pass part of the level just analysed
};

// The grid as boxes of whole precincts, near-square and of at most 2^19
// samples (so that a box's buffers stay small whatever the grid's width),
// in raster order of boxes; the same boxes whatever the thread count.
struct PrecinctBox {
  uint32_t first[3], last[3];  // precinct indices, inclusive
  uint32_t origin[3], size[3]; // samples
};

std::vector<PrecinctBox> precinctBoxes(int num_dims, const uint32_t grid[3], int precinct_log2) {
  const uint32_t edge = 1u << precinct_log2;
  uint32_t per_box[3] = {1, 1, 1}, count[3] = {1, 1, 1};
  constexpr uint64_t kBoxSamples = uint64_t{1} << 19;
  for (uint64_t samples = uint64_t{1} << (precinct_log2 * num_dims); 2 * samples <= kBoxSamples;) {
    int a = 0;
    for (int b = 1; b < num_dims; ++b)
      if (per_box[b] < per_box[a]) a = b;
    per_box[a] *= 2;
    samples *= 2;
  }
  for (int a = 0; a < num_dims; ++a) count[a] = (grid[a] + edge - 1) / edge;
  std::vector<PrecinctBox> boxes;
  for (uint32_t k = 0; k < count[2]; k += per_box[2])
    for (uint32_t j = 0; j < count[1]; j += per_box[1])
      for (uint32_t i = 0; i < count[0]; i += per_box[0]) {
        PrecinctBox b;
        const uint32_t at[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          b.first[a] = at[a];
          b.last[a] = std::min(at[a] + per_box[a], count[a]) - 1;
          b.origin[a] = at[a] * edge;
          b.size[a] = a < num_dims ? std::min((b.last[a] + 1) * edge, grid[a]) - b.origin[a] : 1;
        }
        boxes.push_back(b);
      }
  return boxes;
}

// The `n` items of `queue`, each taken by the first of `threads` workers to
// be free and passed to `work(item)`, until the queue is empty or `stop()`
// (called under `lock`, as every take is: the team's queue is not called
// from two threads at once) is true. No barrier between items: boxes of
// uneven cost keep every worker busy.
template <typename Stop, typename Work>
void drainQueue(WorkQueue& queue, uint64_t n, int threads, std::mutex& lock, const Stop& stop, const Work& work) {
  parallelFor(static_cast<uint64_t>(std::max(threads, 1)), threads, [&](uint64_t) {
    for (;;) {
      uint64_t item = n;
      {
        std::lock_guard<std::mutex> hold(lock);
        if (stop() || (item = queue.take()) >= n) return;
      }
      work(item);
    }
  });
}

// Pass 1, a box of precincts at a time: the valid samples' range and count,
// which fill tiles hold voids, and the mask's blocks.
Error PrecinctStreamEncoder::scan() {
  const uint32_t edge = stripRows();
  for (int a = 0; a < 3; ++a) fill_count_[a] = (size_[a] + edge - 1) / edge;
  tile_has_void_.assign(uint64_t{fill_count_[0]} * fill_count_[1] * fill_count_[2], 0);
  fill_at_.assign(tile_has_void_.size(), UINT64_MAX);
  fill_count_of_.assign(tile_has_void_.size(), 0);
  Error failed = fills_.open();
  const ArrayBox array{{size_[0], size_[1], size_[2]}, num_dims_};
  const int full_resolution[3] = {0, 0, 0};
  BlockCoder coder(setup_.header, &blocks_);
  bool first_valid = true;
  const int threads = std::max(1, run_.threads);
  const std::vector<PrecinctBox> boxes = precinctBoxes(num_dims_, size_, options_.precinct_log2);
  // What reading one box gave: its figures and its voids.
  struct BoxScan {
    double lo = 0, hi = 0;
    uint64_t valid = 0, bad = UINT64_MAX;
    std::vector<uint8_t> mask;  // 1 at a void; empty when the box has none
    Error error;
  };
  auto scanBox = [&](const PrecinctBox& box, BoxScan* r) {
    const uint64_t n = uint64_t{box.size[0]} * box.size[1] * box.size[2];
    std::vector<uint8_t> bytes(n * bytes_);
    std::string error;
    if (!reader_.read(box.origin, box.size, bytes.data(), &error)) {
      r->error = ioFailure(error);
      return;
    }
    for (uint64_t i = 0; i < n; ++i) {
      const uint8_t* p = bytes.data() + i * bytes_;
      if (header_.hasNodata() && std::memcmp(p, &header_.nodata_bits, bytes_) == 0) {
        if (r->mask.empty()) r->mask.assign(n, 0);
        r->mask[i] = 1;
        continue;
      }
      const double v = sampleValue(p, header_.sample_type);
      if (!std::isfinite(v)) {
        r->bad = std::min(r->bad, i);
        continue;
      }
      r->lo = r->valid ? std::min(r->lo, v) : v;
      r->hi = r->valid ? std::max(r->hi, v) : v;
      ++r->valid;
    }
  };
  // Boxes taken from the team's queue, a batch read at once, one per thread;
  // their figures combine in the order taken (min, max, sums: the same
  // whatever the order; the first bad sample found).
  auto combine = [&](const PrecinctBox& box, const BoxScan& r) -> Error {
    if (!r.error.ok()) return r.error;
    if (r.bad != UINT64_MAX) {
      const uint64_t x = box.origin[0] + r.bad % box.size[0], y = box.origin[1] + (r.bad / box.size[0]) % box.size[1],
                     z = box.origin[2] + r.bad / (uint64_t{box.size[0]} * box.size[1]);
      return invalid("samples", "sample " + std::to_string((z * size_[1] + y) * size_[0] + x) +
                                    " is NaN or infinite; mark such samples with --nodata");
    }
    if (r.valid) {
      c_min_ = first_valid ? r.lo : std::min(c_min_, r.lo);
      c_max_ = first_valid ? r.hi : std::max(c_max_, r.hi);
      first_valid = false;
      valid_count_ += r.valid;
    }
    if (r.mask.empty()) return {};
    // The fill tiles (precincts) of the box that hold voids, and the mask's blocks.
    const std::vector<uint8_t>& mask = r.mask;
    for (uint64_t p = 0; p < mask.size(); ++p) {
      if (!mask[p]) continue;
      const uint64_t x = box.origin[0] + p % box.size[0], y = box.origin[1] + (p / box.size[0]) % box.size[1],
                     z = box.origin[2] + p / (uint64_t{box.size[0]} * box.size[1]);
      tile_has_void_[x / edge + fill_count_[0] * (y / edge + uint64_t{fill_count_[1]} * (z / edge))] = 1;
    }
    const ArrayBox source{{box.size[0], box.size[1], box.size[2]}, num_dims_};
    BlockCoder::Coded coded =
        coder.encode(array, full_resolution, box.first, box.last, box.origin, source, nullptr, run_.threads,
                     [&](const ArrayBlock& local, int64_t* q) {
                       std::vector<uint8_t> m(local.box.count());
                       copyBlockOut(mask.data(), source.size[0], size_t{source.size[0]} * source.size[1], local,
                                    m.data());
                       std::copy(m.begin(), m.end(), q);
                       return std::any_of(m.begin(), m.end(), [](uint8_t v) { return v != 0; });
                     });
    return coder.store(array, full_resolution, coded, &mask_);
  };
  {
    // A failure names the first failing box in box order (boxes are taken
    // in order and every box taken is finished).
    std::unique_ptr<WorkQueue> queue = team_.queue(boxes.size());
    std::mutex lock;
    uint64_t failed_box = UINT64_MAX, scanned = 0;
    drainQueue(*queue, boxes.size(), threads, lock, [&] { return !failed.ok(); }, [&](uint64_t i) {
      BoxScan r;
      scanBox(boxes[i], &r);
      std::lock_guard<std::mutex> hold(lock);
      if (!failed.ok() && failed_box == UINT64_MAX) return;  // the scratch file failed to open
      Error e = i < failed_box ? combine(boxes[i], r) : Error{};
      if (!e.ok()) {
        failed = e;
        failed_box = i;
      }
      progress(0.05 * static_cast<double>(++scanned) / static_cast<double>(boxes.size()));
    });
  }
  if (Error e = team_.agree(failed); !e.ok()) return e;
  // The team's figures: every member's range, count and voids.
  if (team_.members() > 1) {
    std::vector<double> lo{first_valid ? HUGE_VAL : c_min_}, hi{first_valid ? -HUGE_VAL : c_max_};
    team_.min(&lo);
    team_.max(&hi);
    c_min_ = lo[0];
    c_max_ = hi[0];
    std::vector<uint64_t> counts(tile_has_void_.begin(), tile_has_void_.end());
    counts.push_back(valid_count_);
    team_.sum(&counts);
    valid_count_ = counts.back();
    for (size_t i = 0; i < tile_has_void_.size(); ++i) tile_has_void_[i] = counts[i] != 0;
    if (valid_count_ == 0) c_min_ = c_max_ = 0;
  }
  uint32_t edge_blocks[3], count[3];
  coder.grid(array, full_resolution, edge_blocks, count);
  mask_.share(team_, uint64_t{count[0]} * count[1] * count[2]);
  return {};
}

// The level's input over a piece: every x, lines [lo[1], lo[1] + n[1]) along
// y and [lo[2], lo[2] + n[2]) along z (in 2-D y is the strip axis and n[2] is
// 1), into `out` (x fastest, the padded row length). Level 1: the padded
// samples in x units, voids filled; above: the low-pass part of the level before.
Error PrecinctStreamEncoder::levelInput(int level, const Piece& piece, int threads, std::vector<double>* out) {
  const uint32_t px = setup_.plan.axis[0].size(level - 1);
  const uint64_t lines = uint64_t{piece.n[1]} * piece.n[2], values = lines * px;
  // Grown to the exact size, the old buffer freed first: a vector grown by
  // resize() doubles and holds both while it moves (75 MB for a 25 MB strip).
  if (out->capacity() < values) {
    *out = std::vector<double>();
    out->reserve(values);
  }
  out->resize(values);
  if (level > 1) {
    const uint64_t ny = setup_.plan.axis[1].size(level - 1);
    for (uint32_t z = 0; z < piece.n[2]; ++z)
      if (Error e = level_low_->readAt(((piece.lo[2] + uint64_t{z}) * ny + piece.lo[1]) * px * sizeof(double),
                                     uint64_t{piece.n[1]} * px * sizeof(double), out->data() + uint64_t{z} * piece.n[1] * px);
          !e.ok())
        return e;
    return {};
  }
  // The samples the piece's lines stand for (a padded line repeats the last
  // sample line of its axis), read as one box.
  const uint32_t n_y = num_dims_ >= 2 ? size_[1] : 1, n_z = num_dims_ == 3 ? size_[2] : 1;
  uint32_t origin[3] = {0, std::min(piece.lo[1], n_y - 1), std::min(piece.lo[2], n_z - 1)};
  uint32_t box[3] = {size_[0], 0, 0};
  box[1] = std::max(origin[1] + 1, std::min(piece.lo[1] + piece.n[1], n_y)) - origin[1];
  box[2] = std::max(origin[2] + 1, std::min(piece.lo[2] + piece.n[2], n_z)) - origin[2];
  std::vector<uint8_t> bytes(uint64_t{box[0]} * box[1] * box[2] * bytes_);
  std::string error;
  if (!reader_.read(origin, box, bytes.data(), &error)) return ioFailure(error);
  // Each sample line is converted once, into the first of the piece's lines
  // that stands for it (its owner); voids are filled there; the other lines
  // (padding) are copies.
  auto owner = [&](uint32_t g, int a) { return g >= piece.lo[a] ? g - piece.lo[a] : 0; };
  auto lineOf = [&](uint32_t y, uint32_t z) { return out->data() + (uint64_t{z} * piece.n[1] + y) * px; };
  parallelFor(uint64_t{box[1]} * box[2], threads, [&](uint64_t line) {
    const uint32_t gy = origin[1] + static_cast<uint32_t>(line % box[1]);
    const uint32_t gz = origin[2] + static_cast<uint32_t>(line / box[1]);
    const uint8_t* p = bytes.data() + line * box[0] * bytes_;
    double* dst = lineOf(owner(gy, 1), owner(gz, 2));
    for (uint32_t i = 0; i < box[0]; ++i, p += bytes_) {
      const bool valid = !header_.hasNodata() || std::memcmp(p, &header_.nodata_bits, bytes_) != 0;
      dst[i] = valid ? (sampleValue(p, header_.sample_type) - c_min_) / setup_.scale : 0.0;
    }
  });
  bytes = {};
  if (valid_count_ < header_.sampleCount())
    if (Error e = fillVoids(origin, box, [&](uint32_t gy, uint32_t gz) { return lineOf(owner(gy, 1), owner(gz, 2)); });
        !e.ok())
      return e;
  for (uint32_t z = 0; z < piece.n[2]; ++z)
    for (uint32_t y = 0; y < piece.n[1]; ++y) {
      const uint32_t gz = std::min(piece.lo[2] + z, n_z - 1), gy = std::min(piece.lo[1] + y, n_y - 1);
      double* dst = lineOf(y, z);
      const double* src = lineOf(owner(gy, 1), owner(gz, 2));
      if (src != dst) std::copy(src, src + size_[0], dst);
      std::fill(dst + size_[0], dst + px, dst[size_[0] - 1]);
    }
  return {};
}

// The voids of the sample box at `origin` filled by pull-push within their
// fill tile (a precinct at full resolution), so that every piece reading a
// tile fills it alike. `line(y, z)`: where sample line (y, z) of the box
// holds its values (x from 0).
Error PrecinctStreamEncoder::fillVoids(const uint32_t origin[3], const uint32_t box[3],
                                       const std::function<double*(uint32_t, uint32_t)>& line) {
  std::lock_guard<std::mutex> hold(fill_lock_);  // 3-D pieces run at once; the fills are kept once
  const uint32_t edge = stripRows();
  std::vector<uint8_t> bytes;
  uint32_t t_lo[3], t_hi[3];
  for (int a = 0; a < 3; ++a) {
    t_lo[a] = origin[a] / edge;
    t_hi[a] = (origin[a] + box[a] - 1) / edge;
  }
  for (uint32_t tz = t_lo[2]; tz <= t_hi[2]; ++tz)
    for (uint32_t ty = t_lo[1]; ty <= t_hi[1]; ++ty)
      for (uint32_t tx = t_lo[0]; tx <= t_hi[0]; ++tx) {
        const uint64_t tile_index = tx + fill_count_[0] * (ty + uint64_t{fill_count_[1]} * tz);
        if (!tile_has_void_[tile_index]) continue;
        const uint32_t t[3] = {tx, ty, tz};
        uint32_t t_origin[3], t_box[3];
        for (int a = 0; a < 3; ++a) {
          t_origin[a] = t[a] * edge;
          t_box[a] = a < num_dims_ ? std::min(edge, size_[a] - t_origin[a]) : 1;
        }
        bytes.resize(uint64_t{t_box[0]} * t_box[1] * t_box[2] * bytes_);
        std::string error;
        if (!reader_.read(t_origin, t_box, bytes.data(), &error)) return ioFailure(error);
        const size_t n = bytes.size() / bytes_;
        std::vector<double> tile(n);
        std::vector<uint8_t> valid(n);
        bool any_valid = false;
        for (size_t i = 0; i < n; ++i) {
          const uint8_t* p = bytes.data() + i * bytes_;
          valid[i] = std::memcmp(p, &header_.nodata_bits, bytes_) != 0;
          tile[i] = valid[i] ? (sampleValue(p, header_.sample_type) - c_min_) / setup_.scale : 0.0;
          any_valid |= valid[i] != 0;
        }
        // A tile is filled once: its void values wait in a file for the
        // other pieces and passes that read it.
        std::vector<double> fill;
        if (fill_at_[tile_index] != UINT64_MAX) {
          fill.resize(fill_count_of_[tile_index]);
          if (Error e = fills_.readAt(fill_at_[tile_index], fill.size() * sizeof(double), fill.data()); !e.ok()) return e;
          for (size_t i = 0, k = 0; i < n; ++i)
            if (!valid[i]) tile[i] = fill[k++];
        } else {
          if (any_valid) {
            fillVoidsPullPush(&tile, valid, t_box);
            refineTileFill(t_box, valid, &tile);
          }
          for (size_t i = 0; i < n; ++i)
            if (!valid[i]) fill.push_back(tile[i]);
          fill_count_of_[tile_index] = fill.size();
          if (Error e = fills_.append(fill.data(), fill.size() * sizeof(double), &fill_at_[tile_index]); !e.ok())
            return e;
        }
        // The tile's void values where it meets the box.
        for (uint32_t k = 0; k < t_box[2]; ++k)
          for (uint32_t j = 0; j < t_box[1]; ++j) {
            const uint32_t gy = t_origin[1] + j, gz = t_origin[2] + k;
            if (gy < origin[1] || gy >= origin[1] + box[1] || gz < origin[2] || gz >= origin[2] + box[2]) continue;
            double* dst = line(gy, gz) + t_origin[0];
            const size_t from = (size_t{k} * t_box[1] + j) * t_box[0];
            for (uint32_t i = 0; i < t_box[0]; ++i)
              if (!valid[from + i]) dst[i] = tile[from + i];
          }
      }
  return {};
}

// The in-memory encoder refines its pull-push fill over the whole grid
// (refineVoidFill); a fill tile is refined over a plan of its own. Measured
// on Rainier (SRTM voids) at step 8: 283,127 bytes with pull-push alone,
// 275,234 refined, 274,998 in memory.
void PrecinctStreamEncoder::refineTileFill(const uint32_t box[3], const std::vector<uint8_t>& valid,
                                           std::vector<double>* tile) const {
  GridHeader th = header_;
  th.size_x = box[0];
  th.size_y = box[1];
  th.size_z = box[2];
  WaveletEncodeOptions o = options_;
  o.precinct_log2 = 0;
  WaveletSetup ts;
  if (!makeWaveletSetup(th, c_min_, c_max_, o, &ts).ok()) return;
  std::vector<double> coefficients;
  analyzeSamples(ts.plan, box, *tile, &coefficients);
  refineVoidFill(ts.plan, box, ts.bands, ts.band_gain, valid, (c_max_ - c_min_) / setup_.scale, tile,
                 &coefficients);
}

// One level: its pieces (a strip of band rows along the slowest axis; in 3-D
// cut again into strips along y, so that a piece needs a few rows of planes,
// not whole planes), each analysed along z, y, x as analyze() does, its
// blocks coded, its low-pass part kept for the next level (or as the
// coarsest band).
Error PrecinctStreamEncoder::analyzeLevel(int level, BandPass* pass) {
  const double delta = pass->delta;
  const wavelet::GridPlan& plan = setup_.plan;
  const int s = num_dims_ - 1;
  const bool cut_y = num_dims_ == 3;
  const wavelet::StripLevel along_s = wavelet::stripLevel(plan, level, s);
  const wavelet::StripLevel along_y = wavelet::stripLevel(plan, level, 1);
  const WaveletHeader& wh = setup_.header;
  const int axis_levels[3] = {wh.levels[0], wh.levels[1], wh.levels[2]};
  int resolution[3];
  bandResolution(level, axis_levels, resolution);
  uint32_t edge[3];
  for (int a = 0; a < 3; ++a) edge[a] = std::max((1u << wh.precinct_log2) >> resolution[a], kMinBlockEdge);
  const bool top = level == plan.maxLevels();
  // The level's low-pass part (at the top: the coarsest band), written by
  // the members that analyse its pieces, read by every member.
  Error opened;
  std::unique_ptr<SharedScratch> next_low = team_.scratch(&opened);
  if (Error e = team_.agree(opened); !e.ok()) return e;
  uint32_t low_box[3];
  for (int a = 0; a < 3; ++a) low_box[a] = plan.axis[a].size(level);
  const uint32_t px = along_s.box[0];
  std::vector<double> in;
  const uint32_t strips_s = (along_s.lows + edge[s] - 1) / edge[s];
  const uint32_t strips_y = cut_y ? (along_y.lows + edge[1] - 1) / edge[1] : 1;
  // One piece: analysed on `threads` threads in `in`, its blocks coded, its
  // low-pass lines written (the stores under `store_lock`: pieces may run at once).
  std::mutex store_lock;
  auto analyzePiece = [&](uint32_t k, uint32_t j, int threads, std::vector<double>& in) -> Error {
      // The piece's kept outputs along s (and y): [k0, k1), [j0, j1).
      const uint32_t k0 = k * edge[s], k1 = std::min(k0 + edge[s], along_s.lows);
      const uint32_t j0 = j * edge[1], j1 = cut_y ? std::min(j0 + edge[1], along_y.lows) : 0;
      Piece piece;
      uint32_t first_s, count_s, first_y = 0, count_y = along_s.box[1];
      wavelet::stripInput(along_s, k0, k1, &first_s, &count_s);
      if (cut_y) wavelet::stripInput(along_y, j0, j1, &first_y, &count_y);
      piece.lo[1] = cut_y ? first_y : first_s;
      piece.n[1] = cut_y ? count_y : count_s;
      piece.lo[2] = cut_y ? first_s : 0;
      piece.n[2] = cut_y ? count_s : 1;
      if (Error e = levelInput(level, piece, threads, &in); !e.ok()) return e;
      uint32_t dims[3] = {px, piece.n[1], piece.n[2]};
      wavelet::keepAlong(along_s, dims, &in, first_s, count_s, k0, k1, threads);
      if (cut_y) wavelet::keepAlong(along_y, dims, &in, first_y, count_y, j0, j1, threads);
      wavelet::analyzeBelow(plan, level, 1, dims, in.data(), threads);
      // Per axis above x: the piece's low lines, then its high lines.
      uint32_t lows[3] = {0, 0, 0};
      lows[s] = std::min(k1, along_s.lows) - k0;
      if (cut_y) lows[1] = std::min(j1, along_y.lows) - j0;
      // Every block of every band of the level in this piece, coded at once
      // (one barrier per piece), each read from the piece where its band lies.
      struct Task {
        size_t band;
        uint32_t from[3];  // the band's part of the piece starts here in the piece
        ArrayBlock local;  // the block, origin within the band's part
        uint64_t index;    // in the band's block grid
      };
      std::vector<Task> tasks;
      std::vector<BandQuantizer> quantizers(setup_.bands.size());
      for (size_t bi = 0; bi < setup_.bands.size(); ++bi) {
        const Band& band = setup_.bands[bi];
        if (band.level != level && !(band.mask == 0 && top)) continue;
        // The band's part of this piece: where it starts, how large.
        uint32_t from[3] = {band.offset[0], 0, 0}, part[3] = {band.size[0], 1, 1};
        for (int a = 1; a < num_dims_; ++a) {
          const bool high = (band.mask >> a) & 1;
          from[a] = high ? lows[a] : 0;
          part[a] = high ? dims[a] - lows[a] : lows[a];
        }
        if (uint64_t{part[0]} * part[1] * part[2] == 0) continue;
        // The piece's first position in the band, and its block indices.
        uint32_t at[3] = {0, 0, 0}, index[3] = {0, 0, 0};
        at[s] = k0;
        index[s] = k;
        if (cut_y) {
          at[1] = j0;
          index[1] = j;
        }
        if (band.mask == 0) continue;  // the coarsest band: the top level's low-pass lines
        quantizers[bi] = bandQuantizer(setup_, bi, delta, integer_);
        const ArrayBox band_box{{band.size[0], band.size[1], band.size[2]}, num_dims_};
        uint32_t block_edge[3], block_count[3];
        blockGrid(band_box, resolution, wh.precinct_log2, block_edge, block_count);
        for (uint32_t i = 0; i < block_count[0]; ++i) {
          const uint32_t b_index[3] = {i, index[1], index[2]};
          Task t{bi, {from[0], from[1], from[2]}, blockAt(band_box, block_edge, b_index), 0};
          for (int a = 0; a < 3; ++a) t.local.origin[a] -= at[a];
          t.index = i + uint64_t{block_count[0]} * (index[1] + uint64_t{block_count[1]} * index[2]);
          tasks.push_back(t);
        }
      }
      std::vector<std::vector<uint8_t>> coded(tasks.size());
      parallelFor(tasks.size(), threads, [&](uint64_t ti) {
        const Task& t = tasks[ti];
        const ArrayBox& box = t.local.box;
        std::vector<double> c(box.count());
        for (uint32_t z = 0; z < box.size[2]; ++z)
          for (uint32_t y = 0; y < box.size[1]; ++y) {
            const double* src = in.data() +
                                ((uint64_t{t.from[2] + t.local.origin[2] + z} * dims[1]) + t.from[1] + t.local.origin[1] + y) *
                                    dims[0] +
                                t.from[0] + t.local.origin[0];
            std::copy(src, src + box.size[0], c.data() + (uint64_t{z} * box.size[1] + y) * box.size[0]);
          }
        std::vector<int64_t> q(box.count());
        if (!quantizeArray(quantizers[t.band], c.data(), box, q.data())) return;
        encodeArray(wh.entropy_mode, q.data(), box, ArrayPrediction::kNone, nullptr, &coded[ti]);
      });
      std::lock_guard<std::mutex> hold(store_lock);
      for (size_t ti = 0; ti < tasks.size(); ++ti) {
        if (coded[ti].empty()) continue;
        if (Error e = pass->bands[tasks[ti].band].put(tasks[ti].index, coded[ti], pass->blocks.get()); !e.ok())
          return e;
      }
      // The low-pass lines (every split axis low) for the next level, at
      // their place in its input.
      for (uint32_t z = 0; z < (cut_y ? lows[2] : 1); ++z)
        for (uint32_t y = 0; y < lows[1]; ++y) {
          const uint64_t gz = cut_y ? k0 + z : 0, gy = cut_y ? j0 + y : k0 + y;
          const double* src = in.data() + ((uint64_t{z} * dims[1]) + y) * dims[0];
          if (Error e = next_low->writeAt(((gz * low_box[1]) + gy) * low_box[0] * sizeof(double), src,
                                          low_box[0] * sizeof(double));
              !e.ok())
            return e;
        }
      return {};
  };
  // The pieces taken from the team's queue. In 2-D one at a time, lifted by
  // this member's threads: a piece is a strip of the grid's width (26 MB at
  // the mosaic's first level), two at once would pass a quarter of its raw
  // size. In 3-D a piece is a few rows of planes, small and many: each
  // thread takes pieces of its own (no barrier within a piece; on a
  // 256x256x1024 volume two threads gave 1.73x lifting pieces together).
  Error failed;
  for (size_t bi = 1; bi < setup_.bands.size(); ++bi)  // sized before pieces run at once
    if (setup_.bands[bi].level == level) pass->bands[bi].sized(blockCount(bi));
  {
    const uint64_t pieces = uint64_t{strips_s} * strips_y;
    std::unique_ptr<WorkQueue> queue = team_.queue(pieces);
    auto piece = [&](uint64_t p, int threads, std::vector<double>& buffer) {
      return analyzePiece(static_cast<uint32_t>(p / strips_y), static_cast<uint32_t>(p % strips_y), threads, buffer);
    };
    if (!cut_y) {
      for (uint64_t p; failed.ok() && (p = queue->take()) < pieces;) failed = piece(p, run_.threads, in);
    } else {
      std::mutex lock;
      drainQueue(*queue, pieces, run_.threads, lock, [&] { return !failed.ok(); }, [&](uint64_t p) {
        std::vector<double> own;
        Error e = piece(p, 1, own);
        std::lock_guard<std::mutex> hold(lock);
        if (failed.ok()) failed = e;
      });
    }
  }
  if (Error e = team_.agree(failed); !e.ok()) return e;
  if (Error e = next_low->sync(); !e.ok()) return e;
  // Every band's block lengths on every member.
  for (size_t bi = 1; bi < setup_.bands.size(); ++bi)
    if (setup_.bands[bi].level == level) pass->bands[bi].share(team_, blockCount(bi));
  if (top) {
    coarsest_.resize(uint64_t{low_box[0]} * low_box[1] * low_box[2]);
    level_low_ = nullptr;
    return team_.agree(next_low->readAt(0, coarsest_.size() * sizeof(double), coarsest_.data()));
  }
  level_low_ = std::move(next_low);
  return {};
}

// Codes every band at base step `delta` into `pass`: the analysis level by
// level, the detail bands' blocks as their strips are done, then the
// coarsest band (quantised block by block as the in-memory encoder does, and
// coded with both predictions). `pass->bytes`: the band chunks' framed size.
Error PrecinctStreamEncoder::codeBands(double delta, BandPass* pass) {
  *pass = BandPass{};
  pass->delta = delta;
  pass->blocks = std::make_unique<Spill>();
  if (Error e = team_.agree(pass->blocks->open()); !e.ok()) return e;
  pass->bands.assign(setup_.bands.size(), {});
  coarsest_.clear();
  const int top = setup_.plan.maxLevels();
  for (int level = 1; level <= top; ++level) {
    if (Error e = analyzeLevel(level, pass); !e.ok()) return e;
    if (!(options_.bits_per_sample > 0) || options_.step > 0 || options_.max_error >= 0)
      progress(0.05 + 0.6 * level / top);  // one pass: its levels
  }
  const WaveletHeader& wh = setup_.header;
  const int axis_levels[3] = {wh.levels[0], wh.levels[1], wh.levels[2]};
  const Band& band = setup_.bands[0];
  const ArrayBox box{{band.size[0], band.size[1], band.size[2]}, num_dims_};
  int resolution[3];
  bandResolution(band.level, axis_levels, resolution);
  const BandQuantizer quantizer = bandQuantizer(setup_, 0, delta, integer_);
  std::vector<int64_t> q_all(box.count(), 0);
  const bool any = quantizeBlocked(quantizer, coarsest_.data(), box, resolution, wh.precinct_log2, q_all.data());
  pass->coarsest = bandChunkHead(0, any ? quantizer.step : 0);
  if (any) {
    std::vector<uint8_t> coded;
    pass->coarsest[2] = encodeCoarsestBand(wh, q_all, box, resolution, options_.prediction, nullptr, &coded);
    pass->coarsest.insert(pass->coarsest.end(), coded.begin(), coded.end());
  }
  constexpr uint64_t kFraming = kChunkHeaderSize + kChunkCrcSize, kBandHead = 12;
  pass->bytes = kFraming + pass->coarsest.size();
  for (size_t bi = 1; bi < setup_.bands.size(); ++bi)
    pass->bytes += kFraming + kBandHead + (pass->bands[bi].anyCoded() ? pass->bands[bi].codedSize() : 0);
  return {};
}

// spec 5.9 item 6 out of core: the base step bisected on its logarithm, a
// pass over the grid per step tried (each pass's blocks in a file of its
// own), keeping the smallest step whose stream fits the rate. The stream's
// other chunks are counted with the error figures' largest text. Only the
// full pyramid is searched (as --progressive does in memory).
Error PrecinctStreamEncoder::searchRate(const GridHeader& h, const Metadata& metadata) {
  ContainerWriter head;
  head.addChunk(kChunkGridHeader, serializeGridHeader(h));
  // The error figures' room, as the in-memory search reserves it (a rate
  // records no error_bound).
  Metadata probe = metadata;
  for (const char* key : {"error_max_abs", "error_psnr_db", "error_rmse"}) probe.set(key, "-1.23457e+300");
  head.addChunk(kChunkMeta, serializeMetadata(probe));
  head.addChunk(kChunkWaveletHeader, serializeWaveletHeader(setup_.header));
  constexpr uint64_t kFraming = kChunkHeaderSize + kChunkCrcSize;
  uint64_t fixed = head.image().size() + kFraming;  // and MEND
  if (setup_.header.hasMask()) fixed += kFraming + mask_.codedSize();
  const double target = options_.bits_per_sample * static_cast<double>(h.sampleCount()) / 8.0;
  const double r = std::max(c_max_ - c_min_, 1e-300) * (1.0 / setup_.scale);
  double lo = std::log2(r) - 30, hi = std::log2(r) + 2;  // log2 of the step in x units
  bool found = false;
  BandPass trying;
  iterations_ = 0;
  for (int it = 0; it < 40 && hi - lo > 1e-3; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (Error e = codeBands(std::exp2(mid), &trying); !e.ok()) return e;
    ++iterations_;
    // A larger step gives a smaller stream.
    if (static_cast<double>(fixed + trying.bytes) <= target) {
      std::swap(pass_, trying);
      found = true;
      hi = mid;
      if (static_cast<double>(fixed + pass_.bytes) >= 0.999 * target) break;
    } else {
      lo = mid;
    }
    progress(0.05 + 0.6 * std::min(1.0, (it + 1) / 15.0));
  }
  if (!found) return invalid("bits_per_sample", "the rate is too low for even the coarsest approximation");
  return {};
}

// The number of blocks of a band's array (5.7.6).
uint64_t PrecinctStreamEncoder::blockCount(size_t band_index) const {
  const WaveletHeader& wh = setup_.header;
  const int axis_levels[3] = {wh.levels[0], wh.levels[1], wh.levels[2]};
  const Band& band = setup_.bands[band_index];
  int resolution[3];
  bandResolution(band.level, axis_levels, resolution);
  uint32_t edge[3], count[3];
  blockGrid(ArrayBox{{band.size[0], band.size[1], band.size[2]}, num_dims_}, resolution, wh.precinct_log2, edge, count);
  return uint64_t{count[0]} * count[1] * count[2];
}

// The chunks after WHDR that the decode pass reads: the mask (with voids),
// then the band chunks (GBND) of `pass` in band order.
Error PrecinctStreamEncoder::writeBody(const BandPass& pass, StreamLayout* stream) {
  if (setup_.header.hasMask())
    if (Error e = stream->blockedChunk(kChunkNodataMask, {}, &mask_, &blocks_); !e.ok()) return e;
  if (Error e = stream->chunk(kChunkBand, pass.coarsest); !e.ok()) return e;
  for (size_t bi = 1; bi < setup_.bands.size(); ++bi) {
    const bool any = pass.bands[bi].anyCoded();
    const std::vector<uint8_t> head =
        bandChunkHead(static_cast<uint16_t>(bi), any ? bandQuantizer(setup_, bi, pass.delta, integer_).step : 0);
    Error e = any ? stream->blockedChunk(kChunkBand, head, &pass.bands[bi], pass.blocks.get())
                  : stream->chunk(kChunkBand, head);
    if (!e.ok()) return e;
  }
  return {};
}

// The bands decoded by region (the normative decoder's samples), a box of
// whole precincts at a time, the boxes of a row of precincts decoded in
// parallel: the error figures and, with `residual_step`, the residual layer's
// blocks. A box holds about 2^19 samples, so that the region decoder's
// windows stay small whatever the grid's width.
Error PrecinctStreamEncoder::decodePass(SharedScratch* prefix, uint64_t prefix_size, uint32_t residual_step,
                                        ErrorTally* tally) {
  const ArrayBox array{{size_[0], size_[1], size_[2]}, num_dims_};
  const int full_resolution[3] = {0, 0, 0};
  BlockCoder coder(setup_.header, &blocks_);
  const int threads = std::max(1, run_.threads);
  // Near-square boxes re-decode the fewest blocks around them (the synthesis
  // reaches past a box's edges); the same boxes whatever the thread count,
  // so that the error sums (and the meta chunk) are the same bits.
  const std::vector<PrecinctBox> boxes = precinctBoxes(num_dims_, size_, options_.precinct_log2);
  // What decoding one box gave.
  struct BoxResult {
    PrecinctBox at;
    double sse = 0, max_abs = 0;
    BlockCoder::Coded residual;
    Error error;
  };
  const int64_t rs = residual_step;
  auto decodeBox = [&](BoxResult& b) {
    const uint32_t* origin = b.at.origin;
    const uint32_t* size = b.at.size;
    ScratchSource source(prefix, prefix_size);
    GridRegion region;
    for (int a = 0; a < 3; ++a) {
      region.lo[a] = origin[a];
      region.hi[a] = origin[a] + size[a];
    }
    DecodedGrid decoded;
    if (Error e = decodeGridRegion(source, region, DecodeOptions{}, &decoded); !e.ok()) {
      b.error = e;
      return;
    }
    if (!decoded.region_by_precincts) {
      b.error = Error{Status::kInvalidArgument, 0, "verify", "internal error: the stream was not decoded by precinct"};
      return;
    }
    const uint64_t n = uint64_t{size[0]} * size[1] * size[2];
    std::vector<uint8_t> input(n * bytes_);
    std::string error;
    if (!reader_.read(origin, size, input.data(), &error)) {
      b.error = ioFailure(error);
      return;
    }
    std::vector<int64_t> residual(residual_step ? n : 0, 0);
    std::vector<uint8_t> skip(residual_step ? n : 0, 0);
    for (uint64_t p = 0; p < n; ++p) {
      const uint8_t* in = input.data() + p * bytes_;
      const uint8_t* d = decoded.samples.data() + p * bytes_;
      if (header_.hasNodata() && std::memcmp(in, &header_.nodata_bits, bytes_) == 0) {
        if (std::memcmp(d, &header_.nodata_bits, bytes_) != 0) {
          b.error = Error{Status::kInvalidArgument, 0, "verify", "a void did not come back as no-data"};
          return;
        }
        if (residual_step) skip[p] = 1;
        continue;
      }
      const double v = sampleValue(in, header_.sample_type), got = sampleValue(d, header_.sample_type);
      double error_here = std::fabs(got - v);
      if (residual_step) {
        // The nearest multiple of the odd step: |e - r * step| <= (step - 1) / 2,
        // added to the decoded sample and clamped as the decoder does (5.8.2).
        const int64_t e = static_cast<int64_t>(v) - static_cast<int64_t>(got);
        const int64_t r = e >= 0 ? (e + rs / 2) / rs : -((-e + rs / 2) / rs);
        residual[p] = r;
        const int64_t final_value = clampToType(static_cast<int64_t>(got) + r * rs, header_.sample_type);
        error_here = std::fabs(static_cast<double>(final_value) - v);
      }
      b.sse += error_here * error_here;
      b.max_abs = std::max(b.max_abs, error_here);
    }
    if (!residual_step) return;
    const ArrayBox source_box{{size[0], size[1], size[2]}, num_dims_};
    b.residual = coder.encode(array, full_resolution, b.at.first, b.at.last, origin, source_box, skip.data(), 1,
                              [&](const ArrayBlock& local, int64_t* q) {
                                copyBlockOut(residual.data(), size[0], size_t{size[0]} * size[1], local, q);
                                return std::any_of(q, q + local.box.count(), [](int64_t v) { return v; });
                              });
  };
  // Boxes taken from the team's queue, a batch at a time, decoded in parallel.
  std::vector<double> sse(boxes.size(), 0.0), max_abs(boxes.size(), 0.0);
  Error failed;
  {
    std::unique_ptr<WorkQueue> queue = team_.queue(boxes.size());
    std::mutex lock;
    uint64_t decoded = 0;
    drainQueue(*queue, boxes.size(), threads, lock, [&] { return !failed.ok(); }, [&](uint64_t i) {
      BoxResult b;
      b.at = boxes[i];
      decodeBox(b);
      std::lock_guard<std::mutex> hold(lock);
      if (!failed.ok()) return;
      failed = b.error;
      sse[i] = b.sse;
      max_abs[i] = b.max_abs;
      if (failed.ok() && residual_step) failed = coder.store(array, full_resolution, b.residual, &residual_);
      progress(0.7 + 0.3 * static_cast<double>(++decoded) / static_cast<double>(boxes.size()));
    });
  }
  if (Error e = team_.agree(failed); !e.ok()) return e;
  // Every box's figures on every member (each box was decoded by one; the
  // others hold 0), added in box order whatever the team and thread count.
  team_.max(&sse);
  team_.max(&max_abs);
  for (size_t i = 0; i < boxes.size(); ++i) {
    tally->sse += sse[i];
    tally->max_abs = std::max(tally->max_abs, max_abs[i]);
  }
  if (residual_step) {
    uint32_t edge[3], count[3];
    coder.grid(array, full_resolution, edge, count);
    residual_.share(team_, uint64_t{count[0]} * count[1] * count[2]);
  }
  return {};
}

Error PrecinctStreamEncoder::encode(const Metadata& metadata, SharedScratch& out, WaveletEncodeReport* report) {
  GridHeader h = header_;
  h.coding = GridCoding::kWavelet;
  if (std::string problem = gridHeaderProblem(h); !problem.empty()) return invalid("grid_header", problem);
  num_dims_ = h.num_dims;
  size_[0] = h.size_x;
  size_[1] = h.size_y;
  size_[2] = h.size_z;
  bytes_ = sampleSize(h.sample_type);
  integer_ = h.sample_type != SampleType::kFloat32 && h.sample_type != SampleType::kFloat64;
  if (num_dims_ < 2) return invalid("grid", "out-of-core coding takes 2-D and 3-D grids (a 1-D grid fits in memory)");
  if (options_.precinct_log2 == 0) return invalid("precinct", "out-of-core wavelet coding needs precincts");
  if (!wavelet::isCdf97(options_.order)) return invalid("order", "out-of-core coding uses the CDF 9/7 wavelet only");
  if (options_.has_roi || options_.keep_fraction > 0)
    return invalid("options", "out-of-core coding takes no region of interest and no keep fraction in this version");
  if (options_.psnr > 0)
    return invalid("psnr", "out-of-core precinct coding takes a step, a rate, an error bound or lossless (a PSNR "
                           "target would decode the grid once per step tried)");
  if (!(options_.step > 0) && options_.max_error < 0 && !(options_.bits_per_sample > 0))
    return invalid("options", "give a step, a rate, an error bound or lossless");
  if (options_.bound_route == WaveletEncodeOptions::BoundRoute::kPredictive)
    return invalid("bound_route", "out-of-core precinct coding takes the residual route only (decision D91)");
  if (options_.max_error >= 0 && !integer_)
    return invalid("max_error", "error bounds and lossless coding need integer samples in this version");
  const uint32_t d = options_.max_error >= 0 ? static_cast<uint32_t>(std::floor(options_.max_error)) : 0;
  if (options_.max_error >= 0 && d > (kMaxResidualStep - 1) / 2) return invalid("max_error", "bound above 524287");
  if (Error e = team_.agree(blocks_.open()); !e.ok()) return e;
  setup_.header.entropy_mode = options_.entropy_mode;
  setup_.header.precinct_log2 = static_cast<uint8_t>(options_.precinct_log2);
  progress(0);
  if (Error e = scan(); !e.ok()) return e;
  if (Error e = makeWaveletSetup(h, c_min_, c_max_, options_, &setup_); !e.ok()) return e;
  const int top = setup_.plan.maxLevels();
  if (top == 0) return invalid("grid", "the grid is too small for out-of-core coding (no level); code it in memory");
  const uint32_t residual_step = options_.max_error >= 0 ? 2 * d + 1 : 0;
  if (valid_count_ < h.sampleCount()) setup_.header.wavelet_flags |= kWaveletFlagHasMask;
  if (options_.max_error < 0 && !(options_.step > 0)) {  // a rate (the error bound and the step come first)
    if (Error e = searchRate(h, metadata); !e.ok()) return e;
  } else {
    // An error bound: the bands at boundBaseStep(), a residual layer keeping
    // every sample within d.
    const double delta =
        options_.max_error >= 0 ? boundBaseStep(residual_step) : options_.step * (1.0 / setup_.scale);
    if (Error e = codeBands(delta, &pass_); !e.ok()) return e;
  }
  // The stream without meta and residual, to decode.
  Error opened;
  std::unique_ptr<SharedScratch> prefix = team_.scratch(&opened);
  if (Error e = team_.agree(opened); !e.ok()) return e;
  ContainerWriter head;
  head.addChunk(kChunkGridHeader, serializeGridHeader(h));
  head.addChunk(kChunkWaveletHeader, serializeWaveletHeader(setup_.header));
  StreamLayout prefix_layout(team_, prefix.get(), 0);
  Error written_prefix = prefix_layout.raw(head.image());
  if (written_prefix.ok()) written_prefix = writeBody(pass_, &prefix_layout);
  if (written_prefix.ok()) written_prefix = prefix_layout.chunk(kChunkEnd, {});
  if (Error e = team_.agree(written_prefix); !e.ok()) return e;
  if (Error e = prefix->sync(); !e.ok()) return e;
  progress(0.7);
  ErrorTally tally;
  tally.valid = valid_count_;
  tally.lo = c_min_;
  tally.hi = c_max_;
  tally.levels = top;
  if (Error e = decodePass(prefix.get(), prefix_layout.end(), residual_step, &tally); !e.ok()) return e;
  prefix.reset();
  if (options_.max_error >= 0 && tally.max_abs > d)
    return Error{Status::kInvalidArgument, 0, "verify",
                 "internal error: decoded error " + std::to_string(tally.max_abs) + " above the bound " +
                     std::to_string(d)};
  // The stream: GHDR, meta with the error figures, WHDR, the mask and the
  // bands as in the prefix, the residual, MEND.
  WaveletEncodeReport rep;
  const Metadata recorded = tally.record(metadata, options_, &rep);
  WaveletHeader wh = setup_.header;
  if (residual_step) wh.wavelet_flags |= kWaveletFlagHasResidual;
  ContainerWriter final_head;
  final_head.addChunk(kChunkGridHeader, serializeGridHeader(h));
  final_head.addChunk(kChunkMeta, serializeMetadata(recorded));
  final_head.addChunk(kChunkWaveletHeader, serializeWaveletHeader(wh));
  StreamLayout layout(team_, &out, 0);
  Error written = layout.raw(final_head.image());
  if (written.ok()) written = writeBody(pass_, &layout);
  if (written.ok() && residual_step) {
    std::vector<uint8_t> res_head;
    ByteWriter(&res_head).u32(residual_step);
    written = layout.blockedChunk(kChunkResidual, res_head, &residual_, &blocks_);
  }
  if (written.ok()) written = layout.chunk(kChunkEnd, {});
  if (Error e = team_.agree(written); !e.ok()) return e;
  if (Error e = out.sync(); !e.ok()) return e;
  const uint64_t written_bytes = layout.end();
  rep.bytes = written_bytes;
  rep.bits_per_sample = 8.0 * static_cast<double>(written_bytes) / static_cast<double>(h.sampleCount());
  rep.base_step = pass_.delta;
  rep.residual_step = residual_step;
  rep.iterations = iterations_;
  progress(1);
  if (report) *report = rep;
  return {};
}

}  // namespace

Error encodePrecinctGridFromReader(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                                   const WaveletEncodeOptions& options, const PrecinctStreamOptions& run,
                                   ByteSink& out, WaveletEncodeReport* report) {
  SoloTeam team;
  InOrderScratch stream(&out);
  PrecinctStreamEncoder encoder(header, reader, options, run, team);
  return encoder.encode(metadata, stream, report);
}

Error encodePrecinctGridAsTeam(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                               const WaveletEncodeOptions& options, const PrecinctStreamOptions& run,
                               EncodeTeam& team, SharedScratch& out, WaveletEncodeReport* report) {
  PrecinctStreamEncoder encoder(header, reader, options, run, team);
  return encoder.encode(metadata, out, report);
}

}  // namespace mrsv
