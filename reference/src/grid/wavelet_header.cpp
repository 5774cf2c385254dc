// spec: 5.2 wavelet_header() (WHDR).
#include <cmath>
#include <cstring>

#include "common/byte_reader.h"
#include "common/byte_writer.h"
#include "grid/precincts.h"
#include "mrsv/grid.h"
#include "wavelet/axis_plan.h"

namespace mrsv {
namespace {

bool isFloatType(SampleType t) { return t == SampleType::kFloat32 || t == SampleType::kFloat64; }

}  // namespace

Error parseWaveletHeader(const ChunkView& chunk, const GridHeader& grid, WaveletHeader* out) {
  auto fail = [&](Status s, uint64_t at, const char* field, std::string msg) {
    return Error{s, chunk.payloadOffset() + at, std::string("WHDR.") + field, std::move(msg)};
  };
  if (chunk.chunk_length != kWaveletHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "WHDR.chunk_length",
                 "WHDR payload must be " + std::to_string(kWaveletHeaderSize) + " bytes, not " +
                     std::to_string(chunk.chunk_length)};
  ByteReader r(chunk.payload, chunk.chunk_length);
  WaveletHeader h;
  h.order = r.u8();
  for (uint8_t& l : h.levels) l = r.u8();
  h.entropy_mode = r.u8();
  h.frac_bits = r.u8();
  h.wavelet_flags = r.u8();
  h.precinct_log2 = r.u8();
  h.value_offset = r.u64();
  h.value_scale = r.u64();

  if (!wavelet::isValidOrder(h.order))
    return fail(Status::kBadWaveletHeader, 0, "order", "order must be 1 to 4, or 5 (CDF 9/7)");
  for (int a = 0; a < 3; ++a) {
    if (a >= grid.num_dims && h.levels[a] != 0)
      return fail(Status::kBadWaveletHeader, 1 + a, "levels", "levels must be 0 beyond num_dims");
    if (h.levels[a] > wavelet::kMaxLevels)
      return fail(Status::kBadWaveletHeader, 1 + a, "levels",
                  "levels above " + std::to_string(wavelet::kMaxLevels));
  }
  if (h.entropy_mode != kEntropyAdaptive && h.entropy_mode != kEntropyBaseline)
    return fail(Status::kUnsupportedCoding, 4, "entropy_mode",
                "entropy_mode " + std::to_string(h.entropy_mode) + " is not defined in this version");
  if (h.frac_bits > 24) return fail(Status::kBadWaveletHeader, 5, "frac_bits", "frac_bits above 24");
  if (h.wavelet_flags & ~(kWaveletFlagHasMask | kWaveletFlagHasResidual))
    return fail(Status::kReservedNonZero, 6, "wavelet_flags", "reserved bits must be 0");
  // spec 5.2 checks 6 to 8: every rule on wavelet_flags, at its offset.
  if (h.hasMask() && !grid.hasNodata())
    return fail(Status::kBadWaveletHeader, 6, "wavelet_flags", "has_mask without a no-data value in GHDR");
  const bool float_samples = isFloatType(grid.sample_type);
  if (float_samples && h.hasResidual())
    return fail(Status::kBadWaveletHeader, 6, "wavelet_flags",
                "has_residual is only defined for integer samples");
  if (h.precinct_log2 != 0 &&
      (h.precinct_log2 < kMinPrecinctLog2 || h.precinct_log2 > kMaxPrecinctLog2))
    return fail(Status::kBadWaveletHeader, 7, "precinct_log2",
                "precinct_log2 " + std::to_string(h.precinct_log2) + " is not 0 or " +
                    std::to_string(kMinPrecinctLog2) + " to " + std::to_string(kMaxPrecinctLog2));
  if (float_samples) {
    double offset, scale;
    std::memcpy(&offset, &h.value_offset, 8);
    std::memcpy(&scale, &h.value_scale, 8);
    if (!std::isfinite(offset))
      return fail(Status::kBadWaveletHeader, 8, "value_offset", "must be finite");
    if (!std::isfinite(scale) || !(scale > 0))
      return fail(Status::kBadWaveletHeader, 16, "value_scale", "must be finite and positive");
  } else {
    int64_t offset = static_cast<int64_t>(h.value_offset);
    if (offset > kMaxValueOffset || offset < -kMaxValueOffset)
      return fail(Status::kBadWaveletHeader, 8, "value_offset", "|value_offset| above 2^40");
    if (h.value_scale != 0)
      return fail(Status::kBadWaveletHeader, 16, "value_scale", "must be 0 for integer samples");
  }
  // spec 5.2 check 12: each used axis has a plan (4.3, 4.11.1), reported at its levels byte.
  const uint32_t samples[3] = {grid.size_x, grid.size_y, grid.size_z};
  for (int a = 0; a < grid.num_dims; ++a) {
    wavelet::AxisPlan axis;
    if (!wavelet::makeAxisPlan(samples[a], h.order, h.levels[a], &axis))
      return fail(Status::kBadWaveletHeader, 1 + a, "levels",
                  "no decomposition of axis " + std::string(1, "xyz"[a]) + " with these levels (spec 4.3)");
  }
  const int levels[3] = {h.levels[0], h.levels[1], h.levels[2]};
  wavelet::GridPlan plan;
  if (!wavelet::makeGridPlan(grid.num_dims, samples, h.order, levels, &plan))
    return fail(Status::kBadWaveletHeader, 1, "levels", "no decomposition of this grid (spec 4.3)");
  // spec 5.2 check 13: the padded array, reported at the first levels byte.
  if (plan.paddedCount() > kMaxGridSamples)
    return fail(Status::kBadWaveletHeader, 1, "levels", "padded grid above 2^32 samples");
  *out = h;
  return {};
}

std::vector<uint8_t> serializeWaveletHeader(const WaveletHeader& h) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  w.u8(h.order);
  for (uint8_t l : h.levels) w.u8(l);
  w.u8(h.entropy_mode);
  w.u8(h.frac_bits);
  w.u8(h.wavelet_flags);
  w.u8(h.precinct_log2);
  w.u64(h.value_offset);
  w.u64(h.value_scale);
  return out;
}

}  // namespace mrsv
