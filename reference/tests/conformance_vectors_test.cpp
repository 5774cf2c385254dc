// The conformance vectors, decoded in-process: every valid vector decodes,
// every invalid one fails with its code at its offset, and the decoder
// contract holds on every prefix and with a trailing byte.
#include <gtest/gtest.h>

#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "test_support.h"

namespace mrsv {
namespace {

// Grids, PM and PT streams alike: the stream's first chunk says which it is.
struct AnyDecoded {
  bool pm = false, pt = false;
  DecodedGrid grid;
  DecodedMesh mesh;
  DecodedTetMesh tets;
  const Container& container() const { return pt ? tets.container : pm ? mesh.container : grid.container; }
};
Error decodeAny(const uint8_t* data, size_t size, const DecodeOptions& options, AnyDecoded* out) {
  out->pm = isProgressiveMeshStream(data, size);
  out->pt = isProgressiveTetStream(data, size);
  if (out->pm) return decodeProgressiveMesh(data, size, options, &out->mesh);
  if (out->pt) return decodeProgressiveTetMesh(data, size, options, &out->tets);
  return decodeGrid(data, size, options, &out->grid);
}

using test::manifestVectors;
using test::readFileOrFail;
using test::sourcePath;

TEST(ConformanceVectors, ManifestListsVectors) { EXPECT_GE(manifestVectors().size(), 20u); }

TEST(ConformanceVectors, EachDecodesOrFailsAsTheManifestSays) {
  for (const auto& v : manifestVectors()) {
    std::vector<uint8_t> bytes = readFileOrFail(sourcePath("conformance/" + v.file));
    AnyDecoded grid;
    Error e = decodeAny(bytes.data(), bytes.size(), DecodeOptions{}, &grid);
    if (v.valid) {
      EXPECT_TRUE(e.ok()) << v.file << ": " << e.describe();
    } else {
      EXPECT_EQ(static_cast<int>(e.status), v.error) << v.file << ": " << e.describe();
      EXPECT_EQ(e.offset, v.offset) << v.file << ": " << e.describe();
    }
  }
}

// spec 1.6: decodeGrid implements the grid profile, decodeProgressiveMesh the
// mesh profile and decodeProgressiveTetMesh the tet profile; each reports 904
// at the content header for a valid stream of another.
TEST(ConformanceVectors, ADecoderOfOneProfileReports904ForTheOthers) {
  int grids = 0, meshes = 0, tets = 0;
  for (const auto& v : manifestVectors()) {
    if (!v.valid) continue;
    std::vector<uint8_t> bytes = readFileOrFail(sourcePath("conformance/" + v.file));
    if (bytes.size() < kFileHeaderSize + 12) continue;  // no content header: every profile's
    const bool pm = isProgressiveMeshStream(bytes.data(), bytes.size());
    const bool pt = isProgressiveTetStream(bytes.data(), bytes.size());
    std::vector<Error> others;
    if (pm || pt) {
      DecodedGrid grid;
      others.push_back(decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &grid));
    }
    if (!pm) {
      DecodedMesh mesh;
      others.push_back(decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &mesh));
    }
    if (!pt) {
      DecodedTetMesh tet;
      others.push_back(decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &tet));
    }
    ++(pm ? meshes : pt ? tets : grids);
    for (const Error& e : others) {
      EXPECT_EQ(e.status, Status::kUnsupportedProfile) << v.file << ": " << e.describe();
      EXPECT_EQ(e.offset, 12u) << v.file;
    }
  }
  EXPECT_GT(grids, 0);
  EXPECT_GT(meshes, 0);
  EXPECT_GT(tets, 0);
}

TEST(ConformanceVectors, EveryPrefixOfAValidVectorIsHandled) {
  for (const auto& v : manifestVectors()) {
    if (!v.valid) continue;
    std::vector<uint8_t> bytes = readFileOrFail(sourcePath("conformance/" + v.file));
    // Vectors above 4 KiB (the tiled ones, up to 15 KB, whose every prefix
    // decodes all its tiles again) are cut at every chunk boundary and the 3
    // bytes on each side of it, and at every 13th byte: the prefix lengths
    // where framing changes, and a sample of the lengths inside chunks.
    std::vector<bool> near_boundary(bytes.size() + 4, bytes.size() <= 4096);
    Container whole;
    ASSERT_TRUE(readContainer(bytes.data(), bytes.size(), ContainerOptions{}, &whole).ok()) << v.file;
    for (const ChunkView& c : whole.chunks)
      for (uint64_t at : {c.offset, c.offset + kChunkHeaderSize, c.endOffset()})
        for (uint64_t d = at >= 3 ? at - 3 : 0; d <= at + 3 && d < near_boundary.size(); ++d) near_boundary[d] = true;
    for (size_t n = 0; n < bytes.size(); ++n) {
      if (!near_boundary[n] && n % 13 != 0) continue;
      // A fresh exact-size allocation per prefix: over-reads hit the redzone.
      std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<long>(n));
      AnyDecoded grid;
      Error strict = decodeAny(prefix.data(), prefix.size(), DecodeOptions{}, &grid);
      if (!strict.ok()) {
        EXPECT_TRUE(strict.status == Status::kTruncatedFileHeader ||
                    strict.status == Status::kTruncatedChunkHeader ||
                    strict.status == Status::kChunkPastEnd)
            << v.file << " prefix " << n << ": " << strict.describe();
      }
      if (n >= kFileHeaderSize) {
        DecodeOptions lenient;
        lenient.container.allow_partial_tail = true;
        EXPECT_TRUE(decodeAny(prefix.data(), prefix.size(), lenient, &grid).ok())
            << v.file << " prefix " << n;
      }
    }
  }
}

TEST(ConformanceVectors, OneTrailingByteIsRejectedAfterMend) {
  for (const auto& v : manifestVectors()) {
    if (!v.valid) continue;
    std::vector<uint8_t> bytes = readFileOrFail(sourcePath("conformance/" + v.file));
    AnyDecoded grid;
    ASSERT_TRUE(decodeAny(bytes.data(), bytes.size(), DecodeOptions{}, &grid).ok());
    if (!grid.container().complete) continue;
    bytes.push_back(0);
    Error e = decodeAny(bytes.data(), bytes.size(), DecodeOptions{}, &grid);
    EXPECT_EQ(e.status, Status::kTrailingBytes) << v.file;
    EXPECT_EQ(e.offset, bytes.size() - 1) << v.file;
  }
}

}  // namespace
}  // namespace mrsv
