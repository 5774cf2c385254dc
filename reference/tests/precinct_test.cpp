// Precincts (spec 5.7.6) on real data: the blocks tile every array; a stream
// in precincts decodes to exactly the samples of the same stream without them
// (the blocks change the entropy coding only), prefixes included; lossless
// and error-bounded coding hold with voids; a broken block is reported at its
// offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>

#include "common/crc32c.h"
#include "grid/precincts.h"
#include "tiles/tile_decode.h"
#include "wavelet/axis_plan.h"
#include "mrsv/container.h"
#include "mrsv/encode.h"
#include "mrsv/tiled_grid.h"
#include "shared_data.h"
#include "test_support.h"

namespace mrsv {
namespace {

test::SharedGrid load(const char* relative) {
  test::SharedGrid g;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/" + relative, &g));
  return g;
}

std::vector<uint8_t> encode(const test::SharedGrid& g, WaveletEncodeOptions o, int precinct_log2) {
  o.precinct_log2 = precinct_log2;
  std::vector<uint8_t> stream;
  Error e = encodeWaveletGrid(g.header, g.samples, Metadata{}, o, &stream, nullptr);
  EXPECT_TRUE(e.ok()) << e.describe();
  return stream;
}

Container chunksOf(const std::vector<uint8_t>& stream) {
  Container c;
  Error e = readContainer(stream.data(), stream.size(), ContainerOptions{}, &c);
  EXPECT_TRUE(e.ok()) << e.describe();
  return c;
}

// St Helens with voids (no-data -32768): a lake of 40 x 30 samples across
// precinct borders and every 97th sample.
test::SharedGrid stHelensWithVoids() {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  g.header.grid_flags |= kGridFlagHasNodata;
  g.header.nodata_bits = 0x8000;
  const int16_t void_value = -32768;
  for (uint32_t y = 0; y < 460; ++y)
    for (uint32_t x = 0; x < 317; ++x)
      if ((x >= 110 && x < 150 && y >= 240 && y < 270) || (y * 317 + x) % 97 == 0)
        std::memcpy(g.samples.data() + 2 * (y * 317 + x), &void_value, 2);
  return g;
}

DecodedGrid decode(const std::vector<uint8_t>& stream) {
  DecodedGrid out;
  Error e = decodeGrid(stream.data(), stream.size(), DecodeOptions{}, &out);
  EXPECT_TRUE(e.ok()) << e.describe();
  return out;
}

TEST(Precincts, BlocksTileTheBoxOnce) {
  const uint32_t sizes[][3] = {{317, 460, 1}, {16, 16, 1}, {17, 1, 1}, {37, 29, 19}, {1, 1, 1}};
  const int dims[] = {2, 2, 1, 3, 3};
  for (int c = 0; c < 5; ++c)
    for (int p = kMinPrecinctLog2; p <= 9; ++p)
      for (int r = 0; r <= 6; ++r) {
        ArrayBox box;
        box.num_dims = dims[c];
        std::memcpy(box.size, sizes[c], sizeof box.size);
        const int resolution[3] = {r, r / 2, r};
        std::vector<ArrayBlock> blocks = arrayBlocks(box, resolution, p);
        ASSERT_EQ(blocks.size(), arrayBlockCount(box, resolution, p));
        std::vector<int> covered(box.count(), 0);
        for (const ArrayBlock& b : blocks)
          for (uint32_t z = 0; z < b.box.size[2]; ++z)
            for (uint32_t y = 0; y < b.box.size[1]; ++y)
              for (uint32_t x = 0; x < b.box.size[0]; ++x)
                ++covered[(b.origin[0] + x) + box.size[0] * ((b.origin[1] + y) + size_t{box.size[1]} * (b.origin[2] + z))];
        for (int n : covered) ASSERT_EQ(n, 1);
        // Along a used axis the edge is 2^(p - r), at least 16.
        const uint32_t edge = std::max<uint32_t>(r < p ? 1u << (p - r) : 1u, kMinBlockEdge);
        EXPECT_EQ(blocks[0].box.size[0], std::min(edge, box.size[0]));
      }
}

// At a fixed step every band is quantised block by block (5.9 item 10): a
// band held in one block quantises as without precincts, so the prefixes of
// such bands decode to the same bits; the finer bands differ only where the
// rate-distortion walk and the lone-unit rule meet a block border (at 1 bit
// per sample Rainier and Everest gain 0.01 dB by it, decision D91).
TEST(Precincts, SameSamplesAsWithoutPrecinctsWhileBandsAreOneBlock) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.step = 6;
  const int p = 6;
  std::vector<uint8_t> whole = encode(g, o, 0), blocked = encode(g, o, p);
  EXPECT_NE(whole, blocked);
  Container a = chunksOf(whole), b = chunksOf(blocked);
  ASSERT_EQ(a.chunks.size(), b.chunks.size());
  const DecodedGrid dw = decode(whole), db = decode(blocked);
  const uint32_t size[3] = {g.header.size_x, g.header.size_y, 1};
  const int levels[3] = {dw.wavelet.levels[0], dw.wavelet.levels[1], 0};
  wavelet::GridPlan plan;
  ASSERT_TRUE(wavelet::makeGridPlan(2, size, dw.wavelet.order, levels, &plan));
  const std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
  // Chunks: GHDR, meta, WHDR, then one GBND per band.
  int same = 0;
  for (size_t band = 0; band < bands.size(); ++band) {
    const uint32_t edge = std::max<uint32_t>(1u << std::max(p - bands[band].level, 0), kMinBlockEdge);
    if (bands[band].size[0] > edge || bands[band].size[1] > edge) break;
    const size_t i = 3 + band;
    std::vector<uint8_t> pa(whole.begin(), whole.begin() + a.chunks[i].endOffset());
    std::vector<uint8_t> pb(blocked.begin(), blocked.begin() + b.chunks[i].endOffset());
    EXPECT_EQ(decode(pb).samples, decode(pa).samples) << "prefix of " << i + 1 << " chunks";
    ++same;
  }
  EXPECT_GE(same, 4);
  double sse_whole = 0, sse_blocked = 0;
  for (size_t i = 0; i < g.samples.size(); i += 2) {
    int16_t v, w, k;
    std::memcpy(&v, g.samples.data() + i, 2);
    std::memcpy(&w, dw.samples.data() + i, 2);
    std::memcpy(&k, db.samples.data() + i, 2);
    sse_whole += double(v - w) * (v - w);
    sse_blocked += double(v - k) * (v - k);
  }
  // At the same step (not the same rate: the per-block walk drops more in
  // blocks of 64 or fewer values, St Helens 0.13 dB and its bytes with it).
  EXPECT_NEAR(10 * std::log10(sse_whole / sse_blocked), 0.0, 0.25);
}

TEST(Precincts, LosslessAndBoundedWithVoidsIn2DAnd3D) {
  test::SharedGrid helens = stHelensWithVoids();
  WaveletEncodeOptions o;
  o.max_error = 0;
  EXPECT_EQ(decode(encode(helens, o, 6)).samples, helens.samples);
  o.max_error = 2;
  o.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  DecodedGrid d = decode(encode(helens, o, 5));
  for (size_t i = 0; i < helens.header.sampleCount(); ++i) {
    int16_t want, got;
    std::memcpy(&want, helens.samples.data() + 2 * i, 2);
    std::memcpy(&got, d.samples.data() + 2 * i, 2);
    ASSERT_LE(std::abs(int{want} - int{got}), want == -32768 ? 0 : 2) << "sample " << i;
  }
  test::SharedGrid head = load("volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst");
  WaveletEncodeOptions exact;
  exact.max_error = 0;
  exact.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  EXPECT_EQ(decode(encode(head, exact, 5)).samples, head.samples);
}

TEST(Precincts, ABrokenBlockIsReportedAtItsOffset) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.step = 6;
  std::vector<uint8_t> s = encode(g, o, 6);
  Container c = chunksOf(s);
  // The last band: its table of lengths starts 12 bytes into the payload.
  size_t band = 0;
  for (size_t i = 0; i < c.chunks.size(); ++i)
    if (c.chunks[i].chunk_type == kChunkBand && c.chunks[i].chunk_length > kBandHeaderSize) band = i;
  const uint64_t table = c.chunks[band].payloadOffset() + kBandHeaderSize;
  uint32_t first;
  std::memcpy(&first, s.data() + table, 4);
  ASSERT_GT(first, 0u);
  // Find the first block's data: after the table, whose size the lengths fix.
  uint64_t n = 0, sum = 0;
  const uint64_t coded = c.chunks[band].chunk_length - kBandHeaderSize;
  while (4 * (n + 1) + sum <= coded) {
    uint32_t len;
    std::memcpy(&len, s.data() + table + 4 * n, 4);
    sum += len;
    ++n;
    if (4 * n + sum == coded) break;
  }
  ASSERT_EQ(4 * n + sum, coded);
  std::vector<uint8_t> broken = s;
  broken[table + 4 * n] = 1;  // the first block's first byte must be 0 (spec 5.6)
  const ChunkView& k = c.chunks[band];
  const uint32_t crc = crc32c(0, broken.data() + k.offset, kChunkHeaderSize + k.chunk_length);
  for (int i = 0; i < 4; ++i) broken[k.endOffset() - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  DecodedGrid out;
  Error e = decodeGrid(broken.data(), broken.size(), DecodeOptions{}, &out);
  EXPECT_EQ(e.status, Status::kBadEntropyPayload);
  EXPECT_EQ(e.offset, table + 4 * n);
}

// Region decoding by precinct equals the same box of the whole decode, for
// every wavelet, 2-D and 3-D, with a mask and a residual, for prefixes; and a
// small box reads a small part of the file.
void expectRegionsMatch(const std::vector<uint8_t>& stream, uint32_t trials, uint64_t seed,
                        uint64_t* least_read = nullptr) {
  const DecodedGrid whole = decode(stream);
  const GridHeader& h = whole.header;
  const uint32_t n[3] = {h.size_x, h.size_y, h.size_z};
  const size_t bytes = sampleSize(h.sample_type);
  std::mt19937_64 rng(seed);
  for (uint32_t t = 0; t < trials; ++t) {
    GridRegion r;
    for (int a = 0; a < 3; ++a) {
      uint32_t lo = static_cast<uint32_t>(rng() % n[a]), hi = static_cast<uint32_t>(rng() % n[a]);
      if (t % 3 == 0) hi = std::min<uint32_t>(n[a] - 1, lo + static_cast<uint32_t>(rng() % 40));
      if (lo > hi) std::swap(lo, hi);
      r.lo[a] = lo;
      r.hi[a] = hi + 1;
    }
    MemoryByteSource source(stream.data(), stream.size());
    DecodedGrid region;
    Error e = decodeGridRegion(source, r, DecodeOptions{}, &region);
    ASSERT_TRUE(e.ok()) << e.describe();
    ASSERT_TRUE(region.region_by_precincts);
    ASSERT_EQ(region.has_samples, whole.has_samples);
    if (!whole.has_samples) continue;
    size_t k = 0;
    for (uint32_t z = r.lo[2]; z < r.hi[2]; ++z)
      for (uint32_t y = r.lo[1]; y < r.hi[1]; ++y) {
        const size_t at = ((uint64_t{z} * n[1] + y) * n[0] + r.lo[0]) * bytes, len = (r.hi[0] - r.lo[0]) * bytes;
        ASSERT_EQ(0, std::memcmp(region.samples.data() + k, whole.samples.data() + at, len))
            << "box " << r.lo[0] << "," << r.lo[1] << "," << r.lo[2] << " .. " << r.hi[0] << "," << r.hi[1] << ","
            << r.hi[2] << " row y " << y << " z " << z;
        k += len;
      }
    if (least_read) *least_read = std::min(*least_read, source.bytesRead());
  }
}

TEST(Precincts, RegionsEqualTheWholeDecode) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  for (int order : {kWaveletOrderCdf97, 1, 2, 4}) {
    WaveletEncodeOptions o;
    o.order = order;
    o.step = 5;
    SCOPED_TRACE("order " + std::to_string(order));
    uint64_t least = UINT64_MAX;
    const std::vector<uint8_t> s = encode(g, o, 6);
    expectRegionsMatch(s, 12, 7 + order, &least);
    EXPECT_LT(least, s.size() / 4);  // a box of at most 40^2 samples reads little
  }
  WaveletEncodeOptions bounded;  // a residual without a mask
  bounded.max_error = 1;
  bounded.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  expectRegionsMatch(encode(g, bounded, 4), 12, 9);
  test::SharedGrid feet = g;  // float32 samples (5.8.2's two binary64 operations)
  feet.header.sample_type = SampleType::kFloat32;
  feet.samples.resize(g.samples.size() * 2);
  for (size_t i = 0; i < g.header.sampleCount(); ++i) {
    int16_t v;
    std::memcpy(&v, g.samples.data() + 2 * i, 2);
    const float f = static_cast<float>(v) / 0.3048f;
    std::memcpy(feet.samples.data() + 4 * i, &f, 4);
  }
  WaveletEncodeOptions fine;
  fine.step = 2;
  expectRegionsMatch(encode(feet, fine, 6), 12, 13);
  WaveletEncodeOptions coarse;  // blocks of length 0 at the fine levels
  coarse.step = 60;
  expectRegionsMatch(encode(g, coarse, 5), 12, 3);
}

TEST(Precincts, RegionsWithMaskResidualPrefixesAndVolumes) {
  test::SharedGrid g = stHelensWithVoids();
  WaveletEncodeOptions bounded;
  bounded.max_error = 2;
  bounded.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  const std::vector<uint8_t> s = encode(g, bounded, 5);
  expectRegionsMatch(s, 16, 11);
  // Prefixes: after the mask, after two bands, before GRES, before MEND.
  Container c = chunksOf(s);
  for (size_t i = 2; i < c.chunks.size(); ++i) {
    const ChunkType t = c.chunks[i].chunk_type;
    if (t != kChunkNodataMask && t != kChunkResidual && t != kChunkEnd && i != 6) continue;
    SCOPED_TRACE("prefix before chunk " + std::to_string(i));
    expectRegionsMatch(std::vector<uint8_t>(s.begin(), s.begin() + c.chunks[i].offset), 6, i);
  }
  test::SharedGrid head = load("volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst");
  for (int order : {kWaveletOrderCdf97, 2}) {
    WaveletEncodeOptions o;
    o.order = order;
    o.step = 3;
    SCOPED_TRACE("volume, order " + std::to_string(order));
    expectRegionsMatch(encode(head, o, 4), 12, 5);
  }
}

// A region decode within a memory limit the stream needs more than: the
// whole decode's 901, not an allocation beyond the limit.
TEST(Precincts, RegionWithinTheMemoryLimitOrTheWholeDecodesError) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.step = 5;
  const std::vector<uint8_t> s = encode(g, o, 8);
  GridRegion r;
  r.lo[0] = 10, r.lo[1] = 20, r.hi[0] = 300, r.hi[1] = 400;
  DecodeOptions small;
  small.max_output_bytes = 200000;  // a window of the box alone needs more
  MemoryByteSource source(s.data(), s.size());
  DecodedGrid out;
  Error e = decodeGridRegion(source, r, small, &out);
  EXPECT_EQ(e.status, Status::kResourceLimit) << e.describe();
}

// A crop of a shared grid's first slice: x0 .. x0 + nx, y0 .. y0 + ny (2-D,
// or 1-D when ny is 0).
test::SharedGrid cropOf(const test::SharedGrid& g, uint32_t x0, uint32_t y0, uint32_t nx, uint32_t ny) {
  test::SharedGrid out = g;
  const size_t bytes = sampleSize(g.header.sample_type);
  out.header.num_dims = ny == 0 ? 1 : 2;
  out.header.size_x = nx;
  out.header.size_y = ny == 0 ? 1 : ny;
  out.header.size_z = 1;
  out.samples.clear();
  for (uint32_t y = y0; y < y0 + out.header.size_y; ++y)
    out.samples.insert(out.samples.end(), g.samples.begin() + (y * g.header.size_x + x0) * bytes,
                       g.samples.begin() + (y * g.header.size_x + x0 + nx) * bytes);
  return out;
}

// With reduce_levels K the region is the box's 2^K lattice (spec 11.6), as
// the whole decode reduced by K and cropped gives it; K = 0 too.
TEST(Precincts, ReducedRegionsEqualTheCroppedReducedWhole) {
  struct Case {
    test::SharedGrid grid;
    WaveletEncodeOptions options;
    int precinct_log2;
  };
  std::vector<Case> cases;
  WaveletEncodeOptions step;
  step.step = 5;
  cases.push_back({load("terrain/mt_st_helens_317x460_int16le.raw.zst"), step, 6});
  WaveletEncodeOptions linear = step;
  linear.order = 2;
  cases.push_back({load("terrain/mt_st_helens_317x460_int16le.raw.zst"), linear, 5});
  WaveletEncodeOptions bounded;  // a residual, not applied at a reduced resolution
  bounded.max_error = 2;
  bounded.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  cases.push_back({stHelensWithVoids(), bounded, 4});
  WaveletEncodeOptions two = step;  // fewer levels than K = 3
  two.max_levels = 2;
  cases.push_back({load("terrain/mt_st_helens_317x460_int16le.raw.zst"), two, 5});
  const test::SharedGrid helens = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  cases.push_back({cropOf(helens, 0, 0, 61, 17), step, 4});  // more levels along x than y
  cases.push_back({cropOf(helens, 0, 100, 317, 1), step, 4});  // y has no levels
  cases.push_back({cropOf(helens, 0, 200, 317, 0), step, 4});  // 1-D
  WaveletEncodeOptions quadratic = step;
  quadratic.order = 3;
  cases.push_back({helens, quadratic, 6});
  WaveletEncodeOptions no_levels;  // M = 0 with a residual: decoded at full resolution whatever K
  no_levels.max_levels = 0;
  no_levels.max_error = 3;
  no_levels.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  cases.push_back({helens, no_levels, 5});
  WaveletEncodeOptions volume;
  volume.step = 3;
  volume.max_levels = 3;
  cases.push_back({load("volume/ct_head_vtk_headsq_64x64x93_uint16le.raw.zst"), volume, 4});
  std::mt19937_64 rng(2026);
  for (const Case& c : cases) {
    SCOPED_TRACE("case " + std::to_string(&c - cases.data()));
    const std::vector<uint8_t> blocked = encode(c.grid, c.options, c.precinct_log2);
    const uint32_t n[3] = {c.grid.header.size_x, c.grid.header.size_y, c.grid.header.size_z};
    for (int k = 0; k <= 3; ++k)
      for (int trial = 0; trial < 4; ++trial) {
        GridRegion r;
        for (int a = 0; a < 3; ++a) {
          uint32_t lo = static_cast<uint32_t>(rng() % n[a]), hi = static_cast<uint32_t>(rng() % n[a]);
          if (lo > hi) std::swap(lo, hi);
          r.lo[a] = lo;
          r.hi[a] = std::min(n[a], hi + 1 + (1u << k));
        }
        DecodeOptions options;
        options.reduce_levels = k;
        // What the region is: the whole reduced decode, cropped to its lattice.
        MemoryByteSource b(blocked.data(), blocked.size());
        DecodedGrid whole, want, got;
        Error ea = decodeGrid(blocked.data(), blocked.size(), options, &whole), eb = decodeGridRegion(b, r, options, &got);
        ASSERT_EQ(ea.ok(), eb.ok()) << ea.describe() << " / " << eb.describe();
        if (!ea.ok()) continue;
        regionOutputSize(r, k, want.output_size);
        cropWhole(whole, r, k, &want.samples);
        // (A box without a lattice position is left to the whole decode.)
        if (want.output_size[0] * want.output_size[1] * want.output_size[2] > 0) {
          ASSERT_TRUE(got.region_by_precincts) << "K " << k;
        }
        for (int x = 0; x < 3; ++x) ASSERT_EQ(got.output_size[x], want.output_size[x]);
        ASSERT_EQ(got.samples, want.samples) << "K " << k << " box " << r.lo[0] << "," << r.lo[1] << "," << r.lo[2]
                                             << " .. " << r.hi[0] << "," << r.hi[1] << "," << r.hi[2];
      }
  }
}

}  // namespace
}  // namespace mrsv
