// gdal_translate -of MRSV (issue 25): the driver's CreateCopy. The raster
// becomes a grid through the same code as `mrsv encode IN.tif` (readGdalDataset,
// decision D73), and the creation options are mrsv encode's options under
// GDAL's names, with its rules and defaults: the same raster and options give
// the same bytes (gdal_cli_test.py compares them).
#include <cpl_string.h>
#include <cpl_vsi.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "io/gdal_dataset.h"
#include "mrsv/encode.h"
#include "mrsv/file_io.h"
#include "mrsv_driver.h"

const char kMrsvCreationOptionList[] =
    "<CreationOptionList>"
    "<Option name='CODING' type='string-select' default='WAVELET' description='wavelet: wavelet "
    "coding; stored: the samples as they are'><Value>WAVELET</Value><Value>STORED</Value></Option>"
    "<Option name='LOSSLESS' type='boolean' description='every sample exact (integer samples; the "
    "default when no other target is given)'/>"
    "<Option name='MAX_ERROR' type='float' min='0' max='524287' description='every sample within "
    "this of the input, in sample units (integer samples)'/>"
    "<Option name='RATE' type='float' min='0.001' max='64' description='the best quality within "
    "this many bits per sample'/>"
    "<Option name='PSNR' type='float' min='1' max='400' description='the smallest stream with at "
    "least this PSNR in dB (peak: max - min of the valid samples)'/>"
    "<Option name='STEP' type='float' description='quantiser step in sample units (no rate control)'/>"
    "<Option name='KEEP' type='float' min='0' max='1' description='keep this fraction of the "
    "coefficients that contribute most to the L2 norm'/>"
    "<Option name='WAVELET' type='string-select' default='CDF97' description='cdf97: the CDF 9/7 "
    "wavelet of JPEG 2000; bspline: the B-spline wavelets'><Value>CDF97</Value><Value>BSPLINE</Value></Option>"
    "<Option name='ORDER' type='int' min='1' max='4' default='2' description='B-spline order: 1 Haar, "
    "2 linear, 3 quadratic, 4 cubic (implies WAVELET=BSPLINE)'/>"
    "<Option name='LEVELS' type='int' min='0' max='16' default='16' description='at most this many "
    "decomposition levels per axis (the overviews)'/>"
    "<Option name='PROGRESSIVE' type='boolean' default='NO' description='the most levels LEVELS "
    "allows: every prefix of the file a coarser approximation'/>"
    "<Option name='ENTROPY' type='string-select' default='ADAPTIVE' description='adaptive range "
    "coding or the baseline Huffman coder'><Value>ADAPTIVE</Value><Value>BASELINE</Value></Option>"
    "<Option name='BOUND_ROUTE' type='string-select' default='AUTO' description='how LOSSLESS and "
    "MAX_ERROR are met: wavelet bands and a residual, neighbour prediction (not progressive), or "
    "the smaller'><Value>AUTO</Value><Value>RESIDUAL</Value><Value>PREDICTIVE</Value></Option>"
    "<Option name='PREDICTION' type='string-select' default='AUTO' description='prediction of the "
    "coarsest block'><Value>AUTO</Value><Value>NEIGHBOUR</Value><Value>WEIGHTED</Value></Option>"
    "<Option name='PRECINCT' type='int' description='every band in blocks of this many samples "
    "per side (a power of two, 16 to 2^24; spec 5.7.6), so that a window is read from the blocks "
    "that reach it'/>"
    "</CreationOptionList>";

namespace {

// The creation options as mrsv encode's options; false after a CPLError
// that names the option and the rule it breaks.
class CreationOptions {
 public:
  CreationOptions(const char* filename, char** options) : filename_(filename), options_(options) {}

  bool parse(bool* stored, mrsv::WaveletEncodeOptions* out) {
    mrsv::WaveletEncodeOptions& w = *out;
    const char* coding = value("CODING");
    if (coding && !EQUAL(coding, "WAVELET") && !EQUAL(coding, "STORED"))
      return fail("CODING", "must be WAVELET or STORED");
    *stored = coding && EQUAL(coding, "STORED");
    // One rate or quality target at most; lossless without one.
    int targets = 0;
    const char* lossless = value("LOSSLESS");
    if (!number("MAX_ERROR", 0, 524287, &w.max_error, &targets) ||
        !number("RATE", 1e-3, 64, &w.bits_per_sample, &targets) ||
        !number("PSNR", 1, 400, &w.psnr, &targets) || !number("STEP", 1e-12, 1e300, &w.step, &targets) ||
        !number("KEEP", 1e-9, 1, &w.keep_fraction, &targets))
      return false;
    if (lossless && CPLTestBool(lossless)) {
      w.max_error = 0;
      ++targets;
    }
    if (targets > 1) {
      std::string given;
      for (const char* name : {"LOSSLESS", "MAX_ERROR", "RATE", "PSNR", "STEP", "KEEP"})
        if (value(name)) given += std::string(given.empty() ? "" : ", ") + name;
      CPLError(CE_Failure, CPLE_IllegalArg,
               "%s: creation options %s: give at most one of LOSSLESS, MAX_ERROR, RATE, PSNR, STEP, KEEP",
               filename_, given.c_str());
      return false;
    }
    if (lossless && !CPLTestBool(lossless) && targets == 0)
      return fail("LOSSLESS", "NO needs one of MAX_ERROR, RATE, PSNR, STEP, KEEP");
    if (targets == 0) w.max_error = 0;
    int ignored = 0;
    double order = 2, levels = 16;
    if (!number("ORDER", 1, 4, &order, &ignored) || !number("LEVELS", 0, 16, &levels, &ignored)) return false;
    if (order != std::floor(order)) return fail("ORDER", "takes a whole number");
    if (levels != std::floor(levels)) return fail("LEVELS", "takes a whole number");
    if (const char* e = value("ENTROPY")) {
      if (EQUAL(e, "BASELINE")) w.entropy_mode = mrsv::kEntropyBaseline;
      else if (!EQUAL(e, "ADAPTIVE")) return fail("ENTROPY", "must be ADAPTIVE or BASELINE");
    }
    using Prediction = mrsv::WaveletEncodeOptions::Prediction;
    if (const char* p = value("PREDICTION")) {
      if (EQUAL(p, "NEIGHBOUR")) w.prediction = Prediction::kNeighbour;
      else if (EQUAL(p, "WEIGHTED")) w.prediction = Prediction::kWeighted;
      else if (!EQUAL(p, "AUTO")) return fail("PREDICTION", "must be AUTO, NEIGHBOUR or WEIGHTED");
      if (w.prediction == Prediction::kWeighted && w.entropy_mode == mrsv::kEntropyBaseline)
        return fail("PREDICTION", "WEIGHTED needs ENTROPY=ADAPTIVE");
    }
    const char* progressive = value("PROGRESSIVE");
    w.progressive = progressive && CPLTestBool(progressive);
    using Route = mrsv::WaveletEncodeOptions::BoundRoute;
    if (const char* r = value("BOUND_ROUTE")) {
      if (EQUAL(r, "RESIDUAL")) w.bound_route = Route::kResidual;
      else if (EQUAL(r, "PREDICTIVE")) w.bound_route = Route::kPredictive;
      else if (!EQUAL(r, "AUTO")) return fail("BOUND_ROUTE", "must be AUTO, RESIDUAL or PREDICTIVE");
      if (w.max_error < 0) return fail("BOUND_ROUTE", "goes with LOSSLESS or MAX_ERROR");
      if (w.bound_route == Route::kPredictive && w.progressive)
        return fail("BOUND_ROUTE", "PREDICTIVE is not progressive; drop it or PROGRESSIVE");
    }
    // CDF 9/7 unless B-splines are asked for, by name or by order.
    const char* family = value("WAVELET");
    if (family && !EQUAL(family, "CDF97") && !EQUAL(family, "BSPLINE"))
      return fail("WAVELET", "must be CDF97 or BSPLINE");
    if (family ? EQUAL(family, "BSPLINE") : value("ORDER") != nullptr) {
      w.order = static_cast<int>(order);
    } else {
      if (value("ORDER")) return fail("ORDER", "is for WAVELET=BSPLINE");
      w.order = mrsv::kWaveletOrderCdf97;
    }
    w.max_levels = static_cast<int>(levels);
    if (const char* p = value("PRECINCT")) {
      for (int k = mrsv::kMinPrecinctLog2; k <= mrsv::kMaxPrecinctLog2; ++k)
        if (std::string(p) == std::to_string(1u << k)) w.precinct_log2 = k;
      if (w.precinct_log2 == 0) return fail("PRECINCT", "must be a power of two from 16 to 16777216");
    }
    if (*stored) {
      for (const char* name : {"ORDER", "LEVELS", "MAX_ERROR", "RATE", "PSNR", "STEP", "PRECINCT"})
        if (value(name)) return fail(name, "CODING=STORED takes no rate, quality or wavelet option");
    }
    return true;
  }

 private:
  const char* value(const char* name) const { return CSLFetchNameValue(options_, name); }

  bool fail(const char* name, const std::string& rule) const {
    const char* v = value(name);
    CPLError(CE_Failure, CPLE_IllegalArg, "%s: creation option %s%s%s: %s", filename_, name, v ? "=" : "",
             v ? v : "", rule.c_str());
    return false;
  }

  // A number in [lo, hi] into `out` when the option is given (counted in `given`).
  bool number(const char* name, double lo, double hi, double* out, int* given) const {
    const char* text = value(name);
    if (!text) return true;
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (*text == '\0' || *end != '\0' || !(v >= lo && v <= hi))
      return fail(name, "must be a number from " + CPLString().Printf("%g", lo) + " to " +
                            CPLString().Printf("%g", hi));
    *out = v;
    ++*given;
    return true;
  }

  const char* filename_;
  char** options_;
};

// `bytes` into `filename` under a temporary name, renamed when complete.
bool writeWhole(const char* filename, const std::vector<uint8_t>& bytes) {
  std::string error;
  if (!STARTS_WITH(filename, "/vsi")) {
    if (mrsv::writeFileAtomically(filename, bytes, &error)) return true;
    CPLError(CE_Failure, CPLE_FileIO, "%s: %s", filename, error.c_str());
    return false;
  }
  // GDAL's virtual file systems (/vsimem/, ...): through VSI, the same way.
  const std::string temp = std::string(filename) + ".mrsv-tmp";
  VSILFILE* f = VSIFOpenL(temp.c_str(), "wb");
  bool ok = f && VSIFWriteL(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (f && VSIFCloseL(f) != 0) ok = false;
  if (ok && VSIRename(temp.c_str(), filename) != 0) ok = false;
  if (!ok) {
    VSIUnlink(temp.c_str());
    CPLError(CE_Failure, CPLE_FileIO, "%s: cannot write the file", filename);
  }
  return ok;
}

bool cancelled(GDALProgressFunc progress, void* data, double done, const char* filename) {
  if (progress(done, nullptr, data)) return false;
  CPLError(CE_Failure, CPLE_UserInterrupt, "%s: cancelled; nothing written", filename);
  return true;
}

}  // namespace

GDALDataset* mrsvCreateCopy(const char* filename, GDALDataset* source, int, char** options,
                            GDALProgressFunc progress, void* progress_data) {
  if (!progress) progress = GDALDummyProgress;
  bool stored = false;
  mrsv::WaveletEncodeOptions wavelet;
  if (!CreationOptions(filename, options).parse(&stored, &wavelet)) return nullptr;
  const int bands = source->GetRasterCount();
  if (bands != 1) {
    CPLError(CE_Failure, CPLE_NotSupported,
             "%s: an MRSV grid holds one band and the source has %d: choose one with gdal_translate -b N",
             filename, bands);
    return nullptr;
  }
  // Progress: the samples read 10 %, the encoding to 95 %, the file written.
  mrsv::GridInput input;
  std::string error;
  void* scaled = GDALCreateScaledProgress(0, 0.1, progress, progress_data);
  // (A source gdal_translate made in memory, e.g. for -ot, has no name.)
  const std::string source_name = *source->GetDescription() ? source->GetDescription() : "the source raster";
  const bool read = mrsv::readGdalDataset(GDALDataset::ToHandle(source), source_name, 1, &input, &error,
                                          GDALScaledProgress, scaled);
  GDALDestroyScaledProgress(scaled);
  if (!read) {
    CPLError(CE_Failure, CPLE_AppDefined, "%s: %s", filename, error.c_str());
    return nullptr;
  }
  if (cancelled(progress, progress_data, 0.1, filename)) return nullptr;
  std::vector<uint8_t> stream;
  const mrsv::Error e =
      stored ? mrsv::encodeStoredGrid(input.header, input.samples, input.metadata, &stream)
             : mrsv::encodeWaveletGrid(input.header, input.samples, input.metadata, wavelet, &stream, nullptr);
  if (!e.ok()) {
    CPLError(CE_Failure, CPLE_AppDefined, "%s: %s: %s: %s", filename, source_name.c_str(), e.field.c_str(),
             e.message.c_str());
    return nullptr;
  }
  if (cancelled(progress, progress_data, 0.95, filename) || !writeWhole(filename, stream)) return nullptr;
  progress(1.0, nullptr, progress_data);
  GDALOpenInfo info(filename, GA_ReadOnly);
  return mrsvOpen(&info);
}
