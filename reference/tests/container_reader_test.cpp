// Framing rules of spec 2, on files built byte by byte (no encoder needed).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "common/crc32c.h"
#include "mrsv/container.h"

namespace mrsv {
namespace {

void putU32(std::vector<uint8_t>* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void addChunk(std::vector<uint8_t>* file, const char* type, const std::vector<uint8_t>& payload) {
  size_t start = file->size();
  file->insert(file->end(), type, type + 4);
  putU32(file, static_cast<uint32_t>(payload.size()));
  file->insert(file->end(), payload.begin(), payload.end());
  putU32(file, crc32c(0, file->data() + start, file->size() - start));
}

std::vector<uint8_t> fileHeader() {
  std::vector<uint8_t> f(kSignature, kSignature + sizeof kSignature);
  f.push_back(kVersionMajor);
  f.push_back(kVersionMinor);
  f.push_back(0);
  return f;
}

// GHDR payload contents are not interpreted by readContainer.
std::vector<uint8_t> sampleFile() {
  std::vector<uint8_t> f = fileHeader();
  addChunk(&f, "GHDR", std::vector<uint8_t>(24, 1));
  addChunk(&f, "meta", {'a', '=', '1', '\n'});
  addChunk(&f, "GRAW", {7});
  addChunk(&f, "MEND", {});
  return f;
}

Error read(const std::vector<uint8_t>& f, Container* c, bool partial = false) {
  ContainerOptions options;
  options.allow_partial_tail = partial;
  return readContainer(f.data(), f.size(), options, c);
}

TEST(ContainerReader, ReadsAValidFile) {
  Container c;
  ASSERT_TRUE(read(sampleFile(), &c).ok());
  EXPECT_TRUE(c.complete);
  ASSERT_EQ(c.chunks.size(), 3u);
  EXPECT_EQ(c.chunks[0].chunk_type, kChunkGridHeader);
  EXPECT_EQ(c.chunks[0].offset, 12u);
  EXPECT_EQ(c.chunks[1].chunk_type, kChunkMeta);
  EXPECT_EQ(c.chunks[2].chunk_length, 1u);
  EXPECT_EQ(c.end_chunk_offset, sampleFile().size() - 12);
}

TEST(ContainerReader, UnknownAncillaryChunkIsListedAndSkipped) {
  std::vector<uint8_t> f = fileHeader();
  addChunk(&f, "GHDR", std::vector<uint8_t>(24, 1));
  addChunk(&f, "xtra", {1, 2, 3});
  addChunk(&f, "MEND", {});
  Container c;
  ASSERT_TRUE(read(f, &c).ok());
  EXPECT_EQ(c.chunks.size(), 2u);
}

struct FramingCase {
  const char* name;
  std::vector<uint8_t> file;
  Status status;
  uint64_t offset;
};

std::vector<FramingCase> framingCases() {
  std::vector<FramingCase> cases;
  std::vector<uint8_t> good = sampleFile();
  auto with = [&](auto edit) {
    std::vector<uint8_t> f = good;
    edit(f);
    return f;
  };
  cases.push_back({"empty file", {}, Status::kTruncatedFileHeader, 0});
  cases.push_back({"signature only", std::vector<uint8_t>(kSignature, kSignature + 9),
                   Status::kTruncatedFileHeader, 9});
  cases.push_back({"png", with([](auto& f) { std::memcpy(f.data(), "\x89PNG\r\n\x1a\n", 8); }),
                   Status::kBadSignature, 0});
  cases.push_back({"crlf to lf", with([](auto& f) { f.erase(f.begin() + 5); }),
                   Status::kSignatureTransferDamage, 0});
  cases.push_back({"lf to crlf", with([](auto& f) {
                     f.insert(f.begin() + 8, 0x0D);
                     f.insert(f.begin() + 5, 0x0D);
                   }),
                   Status::kSignatureTransferDamage, 0});
  cases.push_back({"high bit", with([](auto& f) { f[0] &= 0x7F; }), Status::kSignatureTransferDamage, 0});
  cases.push_back({"version", with([](auto& f) { f[9] = 1; }), Status::kUnsupportedVersion, 9});
  cases.push_back({"flags", with([](auto& f) { f[11] = 4; }), Status::kReservedNonZero, 11});
  cases.push_back({"cut in chunk header", with([](auto& f) { f.resize(12 + 36 + 5); }),
                   Status::kTruncatedChunkHeader, 12 + 36});
  cases.push_back({"cut in payload", with([](auto& f) { f.resize(20); }), Status::kChunkPastEnd, 16});
  cases.push_back({"length past end", with([](auto& f) { f[16] = 200; }), Status::kChunkPastEnd, 16});
  cases.push_back({"oversized", with([](auto& f) { f[19] = 0x80; }), Status::kOversizedChunk, 16});
  cases.push_back({"crc", with([](auto& f) { f[20] ^= 1; }), Status::kChecksumMismatch, 44});
  cases.push_back({"type syntax", with([](auto& f) { f[12 + 2] = '1'; }), Status::kBadChunkType, 12});
  cases.push_back({"trailing", with([](auto& f) { f.push_back(0); }), Status::kTrailingBytes,
                   good.size()});
  std::vector<uint8_t> unknown = fileHeader();
  addChunk(&unknown, "GHDR", std::vector<uint8_t>(24, 1));
  addChunk(&unknown, "QQQQ", {});
  cases.push_back({"unknown critical", unknown, Status::kUnknownCriticalChunk, 48});
  std::vector<uint8_t> meta_first = fileHeader();
  addChunk(&meta_first, "meta", {});
  cases.push_back({"meta first", meta_first, Status::kChunkOrder, 12});
  std::vector<uint8_t> two_meta = fileHeader();
  addChunk(&two_meta, "GHDR", std::vector<uint8_t>(24, 1));
  addChunk(&two_meta, "meta", {});
  addChunk(&two_meta, "meta", {});
  cases.push_back({"two meta", two_meta, Status::kChunkOrder, 60});
  std::vector<uint8_t> mend_first = fileHeader();
  addChunk(&mend_first, "MEND", {});
  cases.push_back({"mend first", mend_first, Status::kChunkOrder, 12});
  std::vector<uint8_t> mend_payload = fileHeader();
  addChunk(&mend_payload, "GHDR", std::vector<uint8_t>(24, 1));
  addChunk(&mend_payload, "MEND", {0});
  cases.push_back({"mend payload", mend_payload, Status::kBadChunkLength, 52});
  return cases;
}

TEST(ContainerReader, EachFramingRuleHasItsCodeAndOffset) {
  for (const FramingCase& c : framingCases()) {
    Container container;
    // An exact-size copy, so AddressSanitizer sees any over-read.
    std::vector<uint8_t> exact(c.file);
    Error e = read(exact, &container);
    EXPECT_EQ(e.status, c.status) << c.name << ": " << e.describe();
    EXPECT_EQ(e.offset, c.offset) << c.name << ": " << e.describe();
    EXPECT_FALSE(e.message.empty()) << c.name;
  }
}

// spec 2.3 rule 6 [R2.3-6]: the (2^20 + 1)-th chunk is 119 at its offset. No
// conformance vector holds it (12 MB of empty chunks), so it is built here.
TEST(ContainerReader, TooManyChunks) {
  std::vector<uint8_t> f = fileHeader();
  addChunk(&f, "GHDR", std::vector<uint8_t>(24, 1));
  std::vector<uint8_t> empty;
  addChunk(&empty, "xtra", {});
  f.reserve(f.size() + (size_t{1} << 20) * empty.size());
  for (uint32_t i = 2; i < kMaxChunks; ++i) f.insert(f.end(), empty.begin(), empty.end());
  const uint64_t last = f.size();
  addChunk(&f, "MEND", {});
  Container container;
  EXPECT_TRUE(read(f, &container).ok());  // 2^20 chunks, MEND the last of them
  f.resize(last);
  f.insert(f.end(), empty.begin(), empty.end());
  addChunk(&f, "MEND", {});
  Error e = read(f, &container);
  EXPECT_EQ(e.status, Status::kTooManyChunks) << e.describe();
  EXPECT_EQ(e.offset, last + empty.size()) << e.describe();
}

TEST(ContainerReader, EveryPrefixIsAPrefixOrATruncationError) {
  std::vector<uint8_t> f = sampleFile();
  std::vector<size_t> boundaries = {12};
  Container whole;
  ASSERT_TRUE(read(f, &whole).ok());
  for (const ChunkView& ch : whole.chunks) boundaries.push_back(ch.endOffset());
  for (size_t n = 0; n < f.size(); ++n) {
    std::vector<uint8_t> prefix(f.begin(), f.begin() + static_cast<long>(n));
    Container c;
    Error strict = read(prefix, &c);
    bool at_boundary = std::find(boundaries.begin(), boundaries.end(), n) != boundaries.end();
    if (at_boundary) {
      EXPECT_TRUE(strict.ok()) << n << ": " << strict.describe();
      EXPECT_FALSE(c.complete);
    } else {
      EXPECT_TRUE(strict.status == Status::kTruncatedFileHeader ||
                  strict.status == Status::kTruncatedChunkHeader ||
                  strict.status == Status::kChunkPastEnd)
          << n << ": " << strict.describe();
    }
    if (n >= kFileHeaderSize) {
      Error lenient = read(prefix, &c, /*partial=*/true);
      EXPECT_TRUE(lenient.ok()) << n << ": " << lenient.describe();
      EXPECT_FALSE(c.complete);
      EXPECT_EQ(c.ignored_tail_bytes + (c.chunks.empty() ? 12 : c.chunks.back().endOffset()), n);
    }
  }
}

TEST(ContainerReader, EverySingleBitFlipIsDetected) {
  const std::vector<uint8_t> good = sampleFile();
  for (size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> f = good;
      f[byte] ^= static_cast<uint8_t>(1u << bit);
      Container c;
      EXPECT_FALSE(read(f, &c).ok()) << "byte " << byte << " bit " << bit;
    }
  }
}

TEST(ContainerReader, ChecksumsCanBeSkippedForFuzzing) {
  std::vector<uint8_t> f = sampleFile();
  f[20] ^= 1;
  ContainerOptions options;
  options.verify_checksums = false;
  Container c;
  EXPECT_TRUE(readContainer(f.data(), f.size(), options, &c).ok());
}

}  // namespace
}  // namespace mrsv
