// Precincts (spec 5.7.6) on real data: the blocks tile every array; a stream
// in precincts decodes to exactly the samples of the same stream without them
// (the blocks change the entropy coding only), prefixes included; lossless
// and error-bounded coding hold with voids; a broken block is reported at its
// offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "common/crc32c.h"
#include "grid/precincts.h"
#include "mrsv/container.h"
#include "mrsv/encode.h"
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

// At a fixed step the quantised coefficients do not depend on the blocks, so
// the samples are the same bits, for every prefix of bands as well.
TEST(Precincts, SameSamplesAsWithoutPrecinctsAtTheSameStep) {
  test::SharedGrid g = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  WaveletEncodeOptions o;
  o.step = 6;
  std::vector<uint8_t> whole = encode(g, o, 0), blocked = encode(g, o, 6);
  EXPECT_NE(whole, blocked);
  EXPECT_EQ(decode(blocked).samples, decode(whole).samples);
  Container a = chunksOf(whole), b = chunksOf(blocked);
  ASSERT_EQ(a.chunks.size(), b.chunks.size());
  for (size_t i = 3; i + 1 < a.chunks.size(); i += 3) {
    std::vector<uint8_t> pa(whole.begin(), whole.begin() + a.chunks[i].endOffset());
    std::vector<uint8_t> pb(blocked.begin(), blocked.begin() + b.chunks[i].endOffset());
    EXPECT_EQ(decode(pb).samples, decode(pa).samples) << "prefix of " << i + 1 << " chunks";
  }
}

TEST(Precincts, LosslessAndBoundedWithVoidsIn2DAnd3D) {
  // St Helens with voids: a lake of 40 x 30 samples across precinct borders
  // and every 97th sample.
  test::SharedGrid helens = load("terrain/mt_st_helens_317x460_int16le.raw.zst");
  helens.header.grid_flags |= kGridFlagHasNodata;
  helens.header.nodata_bits = 0x8000;  // -32768
  const int16_t void_value = -32768;
  for (uint32_t y = 0; y < 460; ++y)
    for (uint32_t x = 0; x < 317; ++x)
      if ((x >= 110 && x < 150 && y >= 240 && y < 270) || (y * 317 + x) % 97 == 0)
        std::memcpy(helens.samples.data() + 2 * (y * 317 + x), &void_value, 2);
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

}  // namespace
}  // namespace mrsv
