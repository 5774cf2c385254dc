// Tiled grids (spec 11) on real data: round trips, error bounds, region
// decodes against whole decodes, bytes read, threads, prefixes, seams and the
// index's rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "common/crc32c.h"
#include "mrsv/encode.h"
#include "mrsv/tiled_grid.h"
#include "shared_data.h"
#include "test_support.h"

namespace mrsv {
namespace {

// Mt St Helens, 317 x 460 int16 (USGS 30 m DEM): tiles of 100 x 77 leave
// partial tiles on both axes.
test::SharedGrid stHelens() {
  test::SharedGrid g;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/terrain/mt_st_helens_317x460_int16le.raw.zst", &g));
  return g;
}

std::vector<uint8_t> encodeTiled(const test::SharedGrid& g, uint32_t tx, uint32_t ty, uint32_t tz,
                                 WaveletEncodeOptions options, int threads = 1,
                                 WaveletEncodeReport* report = nullptr) {
  TiledEncodeOptions tiled;
  tiled.tile_size[0] = tx;
  tiled.tile_size[1] = ty;
  tiled.tile_size[2] = tz;
  tiled.threads = threads;
  std::vector<uint8_t> stream;
  Error e = encodeTiledGrid(g.header, g.samples, Metadata{}, options, tiled, &stream, report);
  EXPECT_TRUE(e.ok()) << e.describe();
  return stream;
}

DecodedGrid decode(const std::vector<uint8_t>& stream, DecodeOptions options = {}) {
  DecodedGrid out;
  Error e = decodeGrid(stream.data(), stream.size(), options, &out);
  EXPECT_TRUE(e.ok()) << e.describe();
  return out;
}

int16_t at(const std::vector<uint8_t>& s, size_t i) {
  int16_t v;
  std::memcpy(&v, s.data() + 2 * i, 2);
  return v;
}

WaveletEncodeOptions lossless() {
  WaveletEncodeOptions o;
  o.max_error = 0;
  return o;
}

TEST(TiledGrid, LosslessRoundTripWithPartialTiles) {
  test::SharedGrid g = stHelens();
  std::vector<uint8_t> stream = encodeTiled(g, 100, 77, 1, lossless());
  DecodedGrid d = decode(stream);
  EXPECT_EQ(d.header.coding, GridCoding::kTiled);
  EXPECT_EQ(d.tiles_total, 4u * 6u);
  EXPECT_EQ(d.tiles_with_samples, d.tiles_total);
  EXPECT_TRUE(d.has_samples);
  EXPECT_EQ(d.samples, g.samples);
}

TEST(TiledGrid, ErrorBoundOnEverySampleAndThreadsGiveTheSameBytes) {
  test::SharedGrid g = stHelens();
  WaveletEncodeOptions o;
  o.max_error = 3;
  std::vector<uint8_t> one = encodeTiled(g, 64, 64, 1, o, 1);
  std::vector<uint8_t> two = encodeTiled(g, 64, 64, 1, o, 2);
  EXPECT_EQ(one, two);
  DecodeOptions threaded;
  threaded.threads = 2;
  DecodedGrid d = decode(one), d2 = decode(one, threaded);
  EXPECT_EQ(d.samples, d2.samples);
  int worst = 0;
  for (size_t i = 0; i < g.header.sampleCount(); ++i) worst = std::max(worst, std::abs(at(d.samples, i) - at(g.samples, i)));
  EXPECT_LE(worst, 3);
  EXPECT_GT(worst, 0);
}

TEST(TiledGrid, RegionsEqualTheWholeDecodeAndReadOnlyTheirTiles) {
  test::SharedGrid g = stHelens();
  WaveletEncodeOptions o;
  o.bits_per_sample = 2;
  std::vector<uint8_t> stream = encodeTiled(g, 64, 64, 1, o, 2);
  DecodedGrid whole = decode(stream);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    GridRegion r;
    r.lo[0] = rng() % 317;
    r.lo[1] = rng() % 460;
    r.hi[0] = r.lo[0] + 1 + rng() % (317 - r.lo[0]);
    r.hi[1] = r.lo[1] + 1 + rng() % (460 - r.lo[1]);
    MemoryByteSource source(stream.data(), stream.size());
    DecodedGrid region;
    Error e = decodeGridRegion(source, r, DecodeOptions{}, &region);
    ASSERT_TRUE(e.ok()) << e.describe();
    ASSERT_EQ(region.output_size[0], r.hi[0] - r.lo[0]);
    ASSERT_EQ(region.output_size[1], r.hi[1] - r.lo[1]);
    for (uint32_t y = r.lo[1]; y < r.hi[1]; ++y)
      for (uint32_t x = r.lo[0]; x < r.hi[0]; ++x)
        ASSERT_EQ(at(region.samples, (y - r.lo[1]) * region.output_size[0] + (x - r.lo[0])),
                  at(whole.samples, y * 317 + x));
    // Bytes read: everything up to the end of TIDX, then exactly the chunks
    // of the tiles met, and the header of MEND.
    Container c;
    ASSERT_TRUE(readContainer(stream.data(), stream.size(), ContainerOptions{}, &c).ok());
    const ChunkView& tidx = c.chunks[3];
    ASSERT_EQ(tidx.chunk_type, kChunkTileIndex);
    ASSERT_EQ(region.container.chunks.back().offset, tidx.offset);
    TileIndex index;
    ASSERT_TRUE(parseTileIndex(tidx, 5 * 8, &index).ok());
    uint64_t expected = tidx.endOffset();
    for (uint32_t ty = r.lo[1] / 64; ty <= (r.hi[1] - 1) / 64; ++ty)
      for (uint32_t tx = r.lo[0] / 64; tx <= (r.hi[0] - 1) / 64; ++tx) {
        const uint64_t t = ty * 5 + tx;
        for (uint64_t k = index.first[t]; k < index.first[t + 1]; ++k) expected += index.chunk_length[k] + 12;
      }
    const uint64_t meta_and_end = stream.size() - index.end_offset;  // meta is before TINF: only MEND's header
    EXPECT_EQ(source.bytesRead(), expected + std::min<uint64_t>(meta_and_end, kChunkHeaderSize));
    EXPECT_LT(source.bytesRead(), stream.size());
  }
}

TEST(TiledGrid, ReducedRegionsTakeEveryFourthSampleOfTheReducedWhole) {
  test::SharedGrid g = stHelens();
  std::vector<uint8_t> stream = encodeTiled(g, 64, 64, 1, lossless());
  DecodeOptions reduced;
  reduced.reduce_levels = 2;
  DecodedGrid whole = decode(stream, reduced);
  EXPECT_EQ(whole.output_size[0], 80u);  // ceil(317 / 4)
  EXPECT_EQ(whole.output_size[1], 115u);
  GridRegion r;
  r.lo[0] = 30;
  r.lo[1] = 101;
  r.hi[0] = 250;
  r.hi[1] = 333;
  MemoryByteSource source(stream.data(), stream.size());
  DecodedGrid region;
  ASSERT_TRUE(decodeGridRegion(source, r, reduced, &region).ok());
  ASSERT_EQ(region.output_size[0], 55u);  // x = 32, 36, ..., 248
  ASSERT_EQ(region.output_size[1], 58u);  // y = 104, ..., 332
  for (uint32_t j = 0; j < 58; ++j)
    for (uint32_t i = 0; i < 55; ++i)
      ASSERT_EQ(at(region.samples, j * 55 + i), at(whole.samples, (26 + j) * 80 + 8 + i));
}

TEST(TiledGrid, PrefixesDecodeAndGainSamplesOnceEveryTileHasABand) {
  test::SharedGrid g = stHelens();
  WaveletEncodeOptions o;
  o.bits_per_sample = 1;
  o.progressive = true;
  std::vector<uint8_t> stream = encodeTiled(g, 128, 128, 1, o);
  Container c;
  ASSERT_TRUE(readContainer(stream.data(), stream.size(), ContainerOptions{}, &c).ok());
  bool had_samples = false;
  for (const ChunkView& chunk : c.chunks) {
    DecodeOptions options;
    options.container.allow_partial_tail = true;
    DecodedGrid d = decode(std::vector<uint8_t>(stream.begin(), stream.begin() + chunk.endOffset()), options);
    if (had_samples) {
      EXPECT_TRUE(d.has_samples);
    }
    had_samples = d.has_samples;
  }
  EXPECT_TRUE(had_samples);
}

// A lossy tiled grid has no seams: the error next to tile borders is not
// much above the error inside the tiles.
TEST(TiledGrid, NoSeamsAtTileBorders) {
  test::SharedGrid g = stHelens();
  WaveletEncodeOptions o;
  o.bits_per_sample = 1;
  std::vector<uint8_t> stream = encodeTiled(g, 64, 64, 1, o);
  DecodedGrid d = decode(stream);
  double border = 0, inside = 0;
  uint64_t n_border = 0, n_inside = 0;
  for (uint32_t y = 0; y < 460; ++y)
    for (uint32_t x = 0; x < 317; ++x) {
      const double e = at(d.samples, y * 317 + x) - at(g.samples, y * 317 + x);
      const bool near = (x % 64 == 0 || x % 64 == 63 || y % 64 == 0 || y % 64 == 63) && x > 0 && y > 0 &&
                        x < 316 && y < 459;
      (near ? border : inside) += e * e;
      ++(near ? n_border : n_inside);
    }
  const double ratio = std::sqrt(border / n_border) / std::sqrt(inside / n_inside);
  std::printf("RMS error at tile borders / inside: %.3f\n", ratio);
  EXPECT_LT(ratio, 1.5);
}

// The demo's 64 x 64 x 32 crop of the Stanford CT head (demo/data/SOURCES.md).
test::SharedGrid ctHeadCrop() {
  test::SharedGrid g;
  g.header.num_dims = 3;
  g.header.sample_type = SampleType::kUint8;
  g.header.size_x = g.header.size_y = 64;
  g.header.size_z = 32;
  g.samples = test::readFileOrFail(test::sourcePath("demo/data/ct_head_64x64x32_uint8.raw"));
  EXPECT_EQ(g.samples.size(), 64u * 64 * 32);
  return g;
}

TEST(TiledGrid, VolumeBricks) {
  const test::SharedGrid g = ctHeadCrop();
  std::vector<uint8_t> stream = encodeTiled(g, 32, 32, 16, lossless(), 2);
  DecodedGrid d = decode(stream);
  EXPECT_EQ(d.tiles_total, 8u);
  EXPECT_EQ(d.samples, g.samples);
  GridRegion r;
  r.lo[0] = 10; r.lo[1] = 20; r.lo[2] = 5;
  r.hi[0] = 40; r.hi[1] = 33; r.hi[2] = 17;
  MemoryByteSource source(stream.data(), stream.size());
  DecodedGrid region;
  ASSERT_TRUE(decodeGridRegion(source, r, DecodeOptions{}, &region).ok());
  for (uint32_t z = 5; z < 17; ++z)
    for (uint32_t y = 20; y < 33; ++y)
      for (uint32_t x = 10; x < 40; ++x)
        ASSERT_EQ(region.samples[((z - 5) * 13 + (y - 20)) * 30 + (x - 10)], g.samples[(z * 64 + y) * 64 + x]);
}

// Edits one byte of a chunk payload and fixes the chunk's CRC.
std::vector<uint8_t> edited(std::vector<uint8_t> stream, const ChunkView& chunk, size_t at, uint8_t value) {
  stream[chunk.payloadOffset() + at] = value;
  const uint32_t crc = crc32c(0, stream.data() + chunk.offset, kChunkHeaderSize + chunk.chunk_length);
  for (int i = 0; i < 4; ++i) stream[chunk.endOffset() - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  return stream;
}

// DecodeOptions::tile_rows: a whole decode handed over a row of tiles at a
// time gives the whole decode's samples, in order, and its error.
std::vector<uint8_t> decodeByRows(const std::vector<uint8_t>& stream, DecodeOptions options, Error* error,
                                  int* rows, int* axis_seen) {
  std::vector<uint8_t> joined;
  *rows = 0;
  uint32_t next = 0;
  options.tile_rows = [&](int axis, uint32_t first, uint32_t count, std::vector<uint8_t>& samples) {
    EXPECT_EQ(first, next);
    next = first + count;
    *axis_seen = axis;
    ++*rows;
    joined.insert(joined.end(), samples.begin(), samples.end());
    return true;
  };
  DecodedGrid d;
  *error = decodeGrid(stream.data(), stream.size(), options, &d);
  EXPECT_TRUE(d.samples.empty());
  return error->ok() && d.has_samples ? joined : std::vector<uint8_t>{};
}

TEST(TiledGrid, RowsOfTilesGiveTheWholeDecode) {
  test::SharedGrid g = stHelens();
  WaveletEncodeOptions o;
  o.max_error = 3;
  const std::vector<uint8_t> stream = encodeTiled(g, 64, 96, 1, o);
  Error e;
  int rows = 0, axis = -1;
  for (int levels : {0, 2}) {
    DecodeOptions options;
    options.reduce_levels = levels;
    options.threads = 2;
    EXPECT_EQ(decodeByRows(stream, options, &e, &rows, &axis), decode(stream, options).samples) << levels;
    EXPECT_TRUE(e.ok());
    EXPECT_EQ(rows, 5);  // 460 / 96
    EXPECT_EQ(axis, 1);
  }
  // Bricks: rows along z.
  const test::SharedGrid v = ctHeadCrop();
  const std::vector<uint8_t> bricks = encodeTiled(v, 32, 32, 16, lossless());
  EXPECT_EQ(decodeByRows(bricks, DecodeOptions{}, &e, &rows, &axis), v.samples);
  EXPECT_EQ(rows, 2);
  EXPECT_EQ(axis, 2);
  // Two damaged tiles: the error is the whole decode's, the first in file
  // order, though its tile is in the last row (tile chunks come in rounds:
  // every tile's WHDR, then every tile's next chunk...).
  Container c;
  ASSERT_TRUE(readContainer(stream.data(), stream.size(), ContainerOptions{}, &c).ok());
  std::vector<size_t> whdr;
  for (size_t i = 0; i < c.chunks.size(); ++i)
    if (c.chunks[i].chunk_type == kChunkWaveletHeader) whdr.push_back(i);
  ASSERT_EQ(whdr.size(), 25u);
  std::vector<uint8_t> bad = edited(stream, c.chunks[whdr.back()], 0, 9);  // order 9: 204 in the last tile
  const size_t late = whdr.back() + 1;  // tile 0's next chunk, after every WHDR
  ASSERT_EQ(c.chunks[late].chunk_type, kChunkBand);
  bad = edited(bad, c.chunks[late], 0, 0xEE);
  DecodedGrid whole;
  const Error expected = decodeGrid(bad.data(), bad.size(), DecodeOptions{}, &whole);
  ASSERT_FALSE(expected.ok());
  EXPECT_EQ(expected.offset, c.chunks[whdr.back()].payloadOffset());
  EXPECT_TRUE(decodeByRows(bad, DecodeOptions{}, &e, &rows, &axis).empty());
  EXPECT_EQ(e.status, expected.status);
  EXPECT_EQ(e.offset, expected.offset);
  EXPECT_EQ(e.message, expected.message);
}

// Rows are runs of the output: a grid one tile high, or a volume one brick
// deep, is one row (rows along x or y there would interleave in the output);
// a reduced decode whose tiles miss the 2^K lattice is refused here too.
TEST(TiledGrid, RowsAreRunsOfTheOutput) {
  Error e;
  int rows = 0, axis = -1;
  const test::SharedGrid g = stHelens();
  const std::vector<uint8_t> one_high = encodeTiled(g, 64, 460, 1, lossless());
  DecodeOptions two;
  two.threads = 2;
  EXPECT_EQ(decodeByRows(one_high, two, &e, &rows, &axis), g.samples);
  EXPECT_TRUE(e.ok());
  EXPECT_EQ(rows, 1);
  EXPECT_EQ(axis, 1);
  const test::SharedGrid v = ctHeadCrop();
  const std::vector<uint8_t> one_deep = encodeTiled(v, 16, 16, v.header.size_z, lossless());
  EXPECT_EQ(decodeByRows(one_deep, two, &e, &rows, &axis), v.samples);
  EXPECT_EQ(rows, 1);
  EXPECT_EQ(axis, 2);
  const std::vector<uint8_t> odd = encodeTiled(g, 36, 36, 1, lossless());
  DecodeOptions reduced;
  reduced.reduce_levels = 3;
  EXPECT_TRUE(decodeByRows(odd, reduced, &e, &rows, &axis).empty());
  EXPECT_EQ(e.status, Status::kInvalidArgument);
  EXPECT_EQ(rows, 0);
}

TEST(TiledGrid, IndexAndOrderRulesGiveTheirCodes) {
  test::SharedGrid g = stHelens();
  std::vector<uint8_t> stream = encodeTiled(g, 160, 230, 1, lossless());
  Container c;
  ASSERT_TRUE(readContainer(stream.data(), stream.size(), ContainerOptions{}, &c).ok());
  const ChunkView& tinf = c.chunks[2];
  const ChunkView& tidx = c.chunks[3];
  ASSERT_EQ(tinf.chunk_type, kChunkTiling);
  ASSERT_EQ(tidx.chunk_type, kChunkTileIndex);
  DecodedGrid d;
  // A tile chunk length in TIDX that disagrees with the chunk: 208 at the chunk's length.
  std::vector<uint8_t> bad = edited(stream, tidx, 4, static_cast<uint8_t>(tidx.payload[4] + 1));
  Error e = decodeGrid(bad.data(), bad.size(), DecodeOptions{}, &d);
  EXPECT_EQ(e.status, Status::kBadTileIndex);
  EXPECT_EQ(e.offset, c.chunks[4].offset + 4);
  // A tile count of 0: 208 at that count.
  bad = edited(stream, tidx, 1, 0);
  e = decodeGrid(bad.data(), bad.size(), DecodeOptions{}, &d);
  EXPECT_EQ(e.status, Status::kBadTileIndex);
  EXPECT_EQ(e.offset, tidx.payloadOffset() + 1);
  // A tile size of 0: 207 at it.
  bad = edited(stream, tinf, 4, 0);
  bad = edited(bad, tinf, 5, 0);
  e = decodeGrid(bad.data(), bad.size(), DecodeOptions{}, &d);
  EXPECT_EQ(e.status, Status::kBadTiling);
  EXPECT_EQ(e.offset, tinf.payloadOffset() + 4);
}

}  // namespace
}  // namespace mrsv
