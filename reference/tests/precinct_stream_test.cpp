// Out-of-core encoding in precincts (decision D91) on real data: the strip
// analysis makes the same coefficients as the whole analysis, bit for bit;
// the out-of-core stream's band chunks are those of the in-memory encoder at
// the same step; voids come back as no-data; error bounds and lossless hold
// on every sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "grid/void_fill.h"
#include "mrsv/container.h"
#include "mrsv/encode.h"
#include "mrsv/tiled_grid.h"
#include "shared_data.h"
#include "test_support.h"
#include "wavelet/strip_analysis.h"

namespace mrsv {
namespace {

// A grid held in memory, read a box at a time as a raw file would be (from
// several threads at once).
class MemoryBoxReader : public GridBoxReader {
 public:
  MemoryBoxReader(const GridHeader& h, const std::vector<uint8_t>& samples) : h_(h), samples_(samples) {}
  bool read(const uint32_t origin[3], const uint32_t size[3], uint8_t* out, std::string*) override {
    const size_t bytes = sampleSize(h_.sample_type);
    for (uint32_t z = 0; z < size[2]; ++z)
      for (uint32_t y = 0; y < size[1]; ++y) {
        const size_t from = ((size_t{origin[2] + z} * h_.size_y + origin[1] + y) * h_.size_x + origin[0]) * bytes;
        std::memcpy(out, samples_.data() + from, size[0] * bytes);
        out += size[0] * bytes;
      }
    return true;
  }

 private:
  GridHeader h_;
  const std::vector<uint8_t>& samples_;
};

class VectorSink : public ByteSink {
 public:
  bool write(const uint8_t* data, size_t size) override {
    bytes.insert(bytes.end(), data, data + size);
    return true;
  }
  std::vector<uint8_t> bytes;
};

test::SharedGrid load(const char* relative) {
  test::SharedGrid g;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/" + relative, &g));
  return g;
}

std::vector<uint8_t> outOfCore(const test::SharedGrid& g, const WaveletEncodeOptions& o, int threads = 1,
                               WaveletEncodeReport* report = nullptr) {
  MemoryBoxReader reader(g.header, g.samples);
  VectorSink sink;
  PrecinctStreamOptions run;
  run.threads = threads;
  Error e = encodePrecinctGridFromReader(g.header, reader, Metadata{}, o, run, sink, report);
  EXPECT_TRUE(e.ok()) << e.describe();
  return sink.bytes;
}

std::vector<uint8_t> inMemory(const test::SharedGrid& g, const WaveletEncodeOptions& o) {
  std::vector<uint8_t> stream;
  Error e = encodeWaveletGrid(g.header, g.samples, Metadata{}, o, &stream, nullptr);
  EXPECT_TRUE(e.ok()) << e.describe();
  return stream;
}

// The chunks of a stream but its meta chunk (whose error figures are printed
// from sums taken in another order).
std::vector<std::pair<std::string, std::vector<uint8_t>>> codedChunks(const std::vector<uint8_t>& stream) {
  Container c;
  Error e = readContainer(stream.data(), stream.size(), ContainerOptions{}, &c);
  EXPECT_TRUE(e.ok()) << e.describe();
  std::vector<std::pair<std::string, std::vector<uint8_t>>> out;
  for (const ChunkView& chunk : c.chunks)
    if (chunk.chunk_type != kChunkMeta)
      out.emplace_back(std::string(chunk.chunk_type.c, 4),
                       std::vector<uint8_t>(chunk.payload, chunk.payload + chunk.chunk_length));
  return out;
}

DecodedGrid decode(const std::vector<uint8_t>& stream) {
  DecodedGrid out;
  Error e = decodeGrid(stream.data(), stream.size(), DecodeOptions{}, &out);
  EXPECT_TRUE(e.ok()) << e.describe();
  return out;
}

// Every level of the 9/7 analysis computed strip by strip (strips of `edge`
// rows of each part, the low-pass part of a level fed to the next) equals
// analyze()'s coefficients bit for bit.
void expectStripsEqualWhole(int num_dims, const uint32_t size[3], uint32_t edge, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-500, 3000);
  std::vector<double> x(uint64_t{size[0]} * size[1] * size[2]);
  for (double& v : x) v = std::round(value(rng));
  int levels[3] = {0, 0, 0};
  for (int a = 0; a < num_dims; ++a) levels[a] = wavelet::chooseLevels(size[a], wavelet::kOrderCdf97, 16);
  wavelet::GridPlan plan;
  ASSERT_TRUE(wavelet::makeGridPlan(num_dims, size, wavelet::kOrderCdf97, levels, &plan));
  std::vector<double> whole;
  analyzeSamples(plan, size, x, &whole);
  const uint32_t px = plan.axis[0].size(0), py = plan.axis[1].size(0);
  // The padded samples, then each level's input, rows along the slowest axis.
  std::vector<double> input(plan.paddedCount());
  for (uint32_t z = 0; z < plan.axis[2].size(0); ++z)
    for (uint32_t y = 0; y < py; ++y)
      for (uint32_t i = 0; i < px; ++i)
        input[(uint64_t{z} * py + y) * px + i] =
            x[(uint64_t{std::min(z, size[2] - 1)} * size[1] + std::min(y, size[1] - 1)) * size[0] +
              std::min(i, size[0] - 1)];
  int checked = 0;
  for (int level = 1; level <= plan.maxLevels(); ++level) {
    const wavelet::StripLevel s = wavelet::stripLevel(plan, level);
    const uint64_t row = s.rowSize();
    std::vector<double> low, out;
    for (uint32_t k0 = 0; k0 < s.lows; k0 += edge) {
      const uint32_t k1 = std::min(k0 + edge, s.lows);
      uint32_t first, count;
      wavelet::stripInput(s, k0, k1, &first, &count);
      out.assign(input.begin() + static_cast<long>(first * row), input.begin() + static_cast<long>((first + count) * row));
      const int threads = 1 + static_cast<int>(k0 / edge % 3);
      uint32_t dims[3] = {s.box[0], s.box[1], s.box[2]};
      wavelet::keepAlong(s, dims, &out, first, count, k0, k1, threads);
      wavelet::analyzeBelow(plan, level, s.axis, dims, out.data(), threads);
      const uint32_t lows = std::min(k1, s.lows) - k0, highs = k0 < s.highs ? std::min(k1, s.highs) - k0 : 0;
      ASSERT_EQ(out.size(), (lows + highs) * row);
      // Compare with the whole analysis: output row r of the strip is the
      // level box's row k0 + r (lows) or lows_total + k0 + r (highs).
      for (uint32_t r = 0; r < lows + highs; ++r) {
        const uint32_t at_s = r < lows ? k0 + r : s.lows + k0 + (r - lows);
        for (uint64_t i = 0; i < row; ++i) {
          const uint32_t ix = static_cast<uint32_t>(num_dims == 2 ? i : i % s.box[0]);
          const uint32_t iy = static_cast<uint32_t>(num_dims == 2 ? at_s : i / s.box[0]);
          const uint32_t iz = num_dims == 2 ? 0 : at_s;
          // The low-pass part of a level below the top is analysed further:
          // the whole analysis keeps only its detail bands.
          const uint32_t pos[3] = {ix, iy, iz};
          bool low_pass = true;
          for (int a = 0; a < num_dims; ++a)
            if (plan.axis[a].levels >= level && pos[a] >= plan.axis[a].size(level)) low_pass = false;
          if (low_pass && level < plan.maxLevels()) continue;
          const double expected = whole[(uint64_t{iz} * py + iy) * px + ix];
          ASSERT_EQ(std::memcmp(&expected, &out[r * row + i], sizeof(double)), 0)
              << "level " << level << " row " << at_s << " position " << i << ": " << out[r * row + i]
              << " != " << expected;
          ++checked;
        }
      }
      // The low-pass part (every split axis low) feeds the next level.
      for (uint32_t r = 0; r < lows; ++r)
        for (uint32_t y = 0; y < (num_dims == 3 ? plan.axis[1].size(level) : 1); ++y)
          for (uint32_t i = 0; i < plan.axis[0].size(level); ++i)
            low.push_back(out[r * row + (num_dims == 3 ? y * s.box[0] : 0) + i]);
    }
    input.swap(low);
  }
  EXPECT_GT(checked, 0);
}

TEST(StripAnalysis, EveryLevelEqualsTheWholeAnalysisBitForBit) {
  const uint32_t plane[3] = {301, 187, 1};
  expectStripsEqualWhole(2, plane, 16, 1);
  expectStripsEqualWhole(2, plane, 37, 2);
  const uint32_t tall[3] = {40, 517, 1};
  expectStripsEqualWhole(2, tall, 16, 3);
  const uint32_t volume[3] = {45, 37, 70};
  expectStripsEqualWhole(3, volume, 16, 4);
  const uint32_t flat[3] = {70, 66, 9};  // z with fewer levels than x and y
  expectStripsEqualWhole(3, flat, 16, 5);
}

TEST(PrecinctStream, BandsEqualTheInMemoryStreamAtAStep) {
  const test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  for (int p : {4, 6}) {
    WaveletEncodeOptions o;
    o.precinct_log2 = p;
    o.step = 6;
    const std::vector<uint8_t> ooc = outOfCore(g, o, p == 4 ? 2 : 1);
    EXPECT_EQ(codedChunks(ooc), codedChunks(inMemory(g, o))) << "precinct 2^" << p;
    const DecodedGrid d = decode(ooc);
    EXPECT_EQ(d.samples.size(), g.samples.size());
  }
}

// A rate: the same bisection as the in-memory search of the full pyramid
// (--progressive), a pass over the grid per step, so the same bands.
TEST(PrecinctStream, ARateGivesTheInMemoryProgressiveBands) {
  const test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.precinct_log2 = 6;
  o.bits_per_sample = 1;
  o.progressive = true;
  WaveletEncodeReport report;
  const std::vector<uint8_t> ooc = outOfCore(g, o, 2, &report);
  EXPECT_LE(ooc.size(), 317 * 460 / 8);
  EXPECT_GT(ooc.size(), 0.99 * 317 * 460 / 8);
  EXPECT_GT(report.iterations, 5);
  EXPECT_EQ(codedChunks(ooc), codedChunks(inMemory(g, o)));
}

// Weighted prediction exists only with range coding (5.3): asked for it with
// the baseline entropy mode, both encoders predict the coarsest band from
// its neighbours.
TEST(PrecinctStream, BaselineEntropyPredictsFromNeighbours) {
  const test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.precinct_log2 = 6;
  o.step = 6;
  o.entropy_mode = kEntropyBaseline;
  o.prediction = WaveletEncodeOptions::Prediction::kWeighted;
  const std::vector<uint8_t> ooc = outOfCore(g, o);
  EXPECT_EQ(codedChunks(ooc), codedChunks(inMemory(g, o)));
  EXPECT_EQ(decode(ooc).samples.size(), g.samples.size());
}

TEST(PrecinctStream, AVolumeEqualsTheInMemoryStream) {
  test::SharedGrid g = load("volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst");
  // A crop of 96 x 80 x 40 keeps the test short.
  test::SharedGrid crop = g;
  crop.header.size_x = 96;
  crop.header.size_y = 80;
  crop.header.size_z = 40;
  crop.samples.clear();
  for (uint32_t z = 0; z < 40; ++z)
    for (uint32_t y = 0; y < 80; ++y)
      for (uint32_t x = 0; x < 96; ++x) crop.samples.push_back(g.samples[(uint64_t{30 + z} * 256 + 80 + y) * 256 + 60 + x]);
  WaveletEncodeOptions o;
  o.precinct_log2 = 5;
  o.step = 3;
  // Three threads: each takes pieces of its own (3-D), in any order.
  const auto in_memory = codedChunks(inMemory(crop, o));
  for (int threads : {1, 3}) EXPECT_EQ(codedChunks(outOfCore(crop, o, threads)), in_memory) << threads;
}

TEST(PrecinctStream, BoundsHoldOnEverySampleWithVoids) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  g.header.grid_flags |= kGridFlagHasNodata;
  g.header.nodata_bits = 0x8000;
  const int16_t void_value = -32768;
  for (uint32_t y = 0; y < 460; ++y)
    for (uint32_t x = 0; x < 317; ++x)
      if ((x >= 110 && x < 150 && y >= 240 && y < 270) || (y * 317 + x) % 97 == 0 || (x < 64 && y < 64))
        std::memcpy(g.samples.data() + 2 * (y * 317 + x), &void_value, 2);
  for (double bound : {0.0, 2.0, 7.0}) {
    WaveletEncodeOptions o;
    o.precinct_log2 = 6;
    o.max_error = bound;
    WaveletEncodeReport report;
    const std::vector<uint8_t> stream = outOfCore(g, o, 2, &report);
    const DecodedGrid d = decode(stream);
    ASSERT_EQ(d.samples.size(), g.samples.size());
    double worst = 0;
    for (size_t i = 0; i < g.samples.size(); i += 2) {
      int16_t a, b;
      std::memcpy(&a, g.samples.data() + i, 2);
      std::memcpy(&b, d.samples.data() + i, 2);
      if (a == void_value) {
        ASSERT_EQ(b, void_value) << "sample " << i / 2;
        continue;
      }
      worst = std::max(worst, std::fabs(double(a) - b));
    }
    EXPECT_LE(worst, bound);
    EXPECT_EQ(worst, report.max_abs_error);
  }
}

// 3-D with voids: the CT head's air (sample 0) as no-data, in pieces of
// 16 x 16 x 16 precincts; lossless and a bound of 3 hold on every sample.
TEST(PrecinctStream, AVolumeWithVoidsHoldsItsBounds) {
  const test::SharedGrid g = load("volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst");
  test::SharedGrid crop = g;
  crop.header.size_x = 70;
  crop.header.size_y = 90;
  crop.header.size_z = 37;
  crop.header.grid_flags |= kGridFlagHasNodata;
  crop.header.nodata_bits = 0;
  crop.samples.clear();
  size_t voids = 0;
  for (uint32_t z = 0; z < 37; ++z)
    for (uint32_t y = 0; y < 90; ++y)
      for (uint32_t x = 0; x < 70; ++x) {
        crop.samples.push_back(g.samples[(uint64_t{40 + z} * 256 + 20 + y) * 256 + 90 + x]);
        voids += crop.samples.back() == 0;
      }
  ASSERT_GT(voids, 1000u);
  for (double bound : {0.0, 3.0}) {
    WaveletEncodeOptions o;
    o.precinct_log2 = 4;
    o.max_error = bound;
    WaveletEncodeReport report;
    const DecodedGrid d = decode(outOfCore(crop, o, 2, &report));
    ASSERT_EQ(d.samples.size(), crop.samples.size());
    double worst = 0;
    for (size_t i = 0; i < crop.samples.size(); ++i) {
      if (crop.samples[i] == 0) {
        ASSERT_EQ(d.samples[i], 0) << "void " << i;
        continue;
      }
      worst = std::max(worst, std::fabs(double(crop.samples[i]) - d.samples[i]));
    }
    EXPECT_LE(worst, bound);
  }
}

TEST(PrecinctStream, RefusesWhatItDoesNotDo) {
  const test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  MemoryBoxReader reader(g.header, g.samples);
  VectorSink sink;
  WaveletEncodeOptions o;
  o.step = 4;  // no precincts
  EXPECT_FALSE(encodePrecinctGridFromReader(g.header, reader, Metadata{}, o, {}, sink, nullptr).ok());
  o.precinct_log2 = 6;
  o.order = 2;
  EXPECT_FALSE(encodePrecinctGridFromReader(g.header, reader, Metadata{}, o, {}, sink, nullptr).ok());
  o.order = kWaveletOrderCdf97;
  o.step = 0;
  o.psnr = 50;
  EXPECT_FALSE(encodePrecinctGridFromReader(g.header, reader, Metadata{}, o, {}, sink, nullptr).ok());
}

}  // namespace
}  // namespace mrsv
