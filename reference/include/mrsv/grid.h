// Grids: header, in-memory samples, one-shot decode. spec: 3.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"

namespace mrsv {

// spec: 3.1 sample_type.
enum class SampleType : uint8_t {
  kUint8 = 1,
  kInt16 = 2,
  kUint16 = 3,
  kInt32 = 4,
  kFloat32 = 5,
  kFloat64 = 6,
};

bool isValidSampleType(uint8_t value);
size_t sampleSize(SampleType type);
const char* sampleTypeName(SampleType type);  // "uint8", "int16", ...
bool parseSampleType(const std::string& name, SampleType* out);

// spec: 3.1 coding.
enum class GridCoding : uint8_t {
  kStored = 0,
};

constexpr uint8_t kGridFlagHasNodata = 0x01;
constexpr size_t kGridHeaderSize = 24;

// spec: 3.1 grid_header(), the GHDR payload. Field names follow the spec.
struct GridHeader {
  uint8_t num_dims = 0;
  SampleType sample_type = SampleType::kUint8;
  GridCoding coding = GridCoding::kStored;
  uint8_t grid_flags = 0;
  uint32_t size_x = 1, size_y = 1, size_z = 1;
  uint64_t nodata_bits = 0;  // the no-data value's bit pattern, zero-extended

  // Exact once gridHeaderProblem() has accepted the header (at most 2^32).
  uint64_t sampleCount() const { return uint64_t{size_x} * size_y * size_z; }
  bool hasNodata() const { return (grid_flags & kGridFlagHasNodata) != 0; }
};

// Parses and checks a GHDR payload (spec 3.1 semantics and Annex B.3 limits).
Error parseGridHeader(const ChunkView& chunk, GridHeader* out);
// Returns an empty string when `header` obeys spec 3.1, otherwise the rule broken.
std::string gridHeaderProblem(const GridHeader& header);
std::vector<uint8_t> serializeGridHeader(const GridHeader& header);

struct DecodeOptions {
  ContainerOptions container;
  uint64_t max_output_bytes = kDefaultMaxOutputBytes;
};

// What a file, or a prefix of one, decodes to.
struct DecodedGrid {
  Container container;
  GridHeader header;
  Metadata metadata;
  bool has_samples = false;        // the sample data is complete in the bytes given
  std::vector<uint8_t> samples;    // sample bytes, little-endian, x fastest, then y, then z
};

// One-shot decode. Never throws; on failure returns the first broken rule
// and leaves `out` holding what was read before it.
Error decodeGrid(const uint8_t* data, size_t size, const DecodeOptions& options, DecodedGrid* out);

// spec: 3.4 canonical output, the bytes the conformance suite hashes.
std::vector<uint8_t> canonicalGridOutput(const DecodedGrid& grid);

}  // namespace mrsv
