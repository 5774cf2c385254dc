// Encoders. Deterministic: the same grid, metadata and options give the same bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mrsv/encode_team.h"
#include "mrsv/grid.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"
#include "mrsv/tiled_grid.h"

namespace mrsv {

// Writes a grid with stored (uncompressed, lossless) samples: GHDR, meta (when
// not empty), GRAW, MEND. `samples` are little-endian, x fastest.
// Returns kInvalidArgument with the rule broken when the input cannot be
// represented (dimensions beyond the limits, sample count mismatch, bad metadata).
Error encodeStoredGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                       const Metadata& metadata, std::vector<uint8_t>* out);

// A region of interest in sample coordinates (local oracle, paper 2.2): a box
// (centre +- half_size) or an ellipsoid (centre, semi-axes half_size).
struct RegionOfInterest {
  bool ellipsoid = false;
  double center[3] = {0, 0, 0};
  double half_size[3] = {1, 1, 1};
  double falloff = 16;  // deviation of the Gaussian weight outside, in samples
};

// spec: 5.9 (informative) encoder options of wavelet-coded grids. The rate or
// quality is set by exactly one of: step, bits_per_sample, psnr, max_error
// (max_error 0 is lossless), keep_fraction.
struct WaveletEncodeOptions {
  // kWaveletOrderCdf97 (spec 4.11; best measured, 5.9), or a B-spline order: 1 Haar,
  // 2 linear (the best B-spline), 3 quadratic, 4 cubic.
  int order = kWaveletOrderCdf97;
  uint8_t entropy_mode = kEntropyAdaptive;  // or kEntropyBaseline (the paper's JPEG-like coder)
  int max_levels = 16;        // per axis; fewer when the axis is short (padding <= 1/32)
  double step = 0;            // base quantiser step in sample units
  double bits_per_sample = 0; // rate target (the stream stays at or below it)
  double psnr = 0;            // quality target in dB, peak = max - min of the valid samples
  double max_error = -1;      // >= 0: every valid sample within this of the input
  // How an error bound is met: wavelet bands plus a residual layer (every prefix
  // is a wavelet approximation), or no decomposition and neighbour prediction
  // (often smaller, not progressive); kAuto keeps the smaller stream.
  enum class BoundRoute { kAuto, kResidual, kPredictive };
  BoundRoute bound_route = BoundRoute::kAuto;
  // How the coarsest block is predicted (spec 5.7.4, 5.7.5): kAuto codes it both
  // ways and keeps the smaller (weighted only with range coding).
  enum class Prediction { kAuto, kNeighbour, kWeighted };
  Prediction prediction = Prediction::kAuto;
  // Only streams with decomposition levels (every prefix a coarser
  // approximation): the predictive route is not considered, neither for an
  // error bound (as kResidual) nor, for integer samples, beside the wavelets
  // under a rate or PSNR target (spec 5.9 item 6).
  bool progressive = false;
  double keep_fraction = 0;   // (0, 1]: global oracle, keep the most important coefficients
  bool has_roi = false;       // local oracle: full detail where basis functions reach the region
  RegionOfInterest roi;
  double roi_gain = 8;        // the step inside the region is this many times finer
  // spec 5.7.6: 0, or P (4..24): every array coded in blocks apart, each within
  // a precinct of 2^P samples per axis, so that a box of the grid is decoded
  // from the blocks that reach it (decision D90).
  int precinct_log2 = 0;
};

struct WaveletEncodeReport {
  uint64_t bytes = 0;
  double bits_per_sample = 0;
  double psnr = 0;            // measured by decoding the stream (infinity when exact)
  double max_abs_error = 0;   // measured by decoding the stream
  double sum_squared_error = 0;  // over the valid samples, measured by decoding the stream
  double base_step = 0;       // in normalised units
  uint32_t residual_step = 0; // 0 without a residual layer
  int iterations = 0;         // encodes tried by the rate control
  int levels = 0;             // decomposition levels of the stream (0: the predictive route)
  // The L2 error of the quantised wavelet expansion in function space (finest
  // B-splines, unit knot spacing), exactly through the Gram matrices, and the
  // orthogonal estimate sqrt(sum (e_i ||psi_i||)^2) an orthogonal basis would give.
  double l2_error = 0;
  double l2_error_orthogonal_estimate = 0;
  uint64_t kept_coefficients = 0;  // nonzero quantised coefficients
};

// Encodes a grid with wavelet coding (GHDR coding 1, WHDR, GMSK, GBND..., GRES).
// `samples` as for encodeStoredGrid. The report (may be null) gives what the
// stream achieves, measured with the reference decoder.
Error encodeWaveletGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                        const Metadata& metadata, const WaveletEncodeOptions& options,
                        std::vector<uint8_t>* out, WaveletEncodeReport* report);

// spec: 11.7 (informative) options of tiled grids (GHDR coding 2).
struct TiledEncodeOptions {
  // Samples per tile along x, y, z (axes beyond num_dims take 1).
  uint32_t tile_size[3] = {256, 256, 64};
  // Tiles coded at once; the stream is the same whatever the count.
  int threads = 1;
  // Called after each tile is coded (under a lock, from any thread); a rate or
  // PSNR target codes every tile once per step tried.
  std::function<void(uint64_t done, uint64_t total)> progress;
};

// Encodes a grid as tiles (GHDR coding 2, TINF, TIDX, the tiles' WHDR, GMSK,
// GBND and GRES chunks round by round). Each tile is coded as
// encodeWaveletGrid() codes a grid, with `options`; a rate or PSNR target is
// met for the whole grid with one quantiser step for all tiles, an error
// bound on every sample. Regions of interest are refused.
Error encodeTiledGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                      const Metadata& metadata, const WaveletEncodeOptions& options,
                      const TiledEncodeOptions& tiled, std::vector<uint8_t>* out,
                      WaveletEncodeReport* report);

// encodeTiledGrid() for a grid read a row of tiles at a time from `reader`,
// the coded tiles kept in a temporary file until the stream is written to
// `out`: memory is bounded by a row of tiles, the tiles in flight and the
// index, not by the grid. Lossless, error-bound, step and keep targets only
// (a rate or PSNR target would read the grid once per step tried).
Error encodeTiledGridFromReader(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                                const WaveletEncodeOptions& options, const TiledEncodeOptions& tiled,
                                ByteSink& out, WaveletEncodeReport* report);

// How encodePrecinctGridFromReader() runs: its blocks coded by this many
// threads at once (the stream is the same whatever the count), and its
// progress from 0 to 1.
struct PrecinctStreamOptions {
  int threads = 1;
  std::function<void(double done)> progress;
};

// encodeWaveletGrid() of a grid in precincts (options.precinct_log2 > 0, the
// CDF 9/7 wavelet) read a strip of precincts at a time from `reader` (spec
// 5.9, decision D91): the analysis runs level by level over strips, every
// level's low-pass part and every coded block wait in temporary files, and
// the stream is written to `out`. Memory is bounded by a few strips of the
// grid's width, not by the grid. A step, an error bound (the residual route,
// one base step: D91), lossless, or a rate (the grid read once per step
// tried, the full pyramid only, as with options.progressive); no PSNR
// target, region of interest or keep fraction in this version. Without
// voids, the band chunks are those encodeWaveletGrid() writes at the same
// step (for a rate, with options.progressive); voids are filled within each
// precinct, not over the grid.
Error encodePrecinctGridFromReader(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                                   const WaveletEncodeOptions& options, const PrecinctStreamOptions& run,
                                   ByteSink& out, WaveletEncodeReport* report);

// encodePrecinctGridFromReader() by a team of processes (mrsv-mpi, decision
// D92), each member calling it with its own reader of the same grid: the
// pieces of every level, the boxes of the scan and of the decode pass are
// dealt among the members round-robin, the low-pass parts travel through
// the team's scratch files, and every member writes the blocks it coded
// into `out` (shared), member 0 the rest. The stream (report->bytes long)
// is byte-identical to encodePrecinctGridFromReader()'s whatever the team's
// size and thread counts.
Error encodePrecinctGridAsTeam(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                               const WaveletEncodeOptions& options, const PrecinctStreamOptions& run,
                               EncodeTeam& team, SharedScratch& out, WaveletEncodeReport* report);

}  // namespace mrsv
