// Wavelet-coded grids (spec 5) on real data: lossless and error-bounded coding
// hold exactly, rate and PSNR targets are met, prefixes refine, voids survive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "shared_data.h"
#include "test_support.h"

namespace mrsv {
namespace {

struct TestGrid {
  std::string name;
  GridHeader header;
  std::vector<uint8_t> samples;
};

// A window of a shared grid (keeps the test time small while using real data).
TestGrid window(const test::SharedGrid& g, uint32_t wx, uint32_t wy, uint32_t wz) {
  TestGrid t;
  t.name = g.name;
  t.header = g.header;
  const size_t bytes = sampleSize(g.header.sample_type);
  uint32_t size[3] = {std::min(wx, g.header.size_x), std::min(wy, g.header.size_y),
                      std::min(wz, g.header.size_z)};
  // Centre the window, where the data is most detailed.
  uint32_t origin[3] = {(g.header.size_x - size[0]) / 2, (g.header.size_y - size[1]) / 2,
                        (g.header.size_z - size[2]) / 2};
  t.header.size_x = size[0];
  t.header.size_y = size[1];
  t.header.size_z = size[2];
  for (uint32_t z = 0; z < size[2]; ++z)
    for (uint32_t y = 0; y < size[1]; ++y) {
      size_t start = ((size_t{origin[2] + z} * g.header.size_y + origin[1] + y) * g.header.size_x +
                      origin[0]) * bytes;
      t.samples.insert(t.samples.end(), g.samples.begin() + static_cast<long>(start),
                       g.samples.begin() + static_cast<long>(start + size_t{size[0]} * bytes));
    }
  if (g.header.sample_type == SampleType::kInt16) {  // SRTM voids
    for (size_t i = 0; i < t.samples.size(); i += 2)
      if (t.samples[i] == 0x00 && t.samples[i + 1] == 0x80) {
        t.header.grid_flags = kGridFlagHasNodata;
        t.header.nodata_bits = 0x8000;
        break;
      }
  }
  return t;
}

std::vector<TestGrid> realWindows() {
  std::vector<TestGrid> out;
  for (const std::string& path : test::sharedGridFiles()) {
    test::SharedGrid g;
    if (!test::loadSharedGrid(path, &g)) continue;
    out.push_back(g.header.num_dims == 2 ? window(g, 181, 157, 1) : window(g, 45, 39, 33));
  }
  return out;
}

double sampleAt(const std::vector<uint8_t>& s, size_t i, SampleType t) {
  switch (t) {
    case SampleType::kUint8: return s[i];
    case SampleType::kInt16: { int16_t v; std::memcpy(&v, &s[2 * i], 2); return v; }
    case SampleType::kUint16: { uint16_t v; std::memcpy(&v, &s[2 * i], 2); return v; }
    case SampleType::kInt32: { int32_t v; std::memcpy(&v, &s[4 * i], 4); return v; }
    case SampleType::kFloat32: { float v; std::memcpy(&v, &s[4 * i], 4); return v; }
    case SampleType::kFloat64: { double v; std::memcpy(&v, &s[8 * i], 8); return v; }
  }
  return 0;
}

bool isVoid(const TestGrid& g, size_t i) {
  size_t b = sampleSize(g.header.sample_type);
  return g.header.hasNodata() && std::memcmp(&g.samples[i * b], &g.header.nodata_bits, b) == 0;
}

// Largest |decoded - input| over valid samples; voids must come back exactly.
double maxError(const TestGrid& g, const std::vector<uint8_t>& decoded) {
  double worst = 0;
  size_t b = sampleSize(g.header.sample_type);
  for (size_t i = 0; i < g.header.sampleCount(); ++i) {
    if (isVoid(g, i)) {
      if (std::memcmp(&decoded[i * b], &g.samples[i * b], b) != 0) return 1e300;
      continue;
    }
    worst = std::max(worst, std::fabs(sampleAt(decoded, i, g.header.sample_type) -
                                      sampleAt(g.samples, i, g.header.sample_type)));
  }
  return worst;
}

DecodedGrid decode(const std::vector<uint8_t>& stream, int reduce = 0) {
  DecodedGrid out;
  DecodeOptions options;
  options.reduce_levels = reduce;
  Error e = decodeGrid(stream.data(), stream.size(), options, &out);
  EXPECT_TRUE(e.ok()) << e.describe();
  return out;
}

TEST(WaveletGrid, LosslessIsExactOnRealDataForEveryOrder) {
  std::vector<TestGrid> grids = realWindows();
  ASSERT_GE(grids.size(), 12u);
  for (const TestGrid& g : grids) {
    for (int order : {1, 2, 3, 4, kWaveletOrderCdf97}) {
      WaveletEncodeOptions options;
      options.order = order;
      options.max_error = 0;
      std::vector<uint8_t> stream;
      WaveletEncodeReport report;
      Error e = encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, &report);
      ASSERT_TRUE(e.ok()) << g.name << ": " << e.describe();
      DecodedGrid out = decode(stream);
      EXPECT_TRUE(out.samples == g.samples) << g.name << " order " << order;
      EXPECT_EQ(report.max_abs_error, 0) << g.name;
      EXPECT_LT(stream.size(), g.samples.size()) << g.name << " order " << order;
    }
  }
}

TEST(WaveletGrid, ErrorBoundHoldsForEverySample) {
  for (const TestGrid& g : realWindows()) {
    for (double d : {1.0, 3.0, 10.0}) {
      WaveletEncodeOptions options;
      options.max_error = d;
      std::vector<uint8_t> stream;
      ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, nullptr).ok());
      EXPECT_LE(maxError(g, decode(stream).samples), d) << g.name << " d=" << d;
    }
  }
}

TEST(WaveletGrid, RateAndPsnrTargetsAreMet) {
  for (const TestGrid& g : realWindows()) {
    const double n = static_cast<double>(g.header.sampleCount());
    for (double rate : {0.5, 2.0}) {
      // Progressive (wavelet levels only): the rate is met within 5 %.
      WaveletEncodeOptions options;
      options.bits_per_sample = rate;
      options.progressive = true;
      std::vector<uint8_t> stream;
      WaveletEncodeReport progressive;
      ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, &progressive).ok())
          << g.name;
      double achieved = 8.0 * static_cast<double>(stream.size()) / n;
      EXPECT_LE(achieved, rate) << g.name;
      EXPECT_GE(achieved, 0.95 * rate) << g.name << " (rate met within 5 %)";
      EXPECT_GT(progressive.levels, 0) << g.name;
      // The default also tries the predictive route (spec 5.9 item 6): it never
      // does worse, and a stream well under the rate must be a better one.
      options.progressive = false;
      WaveletEncodeReport chosen;
      ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, &chosen).ok())
          << g.name;
      achieved = 8.0 * static_cast<double>(stream.size()) / n;
      EXPECT_LE(achieved, rate) << g.name;
      EXPECT_GE(chosen.psnr, progressive.psnr) << g.name << " rate " << rate;
      if (achieved < 0.95 * rate) {  // better, or as exact and smaller
        EXPECT_EQ(chosen.levels, 0) << g.name << " rate " << rate;
        EXPECT_TRUE(chosen.psnr > progressive.psnr ||
                    (std::isinf(chosen.psnr) && chosen.bytes < progressive.bytes))
            << g.name << " rate " << rate;
      }
    }
    WaveletEncodeOptions options;
    options.psnr = 45;
    options.progressive = true;
    std::vector<uint8_t> progressive, chosen;
    WaveletEncodeReport report;
    ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &progressive, &report).ok());
    EXPECT_GE(report.psnr, 45) << g.name;
    EXPECT_LT(report.psnr, 46.5) << g.name << ": the target is met without waste";
    options.progressive = false;
    ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &chosen, &report).ok());
    EXPECT_GE(report.psnr, 45) << g.name;
    EXPECT_LE(chosen.size(), progressive.size()) << g.name;
    if (report.levels == 0) {
      EXPECT_LT(chosen.size(), progressive.size()) << g.name;
    }
  }
}

TEST(WaveletGrid, DeterministicAndPrefixesRefine) {
  test::SharedGrid g;
  ASSERT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/terrain/mt_st_helens_317x460_int16le.raw.zst", &g));
  WaveletEncodeOptions options;
  options.bits_per_sample = 2;
  options.progressive = true;
  std::vector<uint8_t> a, b;
  ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &a, nullptr).ok());
  ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &b, nullptr).ok());
  EXPECT_EQ(a, b);
  DecodedGrid whole = decode(a);
  // Every chunk boundary is a valid prefix; more bands never make the error much worse.
  double previous = std::numeric_limits<double>::infinity(), first_sse = -1;
  TestGrid t{g.name, g.header, g.samples};
  for (const ChunkView& chunk : whole.container.chunks) {
    std::vector<uint8_t> prefix(a.begin(), a.begin() + static_cast<long>(chunk.endOffset()));
    DecodedGrid p = decode(prefix);
    if (!p.has_samples) continue;
    double sse = 0;
    for (size_t i = 0; i < g.header.sampleCount(); ++i) {
      double d = sampleAt(p.samples, i, g.header.sample_type) - sampleAt(g.samples, i, g.header.sample_type);
      sse += d * d;
    }
    // The wavelets of one band are not orthogonal to each other, so a band can
    // add a little error in the sample domain; over the stream it falls steeply.
    EXPECT_LE(sse, previous * 1.25 + 1) << "after " << chunk.chunk_type.str() << " at " << chunk.offset;
    if (first_sse < 0) first_sse = sse;
    previous = sse;
  }
  EXPECT_LT(previous, first_sse / 50);
  DecodedGrid half = decode(a, 1);
  EXPECT_EQ(options.order, kWaveletOrderCdf97);
  EXPECT_EQ(half.output_size[0], (317u + 1) / 2);  // ceil(N / 2) (spec 4.11.1)
  EXPECT_EQ(half.samples.size(), size_t{half.output_size[0]} * half.output_size[1] * 2);
}

// The decoder takes the last level of a 3-D 9/7 grid of integer samples slice
// by slice, its bands kept apart (grid/last_level_bands.h); decoding through
// a padded array of the whole grid must give the same samples, byte for byte:
// every real volume, streams of one level and of many, a residual layer,
// every prefix of one stream, and symbols too wide for 16 bits.
TEST(WaveletGrid, LastLevelBySlicesGivesTheSamplesOfTheWholeArray) {
  auto same = [](const std::vector<uint8_t>& stream, const std::string& what) {
    DecodedGrid by_slices, whole;
    DecodeOptions options;
    const Error a = decodeGrid(stream.data(), stream.size(), options, &by_slices);
    options.whole_array_synthesis = true;
    const Error b = decodeGrid(stream.data(), stream.size(), options, &whole);
    ASSERT_TRUE(a.ok() && b.ok()) << what << ": " << a.describe() << " / " << b.describe();
    ASSERT_EQ(by_slices.has_samples, whole.has_samples) << what;
    ASSERT_TRUE(by_slices.samples == whole.samples) << what;
  };
  for (const TestGrid& g : realWindows()) {
    if (g.header.num_dims != 3) continue;
    for (int variant = 0; variant < 4; ++variant) {
      WaveletEncodeOptions options;
      if (variant == 0) options.bits_per_sample = 1;               // one level, weighted block
      if (variant == 1) options.bits_per_sample = 0.5, options.progressive = true;
      if (variant == 2) options.max_error = 2, options.progressive = true;  // residual layer
      if (variant == 3) options.step = 0.25, options.progressive = true;
      std::vector<uint8_t> stream;
      ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, nullptr).ok());
      same(stream, g.name + " variant " + std::to_string(variant));
      if (variant != 1) continue;
      for (const ChunkView& chunk : decode(stream).container.chunks)
        same(std::vector<uint8_t>(stream.begin(), stream.begin() + static_cast<long>(chunk.endOffset())),
             g.name + " prefix to " + std::to_string(chunk.endOffset()));
    }
  }
  // int32 samples of full range, quantised finely: finest-level symbols far
  // beyond 2^15, so that those bands are decoded again to their values.
  GridHeader h;
  h.num_dims = 3;
  h.size_x = 23, h.size_y = 19, h.size_z = 17;  // one level along every axis
  h.sample_type = SampleType::kInt32;
  std::vector<uint8_t> samples(h.sampleCount() * 4);
  std::mt19937 rng(31);
  for (size_t i = 0; i < h.sampleCount(); ++i) {
    const int32_t v = static_cast<int32_t>(rng());
    std::memcpy(&samples[4 * i], &v, 4);
  }
  WaveletEncodeOptions options;
  options.step = 1;
  options.progressive = true;
  std::vector<uint8_t> stream;
  ASSERT_TRUE(encodeWaveletGrid(h, samples, Metadata{}, options, &stream, nullptr).ok());
  same(stream, "int32 noise");
}

// reducedResolution() (the GDAL driver's overviews) from the headers alone:
// the decode's output size, and the bands it names are all the synthesis
// reads: the prefix before the next band decodes to the same samples.
TEST(WaveletGrid, ReducedResolutionNeedsOnlyItsBands) {
  int checked = 0;
  for (const TestGrid& g : realWindows()) {
    for (int order : {2, kWaveletOrderCdf97}) {
      WaveletEncodeOptions options;
      options.order = order;
      options.max_error = 3;
      options.progressive = true;
      std::vector<uint8_t> stream;
      ASSERT_TRUE(encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, nullptr).ok());
      Container c;
      ASSERT_TRUE(readContainer(stream.data(), stream.size(), ContainerOptions{}, &c).ok());
      std::vector<uint64_t> bands;
      for (const ChunkView& chunk : c.chunks)
        if (chunk.chunk_type == kChunkBand) bands.push_back(chunk.offset);
      const DecodedGrid full = decode(stream);
      const int levels = std::max({full.wavelet.levels[0], full.wavelet.levels[1], full.wavelet.levels[2]});
      for (int reduce = 0; reduce <= levels + 1; ++reduce) {
        ReducedResolution r;
        ASSERT_TRUE(reducedResolution(full.header, full.wavelet, reduce, &r));
        const DecodedGrid whole = decode(stream, reduce);
        for (int a = 0; a < 3; ++a)
          EXPECT_EQ(r.size[a], whole.output_size[a]) << g.name << " order " << order << " reduce " << reduce;
        ASSERT_GE(r.bands_needed, 1u);
        ASSERT_LE(r.bands_needed, bands.size());
        EXPECT_EQ(r.bands_needed == bands.size(), reduce == 0) << g.name << " reduce " << reduce;
        const size_t prefix = r.bands_needed < bands.size() ? bands[r.bands_needed] : stream.size();
        DecodedGrid part;
        DecodeOptions o;
        o.reduce_levels = reduce;
        ASSERT_TRUE(decodeGrid(stream.data(), prefix, o, &part).ok());
        EXPECT_TRUE(part.samples == whole.samples) << g.name << " order " << order << " reduce " << reduce;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 50);
  GridHeader stored;
  stored.num_dims = 2;
  ReducedResolution r;
  EXPECT_FALSE(reducedResolution(stored, WaveletHeader{}, 1, &r));
}

TEST(WaveletGrid, FloatSamplesAndRefusals) {
  test::SharedGrid g;
  ASSERT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/terrain/mt_st_helens_317x460_int16le.raw.zst", &g));
  GridHeader h = g.header;
  h.sample_type = SampleType::kFloat32;
  std::vector<uint8_t> floats(g.header.sampleCount() * 4);
  for (size_t i = 0; i < g.header.sampleCount(); ++i) {
    float v = static_cast<float>(sampleAt(g.samples, i, SampleType::kInt16)) * 0.3048f;  // feet
    std::memcpy(&floats[4 * i], &v, 4);
  }
  WaveletEncodeOptions options;
  options.psnr = 60;
  std::vector<uint8_t> stream;
  WaveletEncodeReport report;
  ASSERT_TRUE(encodeWaveletGrid(h, floats, Metadata{}, options, &stream, &report).ok());
  EXPECT_GE(report.psnr, 60);
  EXPECT_TRUE(decode(stream).has_samples);

  float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&floats[40], &nan, 4);
  EXPECT_EQ(encodeWaveletGrid(h, floats, Metadata{}, options, &stream, &report).status,
            Status::kInvalidArgument);
  float fine = 1.0f;
  std::memcpy(&floats[40], &fine, 4);
  options = WaveletEncodeOptions{};
  options.max_error = 0;  // error bounds need integer samples in this version
  EXPECT_EQ(encodeWaveletGrid(h, floats, Metadata{}, options, &stream, &report).status,
            Status::kInvalidArgument);
}

}  // namespace
}  // namespace mrsv
