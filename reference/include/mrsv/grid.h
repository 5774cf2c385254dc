// Grids: header, in-memory samples, one-shot decode. spec: 3.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
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
// The value of one little-endian sample (sampleSize(type) bytes at p), exact
// in a double for every sample type.
double sampleValue(const uint8_t* p, SampleType type);

// spec: 3.1 coding.
enum class GridCoding : uint8_t {
  kStored = 0,
  kWavelet = 1,
  kTiled = 2,  // spec 11: tiles, each coded as coding 1
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

// spec: 5.2 wavelet_header(), the WHDR payload of a wavelet-coded grid.
constexpr size_t kWaveletHeaderSize = 24;
constexpr uint8_t kWaveletFlagHasMask = 0x01;
constexpr uint8_t kWaveletFlagHasResidual = 0x02;
constexpr uint8_t kEntropyBaseline = 0;  // spec 5.10: run/size symbols, Huffman table in the stream
constexpr uint8_t kEntropyAdaptive = 1;  // spec 5.6, 5.7: context-modelled range coding
// WaveletHeader::order (and WaveletEncodeOptions::order) of the CDF 9/7 wavelet
// (spec 4.11), beside the B-spline orders 1 to 4.
constexpr int kWaveletOrderCdf97 = 5;

struct WaveletHeader {
  uint8_t order = 4;
  uint8_t levels[3] = {0, 0, 0};
  uint8_t entropy_mode = kEntropyAdaptive;
  uint8_t frac_bits = 0;
  uint8_t wavelet_flags = 0;
  // spec 5.2, 5.7.6: 0, or P: every array coded in blocks of precincts of 2^P samples.
  uint8_t precinct_log2 = 0;
  uint64_t value_offset = 0;  // int64 (integer samples) or float64 bits (float samples)
  uint64_t value_scale = 0;   // float64 bits; 0 for integer samples
  bool hasMask() const { return (wavelet_flags & kWaveletFlagHasMask) != 0; }
  bool hasResidual() const { return (wavelet_flags & kWaveletFlagHasResidual) != 0; }
};

// spec: 5.2 WHDR.precinct_log2 P: 0 (no blocks) or kMinPrecinctLog2..kMaxPrecinctLog2.
constexpr int kMinPrecinctLog2 = 4;
constexpr int kMaxPrecinctLog2 = 24;

// spec: 5.3 band_header(), the first 12 bytes of a GBND payload.
constexpr size_t kBandHeaderSize = 12;
constexpr uint8_t kBandPredictionMask = 0x03;  // bits 0-1: prediction 0 none, 1 neighbour, 2 weighted
constexpr uint8_t kBandPredictionNeighbour = 1;
constexpr uint8_t kBandPredictionWeighted = 2;
// spec: 5.5 residual_header(), the first 4 bytes of a GRES payload.
constexpr size_t kResidualHeaderSize = 4;
constexpr uint32_t kMaxResidualStep = 1u << 20;
// spec: 5.2 bound of |value_offset| for integer samples.
constexpr int64_t kMaxValueOffset = int64_t{1} << 40;

Error parseWaveletHeader(const ChunkView& chunk, const GridHeader& grid, WaveletHeader* out);
std::vector<uint8_t> serializeWaveletHeader(const WaveletHeader& header);

struct DecodeOptions {
  ContainerOptions container;
  uint64_t max_output_bytes = kDefaultMaxOutputBytes;
  // Reduced resolution (spec 5.8.3): stop the synthesis this many levels above
  // the finest; 0 decodes at full resolution.
  int reduce_levels = 0;
  // Synthesise through a padded array of the whole grid even where the
  // decoder would take the last level slice by slice (3-D 9/7 grids of
  // integer samples): the same samples, about twice the memory. The tests
  // compare the two.
  bool whole_array_synthesis = false;
  // Give no-data positions the value the synthesis made there (clamped to the
  // sample type, like any sample) instead of the no-data value: the surface the
  // mesh reconstructors (spec 8.1) read. Not a conformance output.
  bool void_values = false;
  // Progressive meshes (PM, PT): stop after the first batch of vertex splits
  // (or the base mesh) that leaves more than `stop_beyond_cells` triangles or
  // tets, or at least `stop_at_vertices` vertices, as if the stream ended
  // there (a prefix, 2.5.1): a reader after a coarse level decodes only the
  // batches it needs, and no chunk after the stop is checked. 0: no limit.
  uint64_t stop_beyond_cells = 0;
  uint64_t stop_at_vertices = 0;
  // Tiled grids (spec 11): tiles decoded by this many threads at once. The
  // samples and any error are the same whatever the count.
  int threads = 1;
  // Tiled grids, complete streams: when set, the samples are not gathered in
  // DecodedGrid::samples but handed here a row of tiles at a time, in order,
  // as soon as each row is decoded: the rows along the slowest axis with more
  // than one tile, so that each is a contiguous part of the output. `first`
  // and `count` are the row's output positions along that axis, `samples` its
  // output samples, x fastest (the callee may take them). A writer keeps the
  // memory to a row of tiles and writes while the next row decodes. The result
  // is that of a whole decode, error included; the rows already handed over
  // are then to be discarded, and so they are unless the decode ends with no
  // error and has_samples. Returning false stops the decode with kIoError.
  std::function<bool(int axis, uint32_t first, uint32_t count, std::vector<uint8_t>& samples)> tile_rows;
};

// Whether a progressive mesh decode stops at these counts (DecodeOptions).
inline bool stopsAt(const DecodeOptions& o, uint64_t cells, uint64_t vertices) {
  return (o.stop_beyond_cells != 0 && cells > o.stop_beyond_cells) ||
         (o.stop_at_vertices != 0 && vertices >= o.stop_at_vertices);
}

// What a file, or a prefix of one, decodes to.
struct DecodedGrid {
  Container container;
  GridHeader header;
  Metadata metadata;
  WaveletHeader wavelet;           // when header.coding is kWavelet
  uint32_t bands_total = 0;        // bands of the wavelet plan
  uint32_t bands_decoded = 0;      // complete GBND chunks among the bytes given
  bool residual_decoded = false;
  bool has_samples = false;        // samples were produced (stored: GRAW read; wavelet: >= 1 band)
  uint32_t output_size[3] = {0, 0, 0};  // sizes of `samples` (smaller with reduce_levels)
  // decodeGridRegion() read only the blocks the region reaches (a grid in
  // precincts, spec 5.7.6), not the whole grid.
  bool region_by_precincts = false;
  // Tiled grids (coding 2, spec 11): the tile size (0 for other codings), the
  // tiles, and those with samples (the grid has samples when all have).
  uint32_t tile_size[3] = {0, 0, 0};
  uint64_t tiles_total = 0;
  uint64_t tiles_with_samples = 0;
  std::vector<uint8_t> samples;    // sample bytes, little-endian, x fastest, then y, then z
};

// One-shot decode: the streaming decoder (stream_decoder.h) fed all the bytes
// at once. Never throws; on failure returns the first broken rule (Annex A.2)
// and leaves `out` holding what was read before it.
Error decodeGrid(const uint8_t* data, size_t size, const DecodeOptions& options, DecodedGrid* out);

// What a decode of a wavelet-coded grid with DecodeOptions::reduce_levels
// gives and reads, known from its GHDR and WHDR alone (spec 5.8.3): the sizes
// of its samples (DecodedGrid::output_size) and how many GBND chunks, the
// first in stream order, its synthesis uses. A prefix of the stream that ends
// before the next GBND decodes to the same samples (the GDAL driver's
// overviews read no more). False for a stored grid or headers with no plan.
struct ReducedResolution {
  uint32_t size[3] = {0, 0, 0};
  uint32_t bands_needed = 0;
};
bool reducedResolution(const GridHeader& grid, const WaveletHeader& wavelet, int reduce_levels,
                       ReducedResolution* out);

// spec: 3.4 canonical output, the bytes the conformance suite hashes.
std::vector<uint8_t> canonicalGridOutput(const DecodedGrid& grid);

}  // namespace mrsv
