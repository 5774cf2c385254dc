// spec: 5.7.6 region decoding of a wavelet-coded grid in precincts.
//
// The windows first: the box at full resolution, then level by level the
// inputs its synthesis reads (wavelet/window_synthesis.h), a low and a high
// range per axis split at that level. Each band is needed over one box (its
// high range along the axes of its mask, the level's low range along the
// others), so only the blocks meeting that box are read and decoded. Then the
// synthesis runs coarse to fine over those windows alone, and the samples of
// the box are made by 5.8.2.
#include "grid/precinct_region.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "bitstream/container_framer.h"
#include "common/byte_reader.h"
#include "grid/array_payload.h"
#include "grid/precincts.h"
#include "tiles/tile_decode.h"
#include "wavelet/axis_plan.h"
#include "wavelet/window_synthesis.h"

namespace mrsv {
namespace {

using wavelet::kValueLimit;

struct Range {
  uint32_t lo = 0, hi = 0;
  uint32_t size() const { return hi - lo; }
};
using Ranges = std::array<Range, 3>;

// Values over a product of index ranges, x fastest; zero when made.
struct Window {
  uint32_t n[3] = {0, 0, 0};
  std::vector<int64_t> v;
  void make(const uint32_t sizes[3]) {
    std::copy(sizes, sizes + 3, n);
    v.assign(uint64_t{n[0]} * n[1] * n[2], 0);
  }
  void make(const Ranges& r) {
    const uint32_t sizes[3] = {r[0].size(), r[1].size(), r[2].size()};
    make(sizes);
  }
  size_t index(uint64_t x, uint64_t y, uint64_t z) const { return (z * n[1] + y) * n[0] + x; }
};

Error ioError(uint64_t offset, const std::string& what) {
  return Error{Status::kIoError, offset, "file", "cannot read " + what};
}

// The 8-byte chunk header at `pos`, framed by the container's own rules
// (spec 2.3: type syntax, length limit). False on an I/O error (*io_error
// set) or a framing error (left to the whole decode, which reports it).
bool readChunkHeader(ByteSource& source, uint64_t pos, ContainerFramer& framer, ChunkView* out,
                     Error* io_error) {
  uint8_t h[kChunkHeaderSize];
  if (!source.read(pos, kChunkHeaderSize, h)) {
    *io_error = ioError(pos, "a chunk header");
    return false;
  }
  return framer.chunkHeader(h, pos, out).ok();
}

// The blocks of one blocked array that meet `need` (ranges of the array's
// box), read from the file and decoded into `dst`, which covers `dst_ranges`
// (holding `need`) and is zero where no block is coded. With `skip` (over the
// same ranges, whole blocks) the array's skipped positions. False when the
// table does not add up or a block does not decode.
class BlockedArrayReader {
 public:
  // `limit`: the decoder's memory limit (DecodeOptions::max_output_bytes); a
  // block needing more is not decoded here (the whole decode reports 901).
  BlockedArrayReader(ByteSource& source, uint8_t entropy_mode, int precinct_log2, uint64_t limit)
      : source_(source), entropy_mode_(entropy_mode), precinct_log2_(precinct_log2), limit_(limit) {}

  bool read(uint64_t at, uint64_t size, const char* field, const ArrayBox& box, const int resolution[3],
            ArrayPrediction prediction, uint64_t step, const Ranges& need, const Ranges& dst_ranges,
            const Window* skip, Window* dst, Error* io_error) {
    uint32_t edge[3], count[3];
    blockGrid(box, resolution, precinct_log2_, edge, count);
    const uint64_t n = uint64_t{count[0]} * count[1] * count[2];
    if (size < 4 * n) return false;
    table_.resize(4 * n);
    if (n > 0 && !source_.read(at, 4 * n, table_.data())) {
      *io_error = ioError(at, "a table of block lengths");
      return false;
    }
    if (!blockOffsets(table_.data(), n, size, &offsets_)) return false;
    uint32_t first[3], last[3];  // the blocks meeting `need`, inclusive
    for (int a = 0; a < 3; ++a) {
      if (need[a].lo >= need[a].hi) return true;
      first[a] = need[a].lo / edge[a];
      last[a] = (need[a].hi - 1) / edge[a];
    }
    for (uint32_t k = first[2]; k <= last[2]; ++k)
      for (uint32_t j = first[1]; j <= last[1]; ++j)
        for (uint32_t i = first[0]; i <= last[0]; ++i) {
          const uint64_t b = i + uint64_t{count[0]} * (j + uint64_t{count[1]} * k);
          const uint64_t length = offsets_[b + 1] - offsets_[b];
          if (length == 0) continue;  // every value of the block is 0
          const uint32_t index[3] = {i, j, k};
          const ArrayBlock block = blockAt(box, edge, index);
          const uint64_t offset = at + 4 * n + offsets_[b];
          bytes_.resize(length);
          if (!source_.read(offset, length, bytes_.data())) {
            *io_error = ioError(offset, "a block");
            return false;
          }
          if (!decodeBlock(offset, field, block, prediction, skip, dst_ranges)) return false;
          place(block, step, need, dst_ranges, dst);
        }
    return true;
  }

 private:
  bool decodeBlock(uint64_t offset, const char* field, const ArrayBlock& block, ArrayPrediction prediction,
                   const Window* skip, const Ranges& ranges) {
    const uint64_t count = block.box.count();
    if (count > limit_ / 27) return false;
    values_.resize(count);
    magnitudes_.resize(count);
    symbols_.resize(prediction == ArrayPrediction::kWeighted ? 2 * uint64_t{block.box.size[0]}
                    : prediction == ArrayPrediction::kNone   ? 0
                                                             : count);
    const uint8_t* skipped = nullptr;
    if (skip) {
      skip_.resize(count);
      size_t k = 0;
      for (uint32_t z = 0; z < block.box.size[2]; ++z)
        for (uint32_t y = 0; y < block.box.size[1]; ++y)
          for (uint32_t x = 0; x < block.box.size[0]; ++x)
            skip_[k++] = skip->v[skip->index(block.origin[0] + x - ranges[0].lo, block.origin[1] + y - ranges[1].lo,
                                             block.origin[2] + z - ranges[2].lo)] != 0;
      skipped = skip_.data();
    }
    const ArrayDestination out{values_.data(), block.box.size[0], size_t{block.box.size[0]} * block.box.size[1]};
    return decodeArrayPayload(entropy_mode_, bytes_.data(), bytes_.size(), offset, field, block.box, prediction,
                              skipped, out, symbols_.data(), magnitudes_.data())
        .ok();
  }

  // The decoded block's values within `need` to their places in `dst`,
  // dequantised (spec 5.4) when step > 0.
  void place(const ArrayBlock& block, uint64_t step, const Ranges& need, const Ranges& ranges, Window* dst) const {
    uint32_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(need[a].lo, block.origin[a]);
      hi[a] = std::min(need[a].hi, block.origin[a] + block.box.size[a]);
    }
    for (uint32_t z = lo[2]; z < hi[2]; ++z)
      for (uint32_t y = lo[1]; y < hi[1]; ++y)
        for (uint32_t x = lo[0]; x < hi[0]; ++x) {
          const int64_t q = values_[(uint64_t{z - block.origin[2]} * block.box.size[1] + (y - block.origin[1])) *
                                        block.box.size[0] +
                                    (x - block.origin[0])];
          dst->v[dst->index(x - ranges[0].lo, y - ranges[1].lo, z - ranges[2].lo)] =
              step > 0 ? dequantizeSymbol(q, step) : q;
        }
  }

  ByteSource& source_;
  uint8_t entropy_mode_;
  int precinct_log2_;
  uint64_t limit_;
  std::vector<uint8_t> table_, bytes_, skip_;
  std::vector<uint64_t> offsets_;
  std::vector<int64_t> values_, symbols_;
  std::vector<uint16_t> magnitudes_;
};

// One pass of level j along axis a over the window `in` (along a: the low
// range, then the high range, the inputs `inputs` of the outputs `want`),
// giving `out` over `want` along a.
void synthesizeAxis(const wavelet::WindowLine& line, int a, const wavelet::WindowInputs& inputs, const Range& want,
                    const Window& in, Window* out) {
  uint32_t sizes[3] = {in.n[0], in.n[1], in.n[2]};
  sizes[a] = want.size();
  out->make(sizes);
  const uint64_t stride_in = a == 0 ? 1 : a == 1 ? in.n[0] : uint64_t{in.n[0]} * in.n[1];
  const uint64_t stride_out = a == 0 ? 1 : a == 1 ? out->n[0] : uint64_t{out->n[0]} * out->n[1];
  const int u = a == 0 ? 1 : 0, w = a == 2 ? 1 : 2;  // the other two axes
  std::vector<int64_t> values(in.n[a]), result(want.size()), scratch;
  uint32_t pos[3] = {0, 0, 0};
  for (pos[w] = 0; pos[w] < in.n[w]; ++pos[w])
    for (pos[u] = 0; pos[u] < in.n[u]; ++pos[u]) {
      pos[a] = 0;
      const int64_t* src = in.v.data() + in.index(pos[0], pos[1], pos[2]);
      for (uint32_t i = 0; i < in.n[a]; ++i) values[i] = src[i * stride_in];
      line.synthesize(inputs, values.data(), values.data() + (inputs.low1 - inputs.low0), want.lo, want.hi,
                      result.data(), &scratch);
      int64_t* dst = out->v.data() + out->index(pos[0], pos[1], pos[2]);
      for (uint32_t i = 0; i < want.size(); ++i) dst[i * stride_out] = result[i];
    }
}

// Copies `src` into `dst` at offsets `at` (src fits).
void paste(const Window& src, const uint32_t at[3], Window* dst) {
  ArrayBlock place;
  std::copy(at, at + 3, place.origin);
  std::copy(src.n, src.n + 3, place.box.size);
  copyBlockIn(src.v.data(), place, dst->v.data(), dst->n[0], size_t{dst->n[0]} * dst->n[1]);
}

}  // namespace

bool decodePrecinctRegion(ByteSource& source, uint64_t next, const DecodedGrid& parsed,
                          const GridRegion& region, const DecodeOptions& options, DecodedGrid* out,
                          Error* io_error) {
  const GridHeader& g = parsed.header;
  const WaveletHeader& wh = parsed.wavelet;
  const uint32_t samples[3] = {g.size_x, g.size_y, g.size_z};
  const int levels[3] = {wh.levels[0], wh.levels[1], wh.levels[2]};
  wavelet::GridPlan plan;
  if (!wavelet::makeGridPlan(g.num_dims, samples, wh.order, levels, &plan)) return false;
  const std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
  const int m = plan.maxLevels();

  // The output: the positions p of the region's 2^K lattice (11.6), K =
  // options.reduce_levels; along an axis of L levels the synthesis stops at
  // K_a = min(K, L) and position p is value p >> K_a there (5.8.3).
  const int k = options.reduce_levels;
  if (k < 0 || k > wavelet::kMaxLevels) return false;
  const int stop = std::min(k, m);  // the synthesis runs levels m .. stop + 1
  uint32_t out_count[3], first[3], shift[3];
  regionOutputSize(region, k, out_count);
  for (int a = 0; a < 3; ++a) {
    if (out_count[a] == 0) return false;  // no lattice position in the box: as the whole decode says
    first[a] = static_cast<uint32_t>((uint64_t{region.lo[a]} + (uint64_t{1} << k) - 1) >> k << k);
    shift[a] = static_cast<uint32_t>(std::min(k, plan.axis[a].levels));
  }
  // The windows: low[j] (the outputs of level j + 1, the low part of level j)
  // and high[j] per axis; an axis not split at j passes its window through.
  std::vector<Ranges> low(m + 1), high(m + 1);
  for (int a = 0; a < 3; ++a) {
    const uint64_t last = first[a] + (uint64_t{out_count[a]} - 1) * (uint64_t{1} << k);
    low[stop][a] = {first[a] >> shift[a], static_cast<uint32_t>((last >> shift[a]) + 1)};
  }
  for (int j = stop + 1; j <= m; ++j)
    for (int a = 0; a < 3; ++a) {
      if (plan.axis[a].levels < j) {
        low[j][a] = low[j - 1][a];
        continue;
      }
      const wavelet::WindowInputs in = wavelet::WindowLine(plan.axis[a], j).inputs(low[j - 1][a].lo, low[j - 1][a].hi);
      low[j][a] = {in.low0, in.low1};
      high[j][a] = {in.high0, in.high1};
    }
  // (Detail bands of the levels not synthesised are not needed.)
  // Every window, like the whole decode's arrays, within the memory limit.
  auto fits = [&](const Ranges& r) {
    return uint64_t{r[0].size()} * r[1].size() * r[2].size() <= options.max_output_bytes / 16;
  };
  for (int j = stop; j <= m; ++j) {
    Ranges both = low[j];
    for (int a = 0; a < 3; ++a) both[a].hi += high[j][a].size();
    if (!fits(both)) return false;
  }
  auto bandNeed = [&](const wavelet::Band& b) {
    Ranges r;
    for (int a = 0; a < 3; ++a)
      r[a] = b.mask != 0 && b.level <= stop ? Range{} : (b.mask >> a) & 1 ? high[b.level][a] : low[b.level][a];
    return r;
  };
  // The mask and the residual over the whole blocks (of the level-0 block
  // grid) that meet the box: the residual's skipped positions are the mask's
  // over each of its blocks.
  ArrayBox grid_box;
  grid_box.num_dims = g.num_dims;
  std::copy(samples, samples + 3, grid_box.size);
  const int full_resolution[3] = {0, 0, 0};
  uint32_t edge[3], count[3];
  blockGrid(grid_box, full_resolution, wh.precinct_log2, edge, count);
  Ranges cover;
  for (int a = 0; a < 3; ++a)
    cover[a] = {region.lo[a] / edge[a] * edge[a],
                static_cast<uint32_t>(
                    std::min<uint64_t>(samples[a], ((region.hi[a] - 1) / edge[a] + 1) * uint64_t{edge[a]}))};

  if (!fits(cover)) return false;
  BlockedArrayReader reader(source, wh.entropy_mode, wh.precinct_log2, options.max_output_bytes);
  Window mask, residual;
  std::vector<Window> band_values(bands.size());
  uint32_t bands_read = 0, residual_step = 0;
  bool mask_read = false, residual_seen = false, residual_read = false, complete = false;
  const uint64_t size = source.size();
  ContainerFramer framer(options.container);
  for (uint64_t pos = next; pos + kChunkHeaderSize <= size;) {
    ChunkView h;
    if (!readChunkHeader(source, pos, framer, &h, io_error)) return false;
    const uint64_t end = h.endOffset();
    if (h.chunk_type == kChunkEnd) {
      complete = h.chunk_length == 0 && end == size;
      if (!complete) return false;
      break;
    }
    if (end > size) {
      if (!options.container.allow_partial_tail) return false;
      break;  // a prefix: this chunk has not arrived
    }
    const uint64_t q = pos + kChunkHeaderSize;
    if (h.chunk_type == kChunkMeta || !h.chunk_type.critical()) {
    } else if (h.chunk_type == kChunkNodataMask) {
      if (!wh.hasMask() || mask_read || bands_read > 0) return false;
      mask.make(cover);
      if (!reader.read(q, h.chunk_length, "GMSK", grid_box, full_resolution, ArrayPrediction::kNone, 0, cover, cover,
                       nullptr, &mask, io_error))
        return false;
      for (int64_t v : mask.v)
        if (v != 0 && v != 1) return false;
      mask_read = true;
    } else if (h.chunk_type == kChunkBand) {
      if (bands_read >= bands.size() || (wh.hasMask() && !mask_read) || h.chunk_length < kBandHeaderSize) return false;
      uint8_t header[kBandHeaderSize];
      if (!source.read(q, kBandHeaderSize, header)) {
        *io_error = ioError(q, "a band header");
        return false;
      }
      ByteReader r(header, kBandHeaderSize);
      const uint16_t index = r.u16();
      const uint8_t flags = r.u8(), reserved = r.u8();
      const uint64_t step = r.u64();
      const uint8_t prediction = flags & kBandPredictionMask;
      if (index != bands_read || (flags & ~kBandPredictionMask) || prediction > kBandPredictionWeighted ||
          (prediction == kBandPredictionWeighted && wh.entropy_mode == kEntropyBaseline) || reserved != 0 ||
          step > static_cast<uint64_t>(kValueLimit) || (step == 0 && h.chunk_length != kBandHeaderSize))
        return false;
      const wavelet::Band& band = bands[index];
      const Ranges need = bandNeed(band);
      band_values[index].make(need);
      if (step != 0 && band_values[index].v.size() > 0) {
        ArrayBox box;
        box.num_dims = g.num_dims;
        std::copy(band.size, band.size + 3, box.size);
        int resolution[3];
        bandResolution(band.level, levels, resolution);
        if (!reader.read(q + kBandHeaderSize, h.chunk_length - kBandHeaderSize, "GBND", box, resolution,
                         static_cast<ArrayPrediction>(prediction), step, need, need, nullptr, &band_values[index],
                         io_error))
          return false;
      }
      ++bands_read;
    } else if (h.chunk_type == kChunkResidual) {
      if (!wh.hasResidual() || residual_seen || bands_read != bands.size() || h.chunk_length < kResidualHeaderSize)
        return false;
      uint8_t header[kResidualHeaderSize];
      if (!source.read(q, kResidualHeaderSize, header)) {
        *io_error = ioError(q, "a residual header");
        return false;
      }
      ByteReader r(header, kResidualHeaderSize);
      residual_step = r.u32();
      if (residual_step < 1 || residual_step > kMaxResidualStep) return false;
      residual_seen = true;
      if (stop > 0) {  // not applied at a reduced resolution (5.8.3)
        pos = end;
        continue;
      }
      residual.make(cover);
      if (!reader.read(q + kResidualHeaderSize, h.chunk_length - kResidualHeaderSize, "GRES", grid_box, full_resolution,
                       ArrayPrediction::kNone, 0, cover, cover, mask_read ? &mask : nullptr, &residual, io_error))
        return false;
      residual_read = true;
    } else {
      return false;  // any other critical chunk: the whole decode says what is wrong
    }
    pos = end;
  }
  if (complete && (bands_read != bands.size() || (wh.hasResidual() && !residual_seen))) return false;

  *out = DecodedGrid{};
  out->container = parsed.container;
  out->header = g;
  out->metadata = parsed.metadata;
  out->wavelet = wh;
  out->bands_total = static_cast<uint32_t>(bands.size());
  out->bands_decoded = bands_read;
  out->residual_decoded = residual_seen;
  out->region_by_precincts = true;
  std::copy(out_count, out_count + 3, out->output_size);
  if (bands_read == 0) return true;  // a prefix without samples
  // Coarse to fine: the scaling block's window, then per level the detail
  // bands beside it and the passes x, y, z of the axes split there.
  for (size_t b = bands_read; b < bands.size(); ++b) band_values[b].make(bandNeed(bands[b]));
  Window current = std::move(band_values[0]), passed;
  for (int j = m; j > stop; --j) {
    uint32_t sizes[3];
    for (int a = 0; a < 3; ++a) sizes[a] = low[j][a].size() + high[j][a].size();
    Window in;
    in.make(sizes);
    const uint32_t origin[3] = {0, 0, 0};
    paste(current, origin, &in);
    for (size_t b = 1; b < bands.size(); ++b) {
      if (bands[b].level != j) continue;
      uint32_t at[3];
      for (int a = 0; a < 3; ++a) at[a] = (bands[b].mask >> a) & 1 ? low[j][a].size() : 0;
      paste(band_values[b], at, &in);
    }
    for (int a = 0; a < 3; ++a) {
      if (plan.axis[a].levels < j) continue;
      const wavelet::WindowInputs inputs{low[j][a].lo, low[j][a].hi, high[j][a].lo, high[j][a].hi};
      synthesizeAxis(wavelet::WindowLine(plan.axis[a], j), a, inputs, low[j - 1][a], in, &passed);
      std::swap(in, passed);
    }
    current = std::move(in);
  }
  // spec 5.8.2 over the lattice positions p of the box: the value p >> K_a
  // of the synthesised window, the mask (and at full resolution the residual)
  // at p.
  const size_t bytes = sampleSize(g.sample_type);
  out->samples.resize(uint64_t{out_count[0]} * out_count[1] * out_count[2] * bytes);
  uint8_t* dst = out->samples.data();
  const uint32_t step = 1u << k;
  for (uint32_t i2 = 0; i2 < out_count[2]; ++i2)
    for (uint32_t i1 = 0; i1 < out_count[1]; ++i1)
      for (uint32_t i0 = 0; i0 < out_count[0]; ++i0, dst += bytes) {
        const uint32_t p[3] = {first[0] + i0 * step, first[1] + i1 * step, first[2] + i2 * step};
        uint64_t v[3], c[3];
        for (int a = 0; a < 3; ++a) {
          v[a] = (p[a] >> shift[a]) - low[stop][a].lo;
          c[a] = p[a] - cover[a].lo;  // the mask and the residual cover the same blocks
        }
        sampleOfValue(g, wh, current.v[current.index(v[0], v[1], v[2])],
                      mask_read && !options.void_values && mask.v[mask.index(c[0], c[1], c[2])] != 0,
                      residual_read ? residual.v[residual.index(c[0], c[1], c[2])] : 0,
                      residual_read ? residual_step : 0, dst);
      }
  out->has_samples = true;
  return true;
}

}  // namespace mrsv
