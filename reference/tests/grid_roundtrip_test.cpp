// Stored grids on the real terrains and volumes of ../shared/data.
#include <gtest/gtest.h>

#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "shared_data.h"

namespace mrsv {
namespace {

TEST(StoredGrid, RealDataRoundTripsExactlyAndDeterministically) {
  std::vector<std::string> files = test::sharedGridFiles();
  EXPECT_GE(files.size(), 12u);
  for (const std::string& path : files) {
    test::SharedGrid g;
    if (!test::loadSharedGrid(path, &g)) continue;
    Metadata meta;
    meta.set("provenance", g.name);
    std::vector<uint8_t> first, second;
    ASSERT_TRUE(encodeStoredGrid(g.header, g.samples, meta, &first).ok()) << g.name;
    ASSERT_TRUE(encodeStoredGrid(g.header, g.samples, meta, &second).ok()) << g.name;
    EXPECT_EQ(first, second) << g.name << ": encoder is not deterministic";

    DecodedGrid out;
    Error e = decodeGrid(first.data(), first.size(), DecodeOptions{}, &out);
    ASSERT_TRUE(e.ok()) << g.name << ": " << e.describe();
    EXPECT_TRUE(out.container.complete);
    EXPECT_EQ(out.header.size_x, g.header.size_x);
    EXPECT_EQ(out.header.size_y, g.header.size_y);
    EXPECT_EQ(out.header.size_z, g.header.size_z);
    EXPECT_EQ(out.header.sample_type, g.header.sample_type);
    EXPECT_TRUE(out.samples == g.samples) << g.name;
    ASSERT_NE(out.metadata.find("provenance"), nullptr);
    EXPECT_EQ(*out.metadata.find("provenance"), g.name);
  }
}

TEST(StoredGrid, NodataValueComesBack) {
  GridHeader h;
  h.num_dims = 2;
  h.size_x = 3;
  h.size_y = 2;
  h.sample_type = SampleType::kInt16;
  h.grid_flags = kGridFlagHasNodata;
  h.nodata_bits = 0x8000;  // -32768, the SRTM void
  std::vector<uint8_t> samples(12, 0);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encodeStoredGrid(h, samples, Metadata{}, &bytes).ok());
  DecodedGrid out;
  ASSERT_TRUE(decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &out).ok());
  EXPECT_TRUE(out.header.hasNodata());
  EXPECT_EQ(out.header.nodata_bits, 0x8000u);
}

TEST(StoredGrid, EncoderRefusesWhatTheFormatCannotHold) {
  GridHeader h;
  h.num_dims = 2;
  h.size_x = 4;
  h.size_y = 4;
  std::vector<uint8_t> out;
  EXPECT_EQ(encodeStoredGrid(h, std::vector<uint8_t>(15), Metadata{}, &out).status,
            Status::kInvalidArgument);
  GridHeader zero = h;
  zero.size_y = 0;
  EXPECT_EQ(encodeStoredGrid(zero, {}, Metadata{}, &out).status, Status::kInvalidArgument);
  Metadata bad;
  bad.entries.emplace_back("Bad Key", "x");
  EXPECT_EQ(encodeStoredGrid(h, std::vector<uint8_t>(16), bad, &out).status,
            Status::kInvalidArgument);
  Metadata twice;
  twice.entries.emplace_back("a", "1");
  twice.entries.emplace_back("a", "2");
  EXPECT_EQ(encodeStoredGrid(h, std::vector<uint8_t>(16), twice, &out).status,
            Status::kInvalidArgument);
}

TEST(StoredGrid, DecoderOutputLimitIsEnforcedBeforeCopying) {
  GridHeader h;
  h.num_dims = 1;
  h.size_x = 1000;
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encodeStoredGrid(h, std::vector<uint8_t>(1000, 5), Metadata{}, &bytes).ok());
  DecodeOptions small;
  small.max_output_bytes = 999;
  DecodedGrid out;
  EXPECT_EQ(decodeGrid(bytes.data(), bytes.size(), small, &out).status, Status::kResourceLimit);
}

}  // namespace
}  // namespace mrsv
