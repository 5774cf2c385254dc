// The streaming decoder (stream_decoder.h) on the conformance vectors: fed
// byte by byte, it ends with the one-shot decoder's error and output; finished
// early, with what a one-shot decode of that prefix gives; and the grid levels
// it hands out as the bands arrive equal one-shot decodes at reduced resolution.
#include <gtest/gtest.h>

#include "common/crc32c.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/stream_decoder.h"
#include "test_support.h"

namespace mrsv {
namespace {

StreamContent contentOf(const std::vector<uint8_t>& b) {
  return isProgressiveMeshStream(b.data(), b.size())  ? StreamContent::kMesh
         : isProgressiveTetStream(b.data(), b.size()) ? StreamContent::kTetMesh
                                                      : StreamContent::kGrid;
}

struct Result {
  Error error;
  std::vector<uint8_t> canonical;
  size_t chunks = 0;
};

std::string describe(const Error& e) { return e.ok() ? "ok" : e.describe() + " [" + e.field + "]"; }

Result oneShot(const std::vector<uint8_t>& b, size_t size, const DecodeOptions& options) {
  Result r;
  switch (contentOf(b)) {
    case StreamContent::kMesh: {
      DecodedMesh m;
      r.error = decodeProgressiveMesh(b.data(), size, options, &m);
      if (m.has_mesh) r.canonical = canonicalMeshOutput(m.mesh);
      r.chunks = m.container.chunks.size();
      break;
    }
    case StreamContent::kTetMesh: {
      DecodedTetMesh t;
      r.error = decodeProgressiveTetMesh(b.data(), size, options, &t);
      if (t.has_mesh) r.canonical = canonicalTetMeshOutput(t.mesh);
      r.chunks = t.container.chunks.size();
      break;
    }
    default: {
      DecodedGrid g;
      r.error = decodeGrid(b.data(), size, options, &g);
      r.canonical = canonicalGridOutput(g);
      r.chunks = g.container.chunks.size();
    }
  }
  return r;
}

Result byteByByte(const std::vector<uint8_t>& b, size_t size, const DecodeOptions& options) {
  StreamDecoder d(options, contentOf(b));
  Result r;
  for (size_t i = 0; i < size && r.error.ok(); ++i) r.error = d.feed(&b[i], 1);
  if (r.error.ok()) r.error = d.finish();
  switch (contentOf(b)) {
    case StreamContent::kMesh:
      if (d.mesh().has_mesh) r.canonical = canonicalMeshOutput(d.mesh().mesh);
      r.chunks = d.mesh().container.chunks.size();
      break;
    case StreamContent::kTetMesh:
      if (d.tetMesh().has_mesh) r.canonical = canonicalTetMeshOutput(d.tetMesh().mesh);
      r.chunks = d.tetMesh().container.chunks.size();
      break;
    default:
      r.canonical = canonicalGridOutput(d.grid());
      r.chunks = d.grid().container.chunks.size();
  }
  return r;
}

void expectSame(const Result& a, const Result& b, const std::string& what) {
  EXPECT_EQ(describe(a.error), describe(b.error)) << what;
  EXPECT_TRUE(a.canonical == b.canonical) << what;
  if (a.error.ok()) {
    EXPECT_EQ(a.chunks, b.chunks) << what;
  }
}

TEST(StreamDecoder, ByteByByteEqualsOneShotOnEveryVector) {
  for (const auto& v : test::manifestVectors()) {
    std::vector<uint8_t> bytes = test::readFileOrFail(test::sourcePath("conformance/" + v.file));
    expectSame(byteByByte(bytes, bytes.size(), DecodeOptions{}), oneShot(bytes, bytes.size(), DecodeOptions{}),
               v.file);
  }
}

TEST(StreamDecoder, FinishedEarlyEqualsOneShotOfThePrefix) {
  for (const auto& v : test::manifestVectors()) {
    std::vector<uint8_t> bytes = test::readFileOrFail(test::sourcePath("conformance/" + v.file));
    for (bool partial : {false, true}) {
      DecodeOptions options;
      options.container.allow_partial_tail = partial;
      for (size_t cut : {size_t{0}, size_t{5}, size_t{12}, size_t{17}, bytes.size() / 3, bytes.size() / 2,
                         bytes.size() - 5}) {
        if (cut > bytes.size()) continue;
        expectSame(byteByByte(bytes, cut, options), oneShot(bytes, cut, options),
                   v.file + " cut at " + std::to_string(cut) + (partial ? " (partial tail)" : ""));
      }
    }
  }
}

// Levels as the bands arrive, on every valid wavelet grid vector.
TEST(StreamDecoder, LevelsEqualReducedOneShotDecodes) {
  int compared = 0;
  for (const auto& v : test::manifestVectors()) {
    if (!v.valid) continue;
    std::vector<uint8_t> bytes = test::readFileOrFail(test::sourcePath("conformance/" + v.file));
    if (contentOf(bytes) != StreamContent::kGrid) continue;
    DecodeOptions options;
    options.whole_array_synthesis = true;
    StreamDecoder d(options, StreamContent::kGrid);
    int asked = 1 << 20;
    for (size_t i = 0; i < bytes.size(); ++i) {
      ASSERT_TRUE(d.feed(&bytes[i], 1).ok()) << v.file;
      for (const StreamUnit& unit : d.takeUnits()) {
        const int complete = unit.complete_level;
        if (complete < 1) continue;
        const int coarsest = std::max({d.grid().wavelet.levels[0], d.grid().wavelet.levels[1],
                                       d.grid().wavelet.levels[2]});
        for (int r = std::min(asked - 1, coarsest); r >= complete && r >= 1; --r, asked = r + 1) {
          uint32_t size[3];
          std::vector<uint8_t> samples;
          Error e = d.gridLevelSamples(r, size, &samples);
          ASSERT_TRUE(e.ok()) << v.file << " level " << r << ": " << e.describe();
          DecodeOptions reduced;
          reduced.reduce_levels = r;
          reduced.container.allow_partial_tail = true;
          DecodedGrid whole, prefix;
          ASSERT_TRUE(decodeGrid(bytes.data(), bytes.size(), reduced, &whole).ok()) << v.file;
          ASSERT_TRUE(decodeGrid(bytes.data(), unit.end_offset, reduced, &prefix).ok()) << v.file;
          EXPECT_TRUE(samples == whole.samples && samples == prefix.samples) << v.file << " level " << r;
          EXPECT_EQ(size[0], whole.output_size[0]);
          EXPECT_EQ(size[1], whole.output_size[1]);
          EXPECT_EQ(size[2], whole.output_size[2]);
          ++compared;
          asked = r;
        }
      }
    }
    const Error e = d.finish();
    ASSERT_TRUE(e.ok()) << v.file << ": " << e.describe();
    DecodedGrid full;
    ASSERT_TRUE(decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &full).ok());
    EXPECT_TRUE(d.grid().samples == full.samples) << v.file << " after levels";
  }
  EXPECT_GE(compared, 10);
}

// A caller that moves a PT to coarser levels between chunks (to show them)
// gets the same mesh at the end: each batch applies to the finest level.
TEST(StreamDecoder, TetMeshMovedBetweenChunksEqualsOneShot) {
  int compared = 0;
  for (const auto& v : test::manifestVectors()) {
    if (!v.valid) continue;
    std::vector<uint8_t> bytes = test::readFileOrFail(test::sourcePath("conformance/" + v.file));
    if (contentOf(bytes) != StreamContent::kTetMesh) continue;
    const Result whole = oneShot(bytes, bytes.size(), DecodeOptions{});
    StreamDecoder d(DecodeOptions{}, StreamContent::kTetMesh);
    uint32_t turn = 0;
    for (size_t i = 0; i < bytes.size(); ++i) {
      ASSERT_TRUE(d.feed(&bytes[i], 1).ok()) << v.file;
      ProgressiveTetMesh& mesh = d.tetMesh().mesh;
      if (d.takeUnits().empty() || !d.tetMesh().has_mesh) continue;
      // Down to the base, half way, or up again, in turn.
      const uint32_t finest = mesh.splitsDecoded();
      mesh.setLevel(turn % 3 == 0 ? 0 : turn % 3 == 1 ? finest / 2 : finest);
      ++turn;
    }
    const Error e = d.finish();
    ASSERT_TRUE(e.ok()) << v.file << ": " << e.describe();
    if (!d.tetMesh().has_mesh) continue;  // a prefix without TBAS
    d.tetMesh().mesh.setLevel(d.tetMesh().mesh.splitsDecoded());
    EXPECT_TRUE(canonicalTetMeshOutput(d.tetMesh().mesh) == whole.canonical) << v.file;
    ++compared;
  }
  EXPECT_GT(compared, 0);
}

TEST(StreamDecoder, ErrorIsReportedByTheFeedThatCompletesTheChunk) {
  // bad_checksum: the CRC of a chunk is wrong; the feed giving its last byte fails.
  std::vector<uint8_t> bytes = test::readFileOrFail(test::sourcePath("conformance/vectors/invalid/bad_checksum.mrsv"));
  DecodedGrid g;
  const Error expected = decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &g);
  ASSERT_EQ(expected.status, Status::kChecksumMismatch);
  StreamDecoder d;
  size_t i = 0;
  Error e;
  for (; i < bytes.size() && e.ok(); ++i) e = d.feed(&bytes[i], 1);
  EXPECT_EQ(describe(e), describe(expected));
  EXPECT_EQ(i, expected.offset + 4);  // the CRC's last byte completed the chunk
  EXPECT_EQ(describe(d.feed(bytes.data(), 1)), describe(expected));  // and stays
}

}  // namespace
}  // namespace mrsv

namespace mrsv {
namespace {

// A band that breaks a rule stops the decoding at once (problem()), but a
// later chunk's framing error outranks it (Annex A.2): feed() returns that
// one when its chunk completes, and finish() too, as the one-shot decoder.
TEST(StreamDecoder, ProblemAtItsChunkErrorByAnnexA2) {
  std::vector<uint8_t> bytes =
      test::readFileOrFail(test::sourcePath("conformance/vectors/coded_valid/terrain_cdf97_lossless.mrsv"));
  Container c;
  ASSERT_TRUE(readContainer(bytes.data(), bytes.size(), ContainerOptions{}, &c).ok());
  size_t band = 0;
  while (band < c.chunks.size() && c.chunks[band].chunk_type != kChunkBand) ++band;
  ASSERT_LT(band + 2, c.chunks.size());
  // band_index 7 where 0 is next, with the CRC made right again.
  const ChunkView& b = c.chunks[band];
  bytes[b.payloadOffset()] = 7;
  const uint32_t crc = crc32c(0, bytes.data() + b.offset, kChunkHeaderSize + b.chunk_length);
  for (int i = 0; i < 4; ++i) bytes[b.payloadOffset() + b.chunk_length + i] = static_cast<uint8_t>(crc >> (8 * i));

  for (bool later_crc : {false, true}) {
    std::vector<uint8_t> s = bytes;
    const ChunkView& last = c.chunks.back();
    if (later_crc) s[last.endOffset() - 1] ^= 0x55;
    DecodedGrid g;
    const Error expected = decodeGrid(s.data(), s.size(), DecodeOptions{}, &g);
    EXPECT_EQ(expected.status, later_crc ? Status::kChecksumMismatch : Status::kBadBandHeader);
    StreamDecoder d;
    Error e;
    size_t i = 0;
    for (; i < s.size() && e.ok(); ++i) {
      e = d.feed(&s[i], 1);
      if (i + 1 == b.endOffset()) {
        EXPECT_EQ(d.problem().status, Status::kBadBandHeader);
        EXPECT_EQ(d.problem().offset, b.payloadOffset());
      }
    }
    if (later_crc) {
      EXPECT_EQ(i, last.endOffset());  // returned by the feed completing that chunk
      EXPECT_EQ(describe(e), describe(expected));
    } else {
      EXPECT_TRUE(e.ok());
      EXPECT_EQ(describe(d.finish()), describe(expected));
    }
    for (const StreamUnit& unit : d.takeUnits()) EXPECT_LT(unit.offset, b.offset);  // nothing after it
  }
}

}  // namespace
}  // namespace mrsv
