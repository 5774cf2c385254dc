// spec: 5 decoding a wavelet-coded grid: chunk rules, bands, mask, residual,
// synthesis and the mapping to samples. Integer arithmetic throughout, so that
// every conforming decoder produces the same samples.
#include "grid/wavelet_decode.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <limits>
#include <memory>
#include <new>

#include "bitstream/range_coder_adapter.h"
#include "bitstream/range_decoder.h"
#include "common/byte_reader.h"
#include "common/large_array.h"
#include "grid/array_decoding.h"
#include "grid/array_payload.h"
#include "grid/baseline_coding.h"
#include "grid/coefficient_coding.h"
#include "grid/last_level_bands.h"
#include "grid/precincts.h"
#include "grid/sample_runs.h"
#include "grid/weighted_array_coding.h"
#include "wavelet/axis_plan.h"
#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv {
namespace {

using wavelet::kValueLimit;

Error orderError(const ChunkView& chunk, std::string message) {
  return Error{Status::kChunkOrder, chunk.offset, chunk.chunk_type.str(), std::move(message)};
}

// spec: 5.4 dequantizeSymbol() over a row of n values, with the test for
// saturation, which rarely succeeds, hoisted out of the multiplication.
void dequantizeRow(const int64_t* src, int64_t* dst, uint32_t n, uint64_t step) {
  const uint64_t limit = static_cast<uint64_t>(kValueLimit) / step;
  const int64_t signed_step = static_cast<int64_t>(step);
  for (uint32_t x = 0; x < n; ++x) {
    const int64_t q = src[x];
    dst[x] = magnitudeOf(q) <= limit ? q * signed_step : dequantizeSymbol(q, step);
  }
}

// floor((v + 2^(w-1)) / 2^w): round half up, for negative values too (spec 5.8.2).
// C++17 leaves >> of a negative value to the implementation; ~(~t >> w) shifts
// a non-negative value and is the floor for t < 0.
int64_t roundShift(int64_t v, int w) {
  const int64_t t = v + (w == 0 ? 0 : int64_t{1} << (w - 1));
  return t >= 0 ? t >> w : ~(~t >> w);
}

// The destination of a contiguous array over `box`.
ArrayDestination contiguous(int64_t* values, const ArrayBox& box) {
  return {values, box.size[0], size_t{box.size[0]} * box.size[1]};
}

// spec: 5.7.6 a blocked array payload (precinct_log2 > 0): the u32 length of
// each block, then the blocks' arrays back to back, each decoded by
// decodeArrayPayload over its own box into its place of `out`; a block of
// length 0 is all zeros. `resolution` gives the blocks (arrayBlocks), `skip` is
// in raster order of the whole box. Arrays that need a contiguous destination
// (predicted or baseline; `out.step` 0) go through `block_values`, scratch of
// the largest block; `block_skip` likewise for a skip.
Error decodeBlockedPayload(const WaveletHeader& header, const uint8_t* payload, size_t size,
                           uint64_t payload_offset, const char* field, const ArrayBox& box,
                           const int resolution[3], ArrayPrediction prediction, const uint8_t* skip,
                           const ArrayDestination& out, int64_t* symbols, uint16_t* magnitudes,
                           BlockScratch* scratch) {
  if (header.precinct_log2 == 0)
    return decodeArrayPayload(header.entropy_mode, payload, size, payload_offset, field, box,
                              prediction, skip, out, symbols, magnitudes);
  const uint64_t count = arrayBlockCount(box, resolution, header.precinct_log2);
  const uint64_t table = 4 * count;
  auto fail = [&](uint64_t at, std::string message) {
    return Error{Status::kBadEntropyPayload, payload_offset + at, field, std::move(message)};
  };
  if (size < table)
    return fail(0, "coded data shorter than its table of " + std::to_string(count) + " block lengths");
  const std::vector<ArrayBlock> blocks = arrayBlocks(box, resolution, header.precinct_log2);
  std::vector<uint64_t>& offsets = scratch->offsets;
  if (!blockOffsets(payload, count, size, &offsets))
    return fail(0, "the block lengths add up to " + std::to_string(offsets[count]) + " bytes, not the " +
                       std::to_string(size - table) + " after the table");
  const bool strided = header.entropy_mode != kEntropyBaseline && prediction == ArrayPrediction::kNone;
  const bool narrow = out.narrow != nullptr;
  bool all_fit = true;
  for (size_t i = 0; i < blocks.size(); ++i) {
    const ArrayBlock& b = blocks[i];
    const uint64_t at = table + offsets[i], length = offsets[i + 1] - offsets[i];
    const size_t origin = b.origin[0] + b.origin[1] * out.row_stride + b.origin[2] * out.slice_stride;
    const uint8_t* block_skip = nullptr;
    if (skip && length != 0) {
      scratch->skip.resize(b.box.count());
      copyBlockOut(skip, box.size[0], size_t{box.size[0]} * box.size[1], b, scratch->skip.data());
      block_skip = scratch->skip.data();
    }
    if (length == 0) {  // every value of the block is 0
      for (uint32_t z = 0; z < b.box.size[2]; ++z)
        for (uint32_t y = 0; y < b.box.size[1]; ++y) {
          const size_t row = origin + y * out.row_stride + z * out.slice_stride;
          if (narrow)
            std::fill_n(out.narrow + row, b.box.size[0], int16_t{0});
          else
            std::fill_n(out.data + row, b.box.size[0], int64_t{0});
        }
    } else if (strided) {
      ArrayDestination place = out;
      bool fits = false;
      if (narrow) {
        place.narrow = out.narrow + origin;
        place.narrow_fits = &fits;
      } else {
        place.data = out.data + origin;
      }
      if (Error e = decodeArrayPayload(header.entropy_mode, payload + at, length, payload_offset + at,
                                       field, b.box, prediction, block_skip, place, symbols, magnitudes);
          !e.ok())
        return e;
      all_fit &= fits;
    } else {
      scratch->values.resize(b.box.count());
      if (Error e = decodeArrayPayload(header.entropy_mode, payload + at, length, payload_offset + at,
                                       field, b.box, prediction, block_skip,
                                       contiguous(scratch->values.data(), b.box), symbols, magnitudes);
          !e.ok())
        return e;
      copyBlockIn(scratch->values.data(), b, out.data, out.row_stride, out.slice_stride);
    }
  }
  if (out.narrow_fits) *out.narrow_fits = all_fit;
  return {};
}


}  // namespace

// spec: 5.6 and 5.7 (or 5.10 in the baseline mode), declared in
// grid/array_payload.h. Range-coded arrays without prediction (detail bands, mask, residual: nearly
// every coded symbol) go straight to `out`, which may be strided and dequantise
// (out.step), with `magnitudes` as scratch of box.count() entries. The others
// need a contiguous `out` with step 0 (row_stride = X, slice_stride = X * Y)
// and, with prediction, `symbols`: scratch of box.count() entries (neighbour
// prediction) or 2 * X (weighted prediction).
Error decodeArrayPayload(uint8_t entropy_mode, const uint8_t* payload, size_t size,
                         uint64_t payload_offset, const char* field, const ArrayBox& box,
                         ArrayPrediction prediction, const uint8_t* skip,
                         const ArrayDestination& out, int64_t* symbols, uint16_t* magnitudes) {
  auto fail = [&](std::string message) {
    return Error{Status::kBadEntropyPayload, payload_offset, field, std::move(message)};
  };
  if (entropy_mode == kEntropyBaseline) {  // spec: 5.10
    std::string problem = decodeBaselineArray(payload, size, box, prediction, skip, out.data);
    return problem.empty() ? Error{} : fail(problem);
  }
  RangeDecoder rc(payload, size);
  if (!rc.validStart()) return fail("coded data must start with a 0 byte");
  bool ok;
  if (prediction == ArrayPrediction::kNone) {
    ok = decodeUnpredictedArray(&rc, box, skip, out, magnitudes);
  } else {
    DecodingCoder coder{&rc};
    // Weighted arrays (spec 5.7.5) are only bands, which have no skipped positions.
    ok = prediction == ArrayPrediction::kWeighted
             ? skip == nullptr && codeWeightedArray(coder, out.data, symbols, box)
             : codeArray(coder, out.data, symbols, box, prediction, skip);
  }
  if (!ok) return fail("a magnitude prefix is longer than 39 bits");
  if (rc.overrun() != 0) return fail("coded data ends before the array does");
  if (rc.consumed() != size)
    return fail(std::to_string(size - rc.consumed()) + " bytes of coded data left over");
  return {};
}

struct WaveletState {
  const GridHeader* grid = nullptr;
  WaveletHeader header;
  bool seen_header = false;
  bool seen_mask = false;
  bool seen_residual = false;
  wavelet::GridPlan plan;
  std::vector<wavelet::Band> bands;
  // With last_level, the grid's last level is synthesised slice by slice and
  // its bands are kept there; `coefficients` then holds the other bands, and
  // array_plan is the last level's upper plan instead of `plan`.
  std::unique_ptr<LastLevelBands> last_level;
  wavelet::GridPlan array_plan;
  // The padded array of array_plan in the Mallat layout; null until a band has
  // coded data. Not zeroed when allocated: each band's box is written when the
  // band is read (step 0: zeros) and the boxes of bands not read are zeroed
  // before synthesis.
  LargeArray<int64_t> coefficients;
  std::vector<uint8_t> band_written;  // per band of the plan
  std::vector<int64_t> band_values;   // scratch for bands not decoded in place
  std::vector<int64_t> band_symbols;  // scratch for predicted bands
  std::vector<uint16_t> band_magnitudes;  // scratch for bands decoded in place
  BlockScratch blocks;                // scratch for blocked arrays (spec 5.7.6)
  std::vector<uint8_t> mask;          // 1 = no data; empty without a mask
  bool void_values = false;           // DecodeOptions::void_values: the mask is not applied to samples
  std::vector<int64_t> residual;      // empty without a residual
  uint32_t residual_step = 0;
  WaveletCoefficients* keep = nullptr;  // see WaveletGridSteps (wavelet_decode.h)
  // The levels above this one are synthesised in place already (their bands
  // consumed): WaveletGridSteps::levelSamples() goes down one level at a time.
  int synthesized = INT_MAX;
};

namespace {

ArrayBox gridBox(const GridHeader& g) {
  ArrayBox box;
  box.num_dims = g.num_dims;
  box.size[0] = g.size_x;
  box.size[1] = g.size_y;
  box.size[2] = g.size_z;
  return box;
}

// (bytes = kUnavailable: memory within the limit that the system refused.)
constexpr uint64_t kUnavailable = UINT64_MAX;
Error checkMemory(uint64_t bytes, const DecodeOptions& options, const ChunkView& chunk) {
  if (bytes == kUnavailable)
    return Error{Status::kResourceLimit, chunk.offset, chunk.chunk_type.str(),
                 "the memory for decoding could not be allocated"};
  if (bytes > options.max_output_bytes)
    return Error{Status::kResourceLimit, chunk.offset, chunk.chunk_type.str(),
                 "decoding needs " + std::to_string(bytes) + " bytes, above the decoder's limit of " +
                     std::to_string(options.max_output_bytes)};
  return {};
}

// The padded array of s->array_plan, once. The limit is checked against the
// whole plan's array either way, so that whether a stream is within it does
// not depend on how the decoder arranges its work.
Error allocateCoefficients(const DecodeOptions& options, const ChunkView& chunk, WaveletState* s) {
  if (s->coefficients) return {};
  if (Error e = checkMemory(s->plan.paddedCount() * 16, options, chunk); !e.ok()) return e;
  s->coefficients = makeLargeArray<int64_t>(s->array_plan.paddedCount());
  if (!s->coefficients) return checkMemory(kUnavailable, options, chunk);
  return {};
}

Error readMask(const ChunkView& chunk, const DecodeOptions& options, WaveletState* s) {
  ArrayBox box = gridBox(*s->grid);
  if (Error e = checkMemory(box.count() * 19, options, chunk); !e.ok()) return e;
  std::vector<int64_t> values(box.count());
  std::vector<uint16_t> magnitudes(box.count());
  const int full_resolution[3] = {0, 0, 0};
  if (Error e = decodeBlockedPayload(s->header, chunk.payload, chunk.chunk_length, chunk.payloadOffset(),
                                     "GMSK", box, full_resolution, ArrayPrediction::kNone, nullptr,
                                     contiguous(values.data(), box), nullptr, magnitudes.data(),
                                     &s->blocks);
      !e.ok())
    return e;
  s->mask.resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (values[i] != 0 && values[i] != 1)
      return Error{Status::kBadEntropyPayload, chunk.payloadOffset(), "GMSK",
                   "mask value " + std::to_string(values[i]) + " is not 0 or 1"};
    s->mask[i] = static_cast<uint8_t>(values[i]);
  }
  return {};
}

Error readBand(const ChunkView& chunk, uint32_t index, const DecodeOptions& options,
               WaveletState* s) {
  auto fail = [&](uint64_t at, const char* field, std::string message) {
    return Error{Status::kBadBandHeader, chunk.payloadOffset() + at,
                 std::string("GBND.") + field, std::move(message)};
  };
  if (chunk.chunk_length < kBandHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "GBND.chunk_length",
                 "GBND payload shorter than its 12-byte band header"};
  ByteReader r(chunk.payload, kBandHeaderSize);
  uint16_t band_index = r.u16();
  uint8_t band_flags = r.u8();
  uint8_t reserved = r.u8();
  uint64_t step = r.u64();
  if (band_index != index)
    return fail(0, "band_index", "band " + std::to_string(band_index) + " where band " +
                                     std::to_string(index) + " is next");
  if (band_flags & ~kBandPredictionMask)
    return Error{Status::kReservedNonZero, chunk.payloadOffset() + 2, "GBND.band_flags",
                 "reserved bits must be 0"};
  const uint8_t prediction_code = band_flags & kBandPredictionMask;
  if (prediction_code > kBandPredictionWeighted)
    return fail(2, "band_flags", "prediction 3 is reserved");
  if (prediction_code == kBandPredictionWeighted && s->header.entropy_mode == kEntropyBaseline)
    return fail(2, "band_flags", "weighted prediction needs entropy_mode 1");
  if (reserved != 0)
    return Error{Status::kReservedNonZero, chunk.payloadOffset() + 3, "GBND.reserved", "must be 0"};
  if (step > static_cast<uint64_t>(kValueLimit))
    return fail(4, "step", "step above 2^35 - 1");
  const uint8_t* coded = chunk.payload + kBandHeaderSize;
  size_t coded_size = chunk.chunk_length - kBandHeaderSize;
  if (step == 0) {
    if (coded_size != 0) return fail(4, "step", "a band with step 0 has no coded data");
    return {};  // all coefficients of the band are zero (written before synthesis)
  }
  if (Error e = allocateCoefficients(options, chunk, s); !e.ok()) return e;
  const wavelet::Band& band = s->bands[index];
  ArrayBox box;
  box.num_dims = s->plan.num_dims;
  for (int a = 0; a < 3; ++a) box.size[a] = band.size[a];
  const ArrayPrediction prediction = static_cast<ArrayPrediction>(prediction_code);
  const int axis_levels[3] = {s->header.levels[0], s->header.levels[1], s->header.levels[2]};
  int resolution[3];
  bandResolution(band.level, axis_levels, resolution);
  // The weighted predictor keeps two rows of errors (spec 5.7.5) besides the arrays.
  if (prediction == ArrayPrediction::kWeighted) {
    const uint64_t state = uint64_t{box.size[0]} * WeightedPredictor::kBytesPerColumn;
    if (Error e = checkMemory(s->plan.paddedCount() * 16 + state, options, chunk); !e.ok()) return e;
  }
  // A range-coded band without prediction (every detail band) is decoded in
  // place and dequantised there. The others are decoded to their symbols,
  // then dequantised into place (spec 5.4): in place too when the place is
  // contiguous (the band fills its array), else through scratch kept from band
  // to band (array() writes every entry, so it is not cleared).
  const bool in_place =
      s->header.entropy_mode != kEntropyBaseline && prediction == ArrayPrediction::kNone;
  // The band's box: in the padded array (the Mallat layout), or a box of its
  // own for a band of the last level kept apart.
  const bool apart = s->last_level && band.level == 1 && band.mask != 0;
  ArrayDestination place;
  bool narrow_fits = false;
  if (apart) {
    // Symbols in 16 bits when decoded in place; should one not fit, the band
    // is decoded again below, to its values.
    place = contiguous(nullptr, box);
    if (in_place) {
      place.narrow = s->last_level->narrow(band.mask, box.count(), step);
      place.narrow_fits = &narrow_fits;
    } else {
      place.data = s->last_level->wide(band.mask, box.count());
    }
    if (!place.narrow && !place.data) return checkMemory(kUnavailable, options, chunk);
  } else {
    const uint64_t px = s->array_plan.axis[0].size(0), pxy = px * s->array_plan.axis[1].size(0);
    place = {s->coefficients.get() + band.offset[0] + band.offset[1] * px + band.offset[2] * pxy,
             px, pxy};
  }
  const bool symbols_in_place = place.row_stride == box.size[0] &&
                                place.slice_stride == size_t{box.size[0]} * box.size[1];
  // The weighted predictor's contexts read two rows of symbols (5.7.5),
  // neighbour prediction's the whole array (5.7.4).
  const uint64_t symbol_scratch = prediction == ArrayPrediction::kWeighted ? 2 * uint64_t{box.size[0]}
                                  : prediction == ArrayPrediction::kNone   ? 0
                                                                           : box.count();
  try {
    if (in_place && s->band_magnitudes.size() < box.count())
      s->band_magnitudes.resize(box.count());
    if (!in_place && !symbols_in_place && s->band_values.size() < box.count())
      s->band_values.resize(box.count());
    if (s->band_symbols.size() < symbol_scratch) s->band_symbols.resize(symbol_scratch);
  } catch (const std::bad_alloc&) {
    return checkMemory(kUnavailable, options, chunk);
  }
  ArrayDestination decoded =
      in_place || symbols_in_place ? place : contiguous(s->band_values.data(), box);
  decoded.step = in_place ? step : 0;
  auto decode = [&] {
    return decodeBlockedPayload(s->header, coded, coded_size, chunk.payloadOffset() + kBandHeaderSize,
                                "GBND", box, resolution, prediction, nullptr, decoded,
                                s->band_symbols.data(), s->band_magnitudes.data(), &s->blocks);
  };
  Error e = decode();
  if (decoded.narrow && !narrow_fits) {  // rare: symbols of 2^15 and more
    decoded = contiguous(s->last_level->wide(band.mask, box.count()), box);
    if (!decoded.data) return checkMemory(kUnavailable, options, chunk);
    decoded.step = step;
    e = decode();
  }
  if (!e.ok()) return e;
  if (!in_place)
    for (uint32_t z = 0; z < box.size[2]; ++z)
      for (uint32_t y = 0; y < box.size[1]; ++y)
        dequantizeRow(decoded.data + y * decoded.row_stride + z * decoded.slice_stride,
                      place.data + y * place.row_stride + z * place.slice_stride, box.size[0],
                      step);
  s->band_written[index] = 1;
  return {};
}

Error readResidual(const ChunkView& chunk, const DecodeOptions& options, WaveletState* s) {
  if (chunk.chunk_length < kResidualHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "GRES.chunk_length",
                 "GRES payload shorter than its 4-byte residual header"};
  ByteReader r(chunk.payload, kResidualHeaderSize);
  uint32_t step = r.u32();
  if (step < 1 || step > kMaxResidualStep)
    return Error{Status::kBadWaveletHeader, chunk.payloadOffset(), "GRES.residual_step",
                 "residual_step must be 1 to 2^20"};
  ArrayBox box = gridBox(*s->grid);
  if (Error e = checkMemory(box.count() * 18, options, chunk); !e.ok()) return e;
  s->residual.assign(box.count(), 0);
  std::vector<uint16_t> magnitudes(box.count());
  s->residual_step = step;
  const int full_resolution[3] = {0, 0, 0};
  return decodeBlockedPayload(s->header, chunk.payload + kResidualHeaderSize,
                              chunk.chunk_length - kResidualHeaderSize,
                              chunk.payloadOffset() + kResidualHeaderSize, "GRES", box, full_resolution,
                              ArrayPrediction::kNone, s->mask.empty() ? nullptr : s->mask.data(),
                              contiguous(s->residual.data(), box), nullptr, magnitudes.data(),
                              &s->blocks);
}

template <class T>
void storeLittleEndian(T value, uint8_t* out) {
  uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  // The reference runs on little-endian hosts; spec 5.8.2 fixes little-endian output.
  std::memcpy(out, bytes, sizeof(T));
}

void writeSample(const GridHeader& g, const WaveletHeader& w, int64_t value, uint8_t* out) {
  switch (g.sample_type) {
    case SampleType::kUint8: *out = static_cast<uint8_t>(value); return;
    case SampleType::kInt16: storeLittleEndian(static_cast<int16_t>(value), out); return;
    case SampleType::kUint16: storeLittleEndian(static_cast<uint16_t>(value), out); return;
    case SampleType::kInt32: storeLittleEndian(static_cast<int32_t>(value), out); return;
    case SampleType::kFloat32:
    case SampleType::kFloat64: {
      double offset, scale;
      std::memcpy(&offset, &w.value_offset, 8);
      std::memcpy(&scale, &w.value_scale, 8);
      // Two IEEE-754 double operations, rounded to nearest: a product, then a sum.
      volatile double product = static_cast<double>(value) * scale;
      double y = offset + product;
      if (g.sample_type == SampleType::kFloat32) storeLittleEndian(static_cast<float>(y), out);
      else storeLittleEndian(y, out);
      return;
    }
  }
}

}  // namespace

// spec: 5.8.2 the sample value of one decoded value (integer samples).
int64_t clampToType(int64_t v, SampleType type) {
  int64_t lo, hi;
  switch (type) {
    case SampleType::kUint8: lo = 0; hi = 255; break;
    case SampleType::kInt16: lo = -32768; hi = 32767; break;
    case SampleType::kUint16: lo = 0; hi = 65535; break;
    default: lo = INT32_MIN; hi = INT32_MAX; break;
  }
  return v < lo ? lo : v > hi ? hi : v;
}

void sampleOfValue(const GridHeader& g, const WaveletHeader& w, int64_t t, bool masked, int64_t r,
                   uint32_t residual_step, uint8_t* out) {
  if (masked) {
    uint8_t nodata[8];
    std::memcpy(nodata, &g.nodata_bits, 8);
    std::memcpy(out, nodata, sampleSize(g.sample_type));
    return;
  }
  int64_t v = roundShift(t, w.frac_bits);
  if (g.sample_type != SampleType::kFloat32 && g.sample_type != SampleType::kFloat64) {
    // Clamped before and after the residual, so that an encoder can compute
    // the residual from the decoded samples alone.
    v = clampToType(v + static_cast<int64_t>(w.value_offset), g.sample_type);
    if (residual_step > 0) v = clampToType(v + r * int64_t{residual_step}, g.sample_type);
  }
  writeSample(g, w, v, out);
}

namespace {

// spec: 5.8.2 at full resolution, integer samples of type T: output position k
// is grid position k, so the mask and the residual are read at k. Row by row,
// with the common case (no mask, no residual) a loop of its own.
template <class T>
struct IntegerSamples {
  const int64_t* residual;
  const uint8_t* mask;
  int64_t offset, residual_step;
  int w;
  uint32_t nx, ny;
  uint8_t nodata[8];
  uint8_t* out;

  IntegerSamples(const WaveletState& s, uint8_t* samples) {
    const GridHeader& g = *s.grid;
    mask = s.mask.empty() || s.void_values ? nullptr : s.mask.data();
    residual = s.residual.empty() ? nullptr : s.residual.data();
    residual_step = s.residual_step;
    offset = static_cast<int64_t>(s.header.value_offset);
    w = s.header.frac_bits;
    nx = g.size_x;
    ny = g.size_y;
    std::memcpy(nodata, &g.nodata_bits, 8);
    out = samples;
  }

  // The samples of grid positions (x, y, z) .. (x + n - 1, y, z) from their
  // synthesised values src[0 .. n).
  void row(const int64_t* src, size_t x, size_t y, size_t z, size_t n) const {
    constexpr int64_t lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
    auto clamp = [](int64_t v) { return v < lo ? lo : v > hi ? hi : v; };
    auto store = [](int64_t v, uint8_t* dst) { storeLittleEndian(static_cast<T>(v), dst); };
    // Sizes and pointers in locals: the byte stores below could alias anything else.
    const int shift = w;
    const int64_t add = offset, rstep = residual_step;
    const size_t k = x + (y + z * size_t{ny}) * nx;
    const uint8_t* const m = mask ? mask + k : nullptr;
    const int64_t* const r = residual ? residual + k : nullptr;
    uint8_t* const dst = out + k * sizeof(T);
    if (!m && !r) return integerSampleRun<T>(src, dst, n, shift, add);
    uint8_t fill[sizeof(T)];
    std::memcpy(fill, nodata, sizeof(T));
    for (size_t i = 0; i < n; ++i) {
      if (m && m[i]) {
        std::memcpy(dst + i * sizeof(T), fill, sizeof(T));
        continue;
      }
      // Clamped before and after the residual, so that an encoder can compute
      // the residual from the decoded samples alone.
      int64_t v = clamp(roundShift(src[i], shift) + add);
      if (r) v = clamp(v + r[i] * rstep);
      store(v, dst + i * sizeof(T));
    }
  }

  // The whole grid from the synthesised array.
  void all(const WaveletState& s) const {
    const uint64_t px = s.plan.axis[0].size(0), pxy = px * s.plan.axis[1].size(0);
    const int64_t* coefficients = s.coefficients.get();
    for (uint32_t z = 0; z < s.grid->size_z; ++z)
      for (uint32_t y = 0; y < ny; ++y) row(coefficients + y * px + z * pxy, 0, y, z, nx);
  }

  // For wavelet::SynthesisRows: a finished row of the synthesis. The 9/7 plan
  // has no padding (4.11.1), so every row lies in the grid.
  static void fromSynthesis(void* self, size_t x, size_t y, size_t z, const int64_t* values,
                            size_t n) {
    static_cast<const IntegerSamples*>(self)->row(values, x, y, z, n);
  }
};

// spec: 5.8.1 and 5.8.2 at full resolution for integer samples of type T. The
// 9/7 synthesis hands the rows of its last pass straight to the sample
// mapping when it can (instead of writing them to the padded array and
// reading them back): the same values, one trip through memory fewer.
// False only when the few slices of the last level (last_level_bands.h)
// cannot be allocated.
template <class T>
bool synthesizeIntegerSamples(WaveletState* s, uint8_t* samples) {
  IntegerSamples<T> mapping(*s, samples);
  if (wavelet::isCdf97(s->plan.axis[0].order)) {
    const wavelet::SynthesisRows rows{&IntegerSamples<T>::fromSynthesis, &mapping};
    if (s->last_level) {  // see last_level_bands.h; the plan was checked when it was made
      wavelet::synthesizeFixedCdf97(s->array_plan, s->coefficients.get(), 0);
      return wavelet::synthesizeLastLevelCdf97(s->plan, s->last_level->rows(s->coefficients.get()),
                                               rows);
    }
    if (wavelet::synthesizeFixedCdf97(s->plan, s->coefficients.get(), 0, rows, s->synthesized))
      return true;
  } else {
    wavelet::synthesizeFixed(s->plan, s->coefficients.get(), 0, s->synthesized);
  }
  mapping.all(*s);
  return true;
}

// Zeroes the bands with step 0 and those not (yet) in the stream among the
// levels above `below` not synthesised yet (those of a last level kept apart
// are zero when not stored).
void zeroUnwrittenBands(WaveletState* s, int below) {
  const uint64_t px = s->array_plan.axis[0].size(0), pxy = px * s->array_plan.axis[1].size(0);
  for (size_t b = 0; b < s->bands.size(); ++b) {
    const wavelet::Band& band = s->bands[b];
    // (The coarsest scaling block, mask 0, belongs to every level.)
    if (s->band_written[b] || band.level > s->synthesized || (band.mask != 0 && band.level <= below) ||
        (s->last_level && band.level == 1 && band.mask != 0))
      continue;
    for (uint32_t z = 0; z < band.size[2]; ++z)
      for (uint32_t y = 0; y < band.size[1]; ++y) {
        int64_t* row = s->coefficients.get() + (band.offset[0] + (band.offset[1] + y) * px +
                                                (band.offset[2] + z) * pxy);
        std::fill(row, row + band.size[0], 0);
      }
    s->band_written[b] = 1;  // zero now, and not to be zeroed again
  }
}

// The output box at reduced resolution `stop`: the low-pass block of level
// `stop`, cut to what covers the grid (spec 5.8.3).
void outputBox(const wavelet::GridPlan& plan, int stop, uint32_t size[3], int axis_stop[3]) {
  for (int a = 0; a < 3; ++a) {
    const wavelet::AxisPlan& ax = plan.axis[a];
    axis_stop[a] = stop < ax.levels ? stop : ax.levels;
    if (axis_stop[a] == 0) {
      size[a] = ax.samples;
    } else if (wavelet::isCdf97(ax.order)) {
      size[a] = ax.size(axis_stop[a]);  // no padding (4.11.1)
    } else {
      uint32_t d = static_cast<uint32_t>(ax.order - 1);
      uint32_t step = 1u << axis_stop[a];
      size[a] = (ax.samples - d + step - 1) / step + d;
    }
  }
}

// Floating-point samples, and reduced resolution: one sample at a time from
// the low-pass block of level `stop` at the front of the padded array.
void mapSamplesOneByOne(const WaveletState& s, int stop, const uint32_t size[3],
                        const int axis_stop[3], uint8_t* samples) {
  const GridHeader& g = *s.grid;
  const bool full = stop == 0;
  const size_t bytes_per_sample = sampleSize(g.sample_type);
  const uint64_t px = s.array_plan.axis[0].size(0), pxy = px * s.array_plan.axis[1].size(0);
  size_t k = 0;
  for (uint32_t z = 0; z < size[2]; ++z)
    for (uint32_t y = 0; y < size[1]; ++y)
      for (uint32_t x = 0; x < size[0]; ++x, ++k) {
        uint8_t* dst = samples + k * bytes_per_sample;
        // The full-resolution sample this output stands for (itself when full).
        uint64_t fx = uint64_t{x} << axis_stop[0], fy = uint64_t{y} << axis_stop[1],
                 fz = uint64_t{z} << axis_stop[2];
        if (fx >= g.size_x) fx = g.size_x - 1;
        if (fy >= g.size_y) fy = g.size_y - 1;
        if (fz >= g.size_z) fz = g.size_z - 1;
        uint64_t fi = fx + fy * g.size_x + fz * uint64_t{g.size_x} * g.size_y;
        const bool residual = full && !s.residual.empty();
        sampleOfValue(g, s.header, s.coefficients[x + y * px + z * pxy],
                      !s.mask.empty() && !s.void_values && s.mask[fi], residual ? s.residual[fi] : 0,
                      residual ? s.residual_step : 0, dst);
      }
}

// spec: 5.8 synthesis and output mapping.
Error produceSamples(const DecodeOptions& options, const ChunkView& last, WaveletState* s,
                     DecodedGrid* out) {
  const GridHeader& g = *s->grid;
  s->void_values = options.void_values;
  const int stop = options.reduce_levels < s->plan.maxLevels() ? options.reduce_levels
                                                                : s->plan.maxLevels();
  // (None yet when every band so far had step 0.)
  if (Error e = allocateCoefficients(options, last, s); !e.ok()) return e;
  zeroUnwrittenBands(s, 0);
  if (s->keep && !s->last_level) {
    s->keep->plan = s->plan;
    s->keep->values.assign(s->coefficients.get(), s->coefficients.get() + s->plan.paddedCount());
  }

  uint32_t size[3];
  int axis_stop[3];
  outputBox(s->plan, stop, size, axis_stop);
  for (int a = 0; a < 3; ++a) out->output_size[a] = size[a];
  const size_t bytes_per_sample = sampleSize(g.sample_type);
  const uint64_t count = uint64_t{size[0]} * size[1] * size[2];
  if (Error e = checkMemory(s->plan.paddedCount() * 16 + count * bytes_per_sample, options, last);
      !e.ok())
    return e;
  out->samples.assign(count * bytes_per_sample, 0);
  out->has_samples = true;
  const bool full = stop == 0;
  const bool integer = g.sample_type != SampleType::kFloat32 && g.sample_type != SampleType::kFloat64;
  if (full && integer) {
    uint8_t* samples = out->samples.data();
    bool made = false;
    switch (g.sample_type) {
      case SampleType::kUint8: made = synthesizeIntegerSamples<uint8_t>(s, samples); break;
      case SampleType::kInt16: made = synthesizeIntegerSamples<int16_t>(s, samples); break;
      case SampleType::kUint16: made = synthesizeIntegerSamples<uint16_t>(s, samples); break;
      case SampleType::kInt32: made = synthesizeIntegerSamples<int32_t>(s, samples); break;
      default: break;
    }
    return made ? Error{} : checkMemory(kUnavailable, options, last);
  }
  // Only grids without a last level apart get here (last_level is made only
  // for full-resolution integer samples, all returned above): `coefficients`
  // is the padded array of the whole plan.
  wavelet::synthesizeFixed(s->plan, s->coefficients.get(), stop, s->synthesized);
  s->synthesized = stop;
  mapSamplesOneByOne(*s, stop, size, axis_stop, out->samples.data());
  return {};
}

}  // namespace

WaveletGridSteps::WaveletGridSteps(const DecodeOptions& options, DecodedGrid* out,
                                   WaveletCoefficients* keep)
    : options_(options), out_(out), s_(new WaveletState) {
  s_->grid = &out->header;
  s_->keep = keep;
}

WaveletGridSteps::~WaveletGridSteps() = default;

Error WaveletGridSteps::chunk(const ChunkView& chunk) {
  WaveletState& s = *s_;
  DecodedGrid* out = out_;
  const DecodeOptions& options = options_;
  const ChunkType& t = chunk.chunk_type;
  if (t == kChunkMeta || !t.critical()) return {};  // meta is read by the grid steps
  if (t == kChunkGridStored) return orderError(chunk, "GRAW in a wavelet-coded grid");
  if (t == kChunkWaveletHeader) {
    if (s.seen_header) return orderError(chunk, "a second WHDR");
    if (Error e = parseWaveletHeader(chunk, out->header, &s.header); !e.ok()) return e;
    s.seen_header = true;
    out->wavelet = s.header;
    const uint32_t samples[3] = {out->header.size_x, out->header.size_y, out->header.size_z};
    const int levels[3] = {s.header.levels[0], s.header.levels[1], s.header.levels[2]};
    wavelet::makeGridPlan(out->header.num_dims, samples, s.header.order, levels, &s.plan);
    s.bands = wavelet::bandsOf(s.plan);
    // The last level slice by slice: only for what synthesizeIntegerSamples() makes.
    const SampleType type = out->header.sample_type;
    if (options.reduce_levels == 0 && !options.whole_array_synthesis &&
        type != SampleType::kFloat32 && type != SampleType::kFloat64)
      s.last_level = LastLevelBands::make(s.plan);
    s.array_plan = s.last_level ? s.last_level->upperPlan() : s.plan;
    s.band_written.assign(s.bands.size(), 0);
    out->bands_total = static_cast<uint32_t>(s.bands.size());
    return {};
  }
  if (!s.seen_header) return orderError(chunk, "WHDR must come before " + t.str());
  if (t == kChunkNodataMask) {
    if (!s.header.hasMask()) return orderError(chunk, "GMSK without has_mask in WHDR");
    if (s.seen_mask) return orderError(chunk, "a second GMSK");
    if (out->bands_decoded > 0) return orderError(chunk, "GMSK after a GBND");
    if (Error e = readMask(chunk, options, &s); !e.ok()) return e;
    s.seen_mask = true;
  } else if (t == kChunkBand) {
    if (s.header.hasMask() && !s.seen_mask) return orderError(chunk, "GMSK must precede the bands");
    if (out->bands_decoded == out->bands_total)
      return orderError(chunk, "more GBND chunks than the plan has bands (" +
                                   std::to_string(out->bands_total) + ")");
    if (Error e = readBand(chunk, out->bands_decoded, options, &s); !e.ok()) return e;
    ++out->bands_decoded;
  } else if (t == kChunkResidual) {
    if (!s.header.hasResidual()) return orderError(chunk, "GRES without has_residual in WHDR");
    if (s.seen_residual) return orderError(chunk, "a second GRES");
    if (out->bands_decoded != out->bands_total) return orderError(chunk, "GRES before the last band");
    if (Error e = readResidual(chunk, options, &s); !e.ok()) return e;
    s.seen_residual = true;
    out->residual_decoded = true;
  } else {
    return orderError(chunk, t.str() + " in a wavelet-coded grid");
  }
  return {};
}

Error WaveletGridSteps::end(const Container& c) {
  const WaveletState& s = *s_;
  if (c.complete) {
    const ChunkView end{kChunkEnd, 0, 0, c.end_chunk_offset, nullptr};
    if (!s.seen_header) return orderError(end, "a wavelet-coded grid needs a WHDR chunk");
    if (out_->bands_decoded != out_->bands_total)
      return orderError(end, "the stream ends after " + std::to_string(out_->bands_decoded) +
                                 " of " + std::to_string(out_->bands_total) + " bands");
    if (s.header.hasResidual() && !s.seen_residual)
      return orderError(end, "has_residual is set but there is no GRES chunk");
  }
  if (out_->bands_decoded == 0) return {};  // a prefix before any band: shape only
  return produceSamples(options_, c.chunks.back(), s_.get(), out_);
}

int WaveletGridSteps::completeLevel() const {
  const WaveletState& s = *s_;
  const uint32_t done = out_->bands_decoded;
  if (!s.seen_header || done == 0) return -1;
  if (done < out_->bands_total) return s.bands[done].level;
  // Full resolution also needs the residual.
  return s.header.hasResidual() && !s.seen_residual ? 1 : 0;
}

int WaveletGridSteps::maxLevels() const { return s_->seen_header ? s_->plan.maxLevels() : 0; }

Error WaveletGridSteps::levelSamples(int level, const ChunkView& last, uint32_t size[3],
                                     std::vector<uint8_t>* samples) {
  WaveletState* s = s_.get();
  if (s->last_level || level < 1 || level < options_.reduce_levels || level > s->synthesized ||
      completeLevel() < 0 || completeLevel() > level)
    return Error{Status::kInvalidArgument, last.offset, "levelSamples",
                 "level " + std::to_string(level) + " is not available now"};
  if (level > s->plan.maxLevels()) level = s->plan.maxLevels();
  s->void_values = options_.void_values;
  if (Error e = allocateCoefficients(options_, last, s); !e.ok()) return e;
  zeroUnwrittenBands(s, level);
  int axis_stop[3];
  outputBox(s->plan, level, size, axis_stop);
  const size_t bytes_per_sample = sampleSize(s->grid->sample_type);
  const uint64_t count = uint64_t{size[0]} * size[1] * size[2];
  if (Error e = checkMemory(s->plan.paddedCount() * 16 + count * bytes_per_sample, options_, last);
      !e.ok())
    return e;
  wavelet::synthesizeFixed(s->plan, s->coefficients.get(), level, s->synthesized);
  s->synthesized = level;
  samples->assign(count * bytes_per_sample, 0);
  mapSamplesOneByOne(*s, level, size, axis_stop, samples->data());
  return {};
}

Error decodeWaveletGrid(const DecodeOptions& options, DecodedGrid* out,
                        WaveletCoefficients* coefficients) {
  WaveletGridSteps steps(options, out, coefficients);
  const Container& c = out->container;
  for (size_t i = 1; i < c.chunks.size(); ++i)
    if (Error e = steps.chunk(c.chunks[i]); !e.ok()) return e;
  return steps.end(c);
}

bool reducedResolution(const GridHeader& grid, const WaveletHeader& wavelet, int reduce_levels,
                       ReducedResolution* out) {
  const uint32_t samples[3] = {grid.size_x, grid.size_y, grid.size_z};
  const int levels[3] = {wavelet.levels[0], wavelet.levels[1], wavelet.levels[2]};
  wavelet::GridPlan plan;
  if (grid.coding != GridCoding::kWavelet || reduce_levels < 0 ||
      !wavelet::makeGridPlan(grid.num_dims, samples, wavelet.order, levels, &plan))
    return false;
  const int stop = reduce_levels < plan.maxLevels() ? reduce_levels : plan.maxLevels();
  int axis_stop[3];
  outputBox(plan, stop, out->size, axis_stop);
  // The scaling block (first) always; the detail bands above level `stop`.
  const std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
  out->bands_needed = 0;
  for (size_t b = 0; b < bands.size(); ++b)
    if (b == 0 || bands[b].level > stop) ++out->bands_needed;
  return true;
}

}  // namespace mrsv
