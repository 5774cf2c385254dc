// Encoder of wavelet-coded grids (spec 5, informative 5.9): normalisation,
// void filling, analysis, quantisation, entropy coding, rate control and the
// residual layer that makes pointwise error bounds and lossless coding exact.
#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "common/byte_writer.h"
#include "grid/array_encoding.h"
#include "grid/band_quantizer.h"
#include "grid/encoder_setup.h"
#include "grid/oracle.h"
#include "grid/precincts.h"
#include "grid/void_fill.h"
#include "mrsv/encode.h"
#include "wavelet/axis_plan.h"
#include "wavelet/synthesis_fixed.h"
#include "wavelet/transform_float.h"

namespace mrsv {
namespace {

using wavelet::Band;
using wavelet::GridPlan;

bool isFloatType(SampleType t) { return t == SampleType::kFloat32 || t == SampleType::kFloat64; }

Error invalid(std::string field, std::string message) {
  return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
}

class GridEncoder {
 public:
  Error prepare(const GridHeader& header, const std::vector<uint8_t>& samples,
                const WaveletEncodeOptions& options);
  // The stream for base step `delta` (x units); with `residual_step` > 0 a
  // residual layer with that step follows the bands.
  Error encode(double delta, uint32_t residual_step, const Metadata& metadata,
               std::vector<uint8_t>* out);
  // Decodes `stream` with the normative decoder and measures it against the input.
  // `sse`: the sum of squared errors over the valid samples.
  Error measure(const std::vector<uint8_t>& stream, double* psnr, double* max_error, double* sse) const;
  uint64_t validCount() const { return valid_count_; }
  double range() const { return c_max_ - c_min_; }
  bool integerSamples() const { return !isFloatType(header_.sample_type); }
  double unitsPerSample() const { return 1.0 / setup_.scale; }
  double keepThreshold() const { return keep_threshold_; }
  int levels() const { return setup_.plan.maxLevels(); }
  // The exact L2 error of the bands (spec 5.9) and its orthogonal estimate.
  void l2Errors(double delta, WaveletEncodeReport* report) const;

 private:
  void prepareOracles(const WaveletEncodeOptions& options);
  uint64_t quantizeBand(uint16_t index, double delta, std::vector<int64_t>* q) const;
  std::vector<uint8_t> bandChunk(uint16_t index, double delta);
  std::vector<uint8_t> residualChunk(const DecodedGrid& approx, uint32_t residual_step) const;

  GridHeader header_;
  WaveletSetup setup_;  // header, plan, bands, gains, scale
  std::vector<double> coefficients_;  // after analysis, x units
  std::vector<uint8_t> valid_;
  std::vector<double> values_;        // input samples as doubles
  uint64_t valid_count_ = 0;
  double c_min_ = 0, c_max_ = 0;
  std::vector<uint8_t> mask_chunk_;
  WaveletEncodeOptions::Prediction prediction_ = WaveletEncodeOptions::Prediction::kAuto;
  // Oracles.
  double keep_threshold_ = 0;   // importance below which a detail coefficient is dropped
  bool has_roi_ = false;
  double roi_gain_ = 1;
  std::vector<float> weight_;   // region weight of every coefficient (Mallat layout)
};

Error GridEncoder::prepare(const GridHeader& header, const std::vector<uint8_t>& samples,
                           const WaveletEncodeOptions& options) {
  header_ = header;
  header_.coding = GridCoding::kWavelet;
  if (std::string problem = gridHeaderProblem(header_); !problem.empty())
    return invalid("grid_header", problem);
  const size_t n = header_.sampleCount();
  const size_t bytes = sampleSize(header_.sample_type);
  if (samples.size() != n * bytes)
    return invalid("samples", "got " + std::to_string(samples.size()) + " bytes, grid needs " +
                                  std::to_string(n * bytes));
  if (!wavelet::isValidOrder(options.order))
    return invalid("order", "order must be 1 to 4, or 5 for the CDF 9/7 wavelet");

  values_.resize(n);
  valid_.assign(n, 1);
  bool first = true;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = samples.data() + i * bytes;
    if (header_.hasNodata() && std::memcmp(p, &header_.nodata_bits, bytes) == 0) {
      valid_[i] = 0;
      continue;
    }
    double v = sampleValue(p, header_.sample_type);
    if (!std::isfinite(v))
      return invalid("samples", "sample " + std::to_string(i) +
                                    " is NaN or infinite; mark such samples with --nodata");
    values_[i] = v;
    c_min_ = first ? v : std::min(c_min_, v);
    c_max_ = first ? v : std::max(c_max_, v);
    first = false;
    ++valid_count_;
  }
  WaveletSetup setup;
  if (Error e = makeWaveletSetup(header_, c_min_, c_max_, options, &setup); !e.ok()) return e;
  setup_ = std::move(setup);
  prediction_ = options.prediction;  // encodeCoarsestBand() keeps to what the entropy mode allows
  const uint32_t size[3] = {header_.size_x, header_.size_y, header_.size_z};

  // Normalised values, voids filled, then padded by repeating the last sample
  // of every axis (constants cost no detail coefficients).
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = valid_[i] ? (values_[i] - c_min_) / setup_.scale : 0.0;
  if (valid_count_ < n) fillVoidsPullPush(&x, valid_, size);
  analyzeSamples(setup_.plan, size, x, &coefficients_);

  if (valid_count_ < n)
    refineVoidFill(setup_.plan, size, setup_.bands, setup_.band_gain, valid_, (c_max_ - c_min_) / setup_.scale, &x, &coefficients_);
  prepareOracles(options);

  if (valid_count_ < n) {
    setup_.header.wavelet_flags |= kWaveletFlagHasMask;
    ArrayBox box;
    box.num_dims = header_.num_dims;
    std::copy(size, size + 3, box.size);
    std::vector<int64_t> mask(n);
    for (size_t i = 0; i < n; ++i) mask[i] = valid_[i] ? 0 : 1;
    const int full_resolution[3] = {0, 0, 0};
    encodeBlockedArray(setup_.header, mask.data(), box, full_resolution, ArrayPrediction::kNone, nullptr,
                       nullptr, &mask_chunk_);
  }
  return {};
}

// Region weights of every coefficient (local oracle) and the importance
// threshold of the global oracle (keep a fraction of the coefficients).
void GridEncoder::prepareOracles(const WaveletEncodeOptions& options) {
  const uint64_t px = setup_.plan.axis[0].size(0), pxy = px * setup_.plan.axis[1].size(0);
  if (options.has_roi) {
    has_roi_ = true;
    roi_gain_ = std::max(1.0, options.roi_gain);
    weight_.assign(coefficients_.size(), 1.0f);
    std::vector<AxisSupports> supports;
    for (int a = 0; a < 3; ++a) supports.emplace_back(setup_.plan.axis[a]);
    for (const Band& b : setup_.bands) {
      for (uint32_t z = 0; z < b.size[2]; ++z)
        for (uint32_t y = 0; y < b.size[1]; ++y)
          for (uint32_t x = 0; x < b.size[0]; ++x) {
            const uint32_t pos[3] = {x, y, z};
            uint32_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
            for (int a = 0; a < setup_.plan.num_dims; ++a) {
              const wavelet::AxisPlan& ax = setup_.plan.axis[a];
              if ((b.mask >> a) & 1) supports[static_cast<size_t>(a)].wavelet(b.level, pos[a], &lo[a], &hi[a]);
              else supports[static_cast<size_t>(a)].scaling(
                       b.mask == 0 ? ax.levels : std::min(b.level, ax.levels), pos[a], &lo[a], &hi[a]);
            }
            weight_[(b.offset[0] + x) + (b.offset[1] + y) * px + (b.offset[2] + z) * pxy] =
                static_cast<float>(regionWeight(options.roi, setup_.plan.num_dims, lo, hi));
          }
    }
  }
  if (options.keep_fraction > 0) {
    // Importance: the coefficient's contribution to the sample-domain L2 norm
    // (|c| times its band's gain), weighted by the region when there is one.
    std::vector<double> importance;
    uint64_t coarsest = 0;
    for (size_t bi = 0; bi < setup_.bands.size(); ++bi) {
      const Band& b = setup_.bands[bi];
      if (b.mask == 0) {
        coarsest = uint64_t{b.size[0]} * b.size[1] * b.size[2];
        continue;
      }
      for (uint32_t z = 0; z < b.size[2]; ++z)
        for (uint32_t y = 0; y < b.size[1]; ++y)
          for (uint32_t x = 0; x < b.size[0]; ++x) {
            size_t at = (b.offset[0] + x) + (b.offset[1] + y) * px + (b.offset[2] + z) * pxy;
            importance.push_back(std::fabs(coefficients_[at]) * setup_.band_gain[bi] *
                                 (has_roi_ ? weight_[at] : 1.0));
          }
    }
    double wanted = std::ceil(options.keep_fraction * static_cast<double>(coefficients_.size()));
    uint64_t keep = wanted > static_cast<double>(coarsest) ? static_cast<uint64_t>(wanted) - coarsest : 0;
    if (keep == 0 || importance.empty()) {
      keep_threshold_ = std::numeric_limits<double>::max();
    } else if (keep >= importance.size()) {
      keep_threshold_ = std::numeric_limits<double>::min();
    } else {
      std::nth_element(importance.begin(), importance.begin() + static_cast<long>(keep - 1),
                       importance.end(), std::greater<double>());
      keep_threshold_ = std::max(importance[keep - 1], std::numeric_limits<double>::min());
    }
  }
}

// Quantises band `index` for base step `delta` (x units, sample-domain
// normalised by the band gain): returns the fixed-point step (0 for a band that
// quantises to zeros) and the integers in band order. The oracles act here:
// a coefficient below the keep threshold, or outside the region of interest
// and weighted below the dead zone, is dropped (paper 2.2). With precincts
// every block is quantised apart (band_quantizer.h).
uint64_t GridEncoder::quantizeBand(uint16_t index, double delta, std::vector<int64_t>* q) const {
  const Band& band = setup_.bands[index];
  const bool coarsest = band.mask == 0;
  const bool oracles = !coarsest && (keep_threshold_ > 0 || has_roi_);
  // Inside a region of interest the step is roi_gain times finer.
  const BandQuantizer quantizer =
      bandQuantizer(setup_, index, delta, integerSamples(), has_roi_ ? roi_gain_ : 1.0, oracles);
  const ArrayBox box{{band.size[0], band.size[1], band.size[2]}, setup_.plan.num_dims};
  q->assign(box.count(), 0);
  const uint64_t px = setup_.plan.axis[0].size(0), pxy = px * setup_.plan.axis[1].size(0);
  std::vector<double> c(box.count());
  for (uint32_t z = 0, k = 0; z < band.size[2]; ++z)
    for (uint32_t y = 0; y < band.size[1]; ++y, k += band.size[0]) {
      const size_t at = band.offset[0] + (band.offset[1] + y) * px + (band.offset[2] + z) * pxy;
      std::copy(coefficients_.data() + at, coefficients_.data() + at + band.size[0], c.data() + k);
    }
  bool any = false;
  if (oracles) {
    const double gain = setup_.band_gain[index];
    size_t k = 0;
    for (uint32_t z = 0; z < band.size[2]; ++z)
      for (uint32_t y = 0; y < band.size[1]; ++y) {
        const size_t at = band.offset[0] + (band.offset[1] + y) * px + (band.offset[2] + z) * pxy;
        for (uint32_t x = 0; x < band.size[0]; ++x, ++k) {
          const double w = has_roi_ ? weight_[at + x] : 1.0;
          const double importance = std::fabs(c[k]) * gain * w;
          const bool touches_roi = has_roi_ && w >= 1.0;  // support-aware: never dropped
          if (!touches_roi && importance < (keep_threshold_ > 0 ? keep_threshold_ : 0.6 * delta)) c[k] = 0;
        }
      }
  }
  const int axis_levels[3] = {setup_.header.levels[0], setup_.header.levels[1], setup_.header.levels[2]};
  int resolution[3];
  bandResolution(band.level, axis_levels, resolution);
  any = quantizeBlocked(quantizer, c.data(), box, resolution, setup_.header.precinct_log2, q->data());
  return any ? quantizer.step : 0;
}

std::vector<uint8_t> GridEncoder::bandChunk(uint16_t index, double delta) {
  const Band& band = setup_.bands[index];
  const bool coarsest = band.mask == 0;
  std::vector<int64_t> q;
  uint64_t step = quantizeBand(index, delta, &q);
  std::vector<uint8_t> payload = bandChunkHead(index, step);
  if (!step) return payload;
  ArrayBox box;
  box.num_dims = setup_.plan.num_dims;
  for (int a = 0; a < 3; ++a) box.size[a] = band.size[a];
  const int axis_levels[3] = {setup_.header.levels[0], setup_.header.levels[1], setup_.header.levels[2]};
  int resolution[3];
  bandResolution(band.level, axis_levels, resolution);
  if (!coarsest) {
    encodeBlockedArray(setup_.header, q.data(), box, resolution, ArrayPrediction::kNone, nullptr, nullptr,
                       &payload);
    return payload;
  }
  // The coarsest block is coded with neighbour prediction and, with range
  // coding, also with weighted prediction; the smaller one is kept (5.9).
  const bool samples = box.count() == valid_.size() && valid_count_ < valid_.size();
  std::vector<uint8_t> coded;
  payload[2] = encodeCoarsestBand(setup_.header, q, box, resolution, prediction_, samples ? valid_.data() : nullptr,
                                  &coded);
  payload.insert(payload.end(), coded.begin(), coded.end());
  return payload;
}

void GridEncoder::l2Errors(double delta, WaveletEncodeReport* report) const {
  // e = c - dequantised c, in sample units (x units times scale).
  std::vector<double> e(coefficients_.size(), 0.0);
  const double units = std::ldexp(1.0, setup_.header.frac_bits);
  const uint64_t px = setup_.plan.axis[0].size(0), pxy = px * setup_.plan.axis[1].size(0);
  std::vector<double> norms[3];
  for (int a = 0; a < 3; ++a) norms[a] = wavelet::axisBasisNorms(setup_.plan.axis[a]);
  double estimate = 0;
  uint64_t kept = 0;
  std::vector<int64_t> q;
  for (size_t b = 0; b < setup_.bands.size(); ++b) {
    const Band& band = setup_.bands[b];
    uint64_t step = quantizeBand(static_cast<uint16_t>(b), delta, &q);
    size_t k = 0;
    for (uint32_t z = 0; z < band.size[2]; ++z)
      for (uint32_t y = 0; y < band.size[1]; ++y)
        for (uint32_t x = 0; x < band.size[0]; ++x, ++k) {
          const uint32_t pos[3] = {band.offset[0] + x, band.offset[1] + y, band.offset[2] + z};
          const size_t at = pos[0] + pos[1] * px + pos[2] * pxy;
          double d = (coefficients_[at] - static_cast<double>(q[k]) * static_cast<double>(step) / units) * setup_.scale;
          e[at] = d;
          kept += q[k] != 0;
          double n = norms[0][pos[0]] * norms[1][pos[1]] * norms[2][pos[2]];
          estimate += d * d * n * n;
        }
  }
  report->l2_error = std::sqrt(functionSpaceNormSquared(setup_.plan, setup_.bands, e));
  report->l2_error_orthogonal_estimate = std::sqrt(estimate);
  report->kept_coefficients = kept;
}

Error GridEncoder::encode(double delta, uint32_t residual_step, const Metadata& metadata,
                          std::vector<uint8_t>* out) {
  WaveletHeader wh = setup_.header;
  if (residual_step) wh.wavelet_flags |= kWaveletFlagHasResidual;
  ContainerWriter writer;
  writer.addChunk(kChunkGridHeader, serializeGridHeader(header_));
  if (!metadata.entries.empty()) writer.addChunk(kChunkMeta, serializeMetadata(metadata));
  writer.addChunk(kChunkWaveletHeader, serializeWaveletHeader(wh));
  if (wh.hasMask()) writer.addChunk(kChunkNodataMask, mask_chunk_);
  for (size_t b = 0; b < setup_.bands.size(); ++b)
    writer.addChunk(kChunkBand, bandChunk(static_cast<uint16_t>(b), delta));
  if (residual_step) {
    // The residual is taken against what the normative decoder makes of the
    // bands (the stream so far, a prefix), so the bound holds exactly.
    const std::vector<uint8_t>& prefix = writer.image();
    DecodedGrid approx;
    if (Error e = decodeGrid(prefix.data(), prefix.size(), DecodeOptions{}, &approx); !e.ok())
      return e;
    writer.addChunk(kChunkResidual, residualChunk(approx, residual_step));
  }
  *out = writer.finish();
  return {};
}

std::vector<uint8_t> GridEncoder::residualChunk(const DecodedGrid& approx,
                                                uint32_t residual_step) const {
  const size_t n = header_.sampleCount(), bytes = sampleSize(header_.sample_type);
  ArrayBox box;
  box.num_dims = header_.num_dims;
  box.size[0] = header_.size_x;
  box.size[1] = header_.size_y;
  box.size[2] = header_.size_z;
  std::vector<int64_t> r(n, 0);
  std::vector<uint8_t> skip(n);
  const int64_t s = residual_step;
  for (size_t i = 0; i < n; ++i) {
    skip[i] = valid_[i] ? 0 : 1;
    if (!valid_[i]) continue;
    int64_t decoded =
        static_cast<int64_t>(sampleValue(approx.samples.data() + i * bytes, header_.sample_type));
    int64_t e = static_cast<int64_t>(values_[i]) - decoded;
    // The nearest multiple of the odd step s: |e - r*s| <= (s-1)/2.
    r[i] = e >= 0 ? (e + s / 2) / s : -((-e + s / 2) / s);
  }
  std::vector<uint8_t> payload;
  ByteWriter w(&payload);
  w.u32(residual_step);
  const int full_resolution[3] = {0, 0, 0};
  encodeBlockedArray(setup_.header, r.data(), box, full_resolution, ArrayPrediction::kNone, skip.data(),
                     nullptr, &payload);
  return payload;
}

Error GridEncoder::measure(const std::vector<uint8_t>& stream, double* psnr, double* max_error,
                          double* sse_out) const {
  DecodedGrid g;
  if (Error e = decodeGrid(stream.data(), stream.size(), DecodeOptions{}, &g); !e.ok()) return e;
  const size_t bytes = sampleSize(header_.sample_type);
  double sse = 0, worst = 0;
  for (size_t i = 0; i < values_.size(); ++i) {
    const uint8_t* p = g.samples.data() + i * bytes;
    if (!valid_[i]) {
      if (std::memcmp(p, &header_.nodata_bits, bytes) != 0)
        return Error{Status::kInvalidArgument, 0, "verify", "a void did not come back as no-data"};
      continue;
    }
    double d = std::fabs(sampleValue(p, header_.sample_type) - values_[i]);
    sse += d * d;
    worst = std::max(worst, d);
  }
  double mse = valid_count_ ? sse / static_cast<double>(valid_count_) : 0;
  double r = c_max_ - c_min_;
  *psnr = mse > 0 ? 10 * std::log10(r * r / mse) : std::numeric_limits<double>::infinity();
  *max_error = worst;
  *sse_out = sse;
  return {};
}

// Rewrites `stream` with `metadata` as its meta chunk, right after GHDR.
Error replaceMetadata(const Metadata& metadata, std::vector<uint8_t>* stream) {
  Container c;
  if (Error e = readContainer(stream->data(), stream->size(), ContainerOptions{}, &c); !e.ok())
    return e;
  ContainerWriter writer;
  for (size_t i = 0; i < c.chunks.size(); ++i) {
    const ChunkView& chunk = c.chunks[i];
    if (chunk.chunk_type == kChunkMeta) continue;
    writer.addChunk(chunk.chunk_type,
                    std::vector<uint8_t>(chunk.payload, chunk.payload + chunk.chunk_length));
    if (i == 0 && !metadata.entries.empty()) writer.addChunk(kChunkMeta, serializeMetadata(metadata));
  }
  *stream = writer.finish();
  return {};
}

}  // namespace

Error encodeWaveletGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                        const Metadata& metadata, const WaveletEncodeOptions& options,
                        std::vector<uint8_t>* out, WaveletEncodeReport* report) {
  GridEncoder wavelet_enc, predictive_enc;
  GridEncoder* used = &wavelet_enc;
  if (Error e = wavelet_enc.prepare(header, samples, options); !e.ok()) return e;
  WaveletEncodeReport rep;
  const double n = static_cast<double>(header.sampleCount());
  // What decoding a stream measured (GridEncoder::measure).
  struct Measured {
    double psnr = 0, max_error = 0, sse = 0;
  };
  // `known`: the measure of `stream` when the caller has it already.
  auto finish = [&](std::vector<uint8_t>&& stream, double delta, uint32_t residual_step,
                    const std::optional<Measured>& known = std::nullopt) -> Error {
    GridEncoder& enc = *used;
    if (known) {
      rep.psnr = known->psnr;
      rep.max_abs_error = known->max_error;
      rep.sum_squared_error = known->sse;
    } else if (Error e = enc.measure(stream, &rep.psnr, &rep.max_abs_error, &rep.sum_squared_error); !e.ok()) {
      return e;
    }
    // Record the figures in the meta chunk (spec 2.6 error_* keys): the chunk
    // is replaced, the coded chunks stay as they are.
    Metadata recorded = metadata;
    auto text = [](double v) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", v);
      return std::string(buf);
    };
    if (options.max_error >= 0) recorded.set("error_bound", text(std::floor(options.max_error)));
    recorded.set("error_max_abs", text(rep.max_abs_error));
    recorded.set("error_psnr_db", std::isinf(rep.psnr) ? "inf" : text(rep.psnr));
    recorded.set("error_rmse", text(enc.range() / std::pow(10.0, rep.psnr / 20)));
    if (Error e = replaceMetadata(recorded, &stream); !e.ok()) return e;
    rep.bytes = stream.size();
    rep.bits_per_sample = 8.0 * static_cast<double>(stream.size()) / n;
    enc.l2Errors(delta, &rep);
    rep.base_step = delta;
    rep.residual_step = residual_step;
    rep.levels = enc.levels();
    *out = std::move(stream);
    if (report) *report = rep;
    return {};
  };

  if (options.max_error >= 0) {
    if (!wavelet_enc.integerSamples())
      return invalid("max_error", "error bounds and lossless coding need integer samples in this version");
    uint32_t d = static_cast<uint32_t>(std::floor(options.max_error));
    if (d > (kMaxResidualStep - 1) / 2) return invalid("max_error", "bound above 524287");
    uint32_t residual_step = 2 * d + 1;
    std::vector<uint8_t> best, stream;
    double best_delta = 0;
    uint32_t best_residual = 0;
    // Route 1: wavelet bands plus a residual layer; a few wavelet steps around
    // the residual step, keeping the smallest stream.
    const bool try_residual = options.bound_route != WaveletEncodeOptions::BoundRoute::kPredictive;
    const bool try_predictive =
        options.bound_route != WaveletEncodeOptions::BoundRoute::kResidual && !options.progressive;
    for (int k = -1; try_residual && k <= 7; ++k) {
      double delta = std::ldexp(static_cast<double>(residual_step), k);
      if (Error e = wavelet_enc.encode(delta, residual_step, metadata, &stream); !e.ok()) return e;
      ++rep.iterations;
      if (best.empty() || stream.size() < best.size()) {
        best.swap(stream);
        best_delta = delta;
        best_residual = residual_step;
      }
    }
    // Route 2: no decomposition (levels 0): the samples themselves, quantised
    // with step 2d+1 (which alone keeps every error within d) and coded with
    // neighbour prediction; or quantised coarser, with a residual layer, which
    // splits sparse data (CT air, angiograms) into two cheap layers. On noisy or
    // piecewise-flat data this beats route 1.
    WaveletEncodeOptions flat = options;
    flat.max_levels = 0;
    if (try_predictive) {
      if (Error e = predictive_enc.prepare(header, samples, flat); !e.ok()) return e;
      for (int k = 0; k <= 7; ++k) {
        double delta = std::ldexp(static_cast<double>(residual_step), k);
        uint32_t with_residual = k == 0 ? 0 : residual_step;
        if (Error e = predictive_enc.encode(delta, with_residual, metadata, &stream); !e.ok()) return e;
        ++rep.iterations;
        if (best.empty() || stream.size() < best.size()) {
          best.swap(stream);
          best_delta = delta;
          best_residual = with_residual;
          used = &predictive_enc;
        }
      }
    }
    if (Error e = finish(std::move(best), best_delta, best_residual); !e.ok()) return e;
    if (rep.max_abs_error > d)
      return Error{Status::kInvalidArgument, 0, "verify",
                   "internal error: decoded error " + std::to_string(rep.max_abs_error) +
                       " above the bound " + std::to_string(d)};
    return {};
  }
  GridEncoder& enc = wavelet_enc;

  // Lossy: find the base step by bisection on its logarithm.
  const double r = std::max(enc.range(), 1e-300) * enc.unitsPerSample();
  std::vector<uint8_t> stream, best;
  double best_delta = 0;
  std::optional<Measured> best_measured;  // of `best`, set by search()
  if (options.keep_fraction > 0) {
    // Global oracle: the base step is the importance threshold, so that every
    // kept coefficient quantises to at least 1 and every dropped one to 0.
    double delta = std::min(enc.keepThreshold(), 1e300);
    if (Error e = enc.encode(delta, 0, metadata, &stream); !e.ok()) return e;
    rep.iterations = 1;
    return finish(std::move(stream), delta, 0);
  }
  if (options.step > 0) {
    double delta = options.step * enc.unitsPerSample();
    if (Error e = enc.encode(delta, 0, metadata, &stream); !e.ok()) return e;
    rep.iterations = 1;
    return finish(std::move(stream), delta, 0);
  }
  const bool by_rate = options.bits_per_sample > 0;
  if (!by_rate && !(options.psnr > 0))
    return invalid("options", "give a step, a rate, a PSNR, an error bound or lossless");
  // The recorded error figures are added after the rate control: their largest
  // possible size is reserved from the budget.
  Metadata probe = metadata;
  for (const char* key : {"error_max_abs", "error_psnr_db", "error_rmse"}) probe.set(key, "-1.23457e+300");
  const double reserve = static_cast<double>(serializeMetadata(probe).size() -
                                             serializeMetadata(metadata).size()) +
                         (metadata.entries.empty() ? kChunkHeaderSize + kChunkCrcSize : 0);
  const double target_bytes = options.bits_per_sample * n / 8.0 - reserve;
  // The step search on one encoder: for a rate the smallest step that fits,
  // for a PSNR the largest that reaches it, with its measure; `found` is left
  // empty when no step does.
  auto search = [&](GridEncoder& e, std::vector<uint8_t>* found, double* found_delta,
                    std::optional<Measured>* found_measured) -> Error {
    double lo = std::log2(r) - 30, hi = std::log2(r) + 2;  // log2 of the step in x units
    found->clear();
    for (int it = 0; it < 40 && hi - lo > 1e-3; ++it) {
      double mid = 0.5 * (lo + hi), delta = std::exp2(mid);
      if (Error err = e.encode(delta, 0, metadata, &stream); !err.ok()) return err;
      ++rep.iterations;
      bool meets;
      Measured m;
      if (by_rate) {
        meets = static_cast<double>(stream.size()) <= target_bytes;
      } else {
        if (Error err = e.measure(stream, &m.psnr, &m.max_error, &m.sse); !err.ok()) return err;
        meets = m.psnr >= options.psnr;
      }
      // A larger step gives a smaller stream and a lower PSNR.
      if (meets) {
        found->swap(stream);
        *found_delta = delta;
        if (!by_rate) *found_measured = m;
        (by_rate ? hi : lo) = mid;
        if (by_rate && static_cast<double>(found->size()) >= 0.999 * target_bytes) break;
      } else {
        (by_rate ? lo : hi) = mid;
      }
    }
    if (!found->empty() && !*found_measured) {
      found_measured->emplace();
      if (Error err = e.measure(*found, &(*found_measured)->psnr, &(*found_measured)->max_error,
                                &(*found_measured)->sse); !err.ok())
        return err;
    }
    return {};
  };
  if (Error e = search(enc, &best, &best_delta, &best_measured); !e.ok()) return e;
  // Fewer levels as further candidates (decision D28): with the weighted
  // prediction of the coarsest block, 1 or 2 levels often beat the full
  // pyramid. `--progressive` and the local oracle keep the full pyramid.
  std::unique_ptr<GridEncoder> fewer_best;
  if (!options.progressive && !options.has_roi) {
    for (int levels : {2, 1}) {
      if (levels >= enc.levels()) continue;
      WaveletEncodeOptions fewer = options;
      fewer.max_levels = levels;
      auto candidate = std::make_unique<GridEncoder>();
      if (Error e = candidate->prepare(header, samples, fewer); !e.ok()) return e;
      std::vector<uint8_t> found;
      double found_delta = 0;
      std::optional<Measured> found_measured;
      if (Error e = search(*candidate, &found, &found_delta, &found_measured); !e.ok()) return e;
      if (found.empty()) continue;
      const bool better = best.empty() || (by_rate ? found_measured->psnr > best_measured->psnr
                                                   : found.size() < best.size());
      if (!better) continue;
      best.swap(found);
      best_delta = found_delta;
      best_measured = found_measured;
      fewer_best = std::move(candidate);
      used = fewer_best.get();
    }
  }
  if (best.empty()) {
    return invalid(by_rate ? "bits_per_sample" : "psnr",
                   by_rate ? "the rate is too low for even the coarsest approximation"
                           : "the PSNR target cannot be met");
  }
  if (!enc.integerSamples() || options.progressive || options.has_roi)
    return finish(std::move(best), best_delta, 0, best_measured);

  // The predictive route as a second candidate (informative 5.9 item 6): no
  // decomposition, the samples quantised with step 2d+1 and neighbour
  // prediction, so every error is within d. At high rates on noisy or sparse
  // data it beats the wavelets, and when the lossless stream fits (d = 0) it is
  // exact. Its error is close to uniform on -d..d, MSE d(d+1)/3, which bounds
  // the d worth trying.
  const double wavelet_psnr = best_measured->psnr;
  WaveletEncodeOptions flat = options;
  flat.max_levels = 0;
  if (Error e = predictive_enc.prepare(header, samples, flat); !e.ok()) return e;
  const double range_sq = enc.range() * enc.range();
  auto largestBound = [&](double mse) {  // the largest d with d(d+1)/3 <= mse
    double d = std::floor((std::sqrt(1 + 12 * mse) - 1) / 2);
    return static_cast<uint32_t>(std::clamp(d, 0.0, double{(kMaxResidualStep - 1) / 2}));
  };
  auto predictiveAt = [&](uint32_t d, std::vector<uint8_t>* s) {
    ++rep.iterations;
    return predictive_enc.encode(static_cast<double>(2 * d + 1), 0, metadata, s);
  };
  std::vector<uint8_t> candidate;
  uint32_t candidate_d = 0;
  Measured candidate_measured;
  if (by_rate) {
    // The smallest d that fits, searched below the d whose uniform-error MSE
    // is twice the wavelet stream's (beyond it the wavelets surely win).
    const double wavelet_mse = std::isinf(wavelet_psnr) ? 0 : range_sq / std::pow(10.0, wavelet_psnr / 10);
    uint32_t fits = largestBound(2 * wavelet_mse);
    if (Error e = predictiveAt(fits, &stream); !e.ok()) return e;
    if (static_cast<double>(stream.size()) <= target_bytes) {
      candidate.swap(stream);
      candidate_d = fits;
      int64_t fails = -1;  // the largest d known not to fit
      while (static_cast<int64_t>(candidate_d) - fails > 1 &&
             static_cast<double>(candidate.size()) < 0.98 * target_bytes) {
        uint32_t mid = static_cast<uint32_t>((fails + static_cast<int64_t>(candidate_d)) / 2);
        if (Error e = predictiveAt(mid, &stream); !e.ok()) return e;
        if (static_cast<double>(stream.size()) <= target_bytes) {
          candidate.swap(stream);
          candidate_d = mid;
        } else {
          fails = mid;
        }
      }
      Measured& m = candidate_measured;
      if (Error e = predictive_enc.measure(candidate, &m.psnr, &m.max_error, &m.sse); !e.ok()) return e;
      // Kept when better, or as good (both exact) and smaller.
      if (!(m.psnr > wavelet_psnr || (m.psnr == wavelet_psnr && candidate.size() < best.size())))
        candidate.clear();
    }
  } else {
    // The largest d that reaches the PSNR, from the uniform-error estimate
    // down by halving (d = 0 is exact and always reaches it).
    uint32_t d = largestBound(range_sq / std::pow(10.0, options.psnr / 10));
    Measured& m = candidate_measured;
    while (true) {
      if (Error e = predictiveAt(d, &stream); !e.ok()) return e;
      if (Error e = predictive_enc.measure(stream, &m.psnr, &m.max_error, &m.sse); !e.ok()) return e;
      if (m.psnr >= options.psnr || d == 0) break;
      d /= 2;
    }
    if (stream.size() < best.size()) {
      candidate.swap(stream);
      candidate_d = d;
    }
  }
  if (candidate.empty()) return finish(std::move(best), best_delta, 0, best_measured);
  used = &predictive_enc;
  return finish(std::move(candidate), static_cast<double>(2 * candidate_d + 1), 0, candidate_measured);
}

}  // namespace mrsv
