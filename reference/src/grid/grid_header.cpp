// spec: 3.1 grid_header() (GHDR).
#include <cstring>

#include "common/byte_reader.h"
#include "common/byte_writer.h"
#include "mrsv/grid.h"

namespace mrsv {

bool isValidSampleType(uint8_t value) { return value >= 1 && value <= 6; }

size_t sampleSize(SampleType type) {
  switch (type) {
    case SampleType::kUint8: return 1;
    case SampleType::kInt16: return 2;
    case SampleType::kUint16: return 2;
    case SampleType::kInt32: return 4;
    case SampleType::kFloat32: return 4;
    case SampleType::kFloat64: return 8;
  }
  return 0;
}

const char* sampleTypeName(SampleType type) {
  switch (type) {
    case SampleType::kUint8: return "uint8";
    case SampleType::kInt16: return "int16";
    case SampleType::kUint16: return "uint16";
    case SampleType::kInt32: return "int32";
    case SampleType::kFloat32: return "float32";
    case SampleType::kFloat64: return "float64";
  }
  return "invalid";
}

bool parseSampleType(const std::string& name, SampleType* out) {
  for (uint8_t v = 1; v <= 6; ++v) {
    SampleType t = static_cast<SampleType>(v);
    if (name == sampleTypeName(t)) {
      *out = t;
      return true;
    }
  }
  return false;
}

double sampleValue(const uint8_t* p, SampleType type) {
  uint64_t bits = 0;
  const size_t n = sampleSize(type);
  for (size_t i = 0; i < n; ++i) bits |= uint64_t{p[i]} << (8 * i);  // little-endian
  switch (type) {
    case SampleType::kUint8: return static_cast<double>(bits);
    case SampleType::kInt16: return static_cast<int16_t>(static_cast<uint16_t>(bits));
    case SampleType::kUint16: return static_cast<double>(bits);
    case SampleType::kInt32: return static_cast<int32_t>(static_cast<uint32_t>(bits));
    case SampleType::kFloat32: {
      uint32_t b = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &b, 4);
      return f;
    }
    case SampleType::kFloat64: {
      double d;
      std::memcpy(&d, &bits, 8);
      return d;
    }
  }
  return 0;
}

std::string gridHeaderProblem(const GridHeader& h) {
  if (h.num_dims < 1 || h.num_dims > 3) return "num_dims must be 1, 2 or 3";
  const uint32_t sizes[3] = {h.size_x, h.size_y, h.size_z};
  static const char* const kNames[3] = {"size_x", "size_y", "size_z"};
  for (int axis = 0; axis < 3; ++axis) {
    if (axis < h.num_dims && (sizes[axis] < 1 || sizes[axis] > kMaxGridAxis))
      return std::string(kNames[axis]) + " must be 1 to " + std::to_string(kMaxGridAxis);
    if (axis >= h.num_dims && sizes[axis] != 1)
      return std::string(kNames[axis]) + " must be 1 beyond num_dims";
  }
  // Each size is below 2^25, so size_x*size_y fits in 64 bits; the third
  // factor is checked by division so that the product cannot wrap.
  uint64_t xy = uint64_t{h.size_x} * h.size_y;  // sizes are >= 1 here
  if (xy > kMaxGridSamples || xy > kMaxGridSamples / h.size_z)
    return "size_x*size_y*size_z exceeds " + std::to_string(kMaxGridSamples) + " samples";
  if (h.grid_flags & ~kGridFlagHasNodata) return "reserved bits of grid_flags must be 0";
  size_t bits = 8 * sampleSize(h.sample_type);
  if (!h.hasNodata() && h.nodata_bits != 0) return "nodata_bits must be 0 without has_nodata";
  if (bits < 64 && (h.nodata_bits >> bits) != 0)
    return "nodata_bits has bits set above the sample size";
  return {};
}

Error parseGridHeader(const ChunkView& chunk, GridHeader* out) {
  auto fail = [&](Status s, uint64_t at, const char* field, std::string msg) {
    return Error{s, chunk.payloadOffset() + at, std::string("GHDR.") + field, std::move(msg)};
  };
  if (chunk.chunk_length != kGridHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "GHDR.chunk_length",
                 "GHDR payload must be " + std::to_string(kGridHeaderSize) + " bytes, not " +
                     std::to_string(chunk.chunk_length)};
  ByteReader r(chunk.payload, chunk.chunk_length);
  GridHeader h;
  h.num_dims = r.u8();
  uint8_t sample_type = r.u8();
  uint8_t coding = r.u8();
  h.grid_flags = r.u8();
  h.size_x = r.u32();
  h.size_y = r.u32();
  h.size_z = r.u32();
  h.nodata_bits = r.u64();
  if (!isValidSampleType(sample_type))
    return fail(Status::kBadGridHeader, 1, "sample_type",
                "sample_type " + std::to_string(sample_type) + " is not 1 to 6");
  h.sample_type = static_cast<SampleType>(sample_type);
  if (coding != static_cast<uint8_t>(GridCoding::kStored) &&
      coding != static_cast<uint8_t>(GridCoding::kWavelet) &&
      coding != static_cast<uint8_t>(GridCoding::kTiled))
    return fail(Status::kUnsupportedCoding, 2, "coding",
                "coding " + std::to_string(coding) + " is not defined in this version");
  h.coding = static_cast<GridCoding>(coding);
  if (h.grid_flags & ~kGridFlagHasNodata)
    return fail(Status::kReservedNonZero, 3, "grid_flags", "reserved bits of grid_flags must be 0");
  if (std::string problem = gridHeaderProblem(h); !problem.empty())
    return fail(Status::kBadGridHeader, 0, "grid_header", problem);
  *out = h;
  return {};
}

std::vector<uint8_t> serializeGridHeader(const GridHeader& h) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  w.u8(h.num_dims);
  w.u8(static_cast<uint8_t>(h.sample_type));
  w.u8(static_cast<uint8_t>(h.coding));
  w.u8(h.grid_flags);
  w.u32(h.size_x);
  w.u32(h.size_y);
  w.u32(h.size_z);
  w.u64(h.nodata_bits);
  return out;
}

}  // namespace mrsv
