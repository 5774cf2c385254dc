#include <gtest/gtest.h>

#include "mrsv/container.h"

namespace mrsv {
namespace {

TEST(ContainerWriter, WhatItWritesReadsBack) {
  ContainerWriter w;
  w.addChunk(kChunkGridHeader, std::vector<uint8_t>(24, 9));
  w.addChunk(ChunkType{{'x', 't', 'r', 'a'}}, {1, 2, 3});
  w.addChunk(kChunkGridStored, std::vector<uint8_t>(1000, 7));
  std::vector<uint8_t> f = w.finish();
  Container c;
  ASSERT_TRUE(readContainer(f.data(), f.size(), ContainerOptions{}, &c).ok());
  ASSERT_EQ(c.chunks.size(), 3u);
  EXPECT_EQ(c.chunks[1].chunk_length, 3u);
  EXPECT_EQ(c.chunks[2].payload[999], 7);
  EXPECT_TRUE(c.complete);
  // A finished writer starts over with a fresh file header.
  std::vector<uint8_t> again = w.finish();
  EXPECT_EQ(again.size(), kFileHeaderSize + kChunkHeaderSize + kChunkCrcSize);
}

}  // namespace
}  // namespace mrsv
