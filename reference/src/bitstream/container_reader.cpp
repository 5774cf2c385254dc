// spec: 2 (container). Framing only; chunk payloads are parsed elsewhere.
#include <cassert>
#include <cstring>

#include "common/byte_reader.h"
#include "common/crc32c.h"
#include "bitstream/container_framer.h"
#include "mrsv/container.h"

namespace mrsv {
namespace {

Error fail(Status status, uint64_t offset, std::string field, std::string message) {
  return Error{status, offset, std::move(field), std::move(message)};
}

// spec: 2.2. The signature's bytes are chosen so that the usual transfer
// damages leave a recognisable pattern; naming the damage tells the user to
// re-transfer in binary mode instead of suspecting the encoder.
Error checkSignature(const uint8_t* data, size_t size) {
  struct Damage {
    uint8_t bytes[12];
    size_t size;
    const char* what;
  };
  static const Damage kDamages[] = {
      {{0x8E, 'M', 'R', 'S', 'V', 0x0A, 0x1A, 0x0A}, 8, "CR LF was converted to LF"},
      {{0x8E, 'M', 'R', 'S', 'V', 0x0D, 0x0D, 0x0A, 0x1A, 0x0D, 0x0A}, 11,
       "LF was converted to CR LF"},
      {{0x0E, 'M', 'R', 'S', 'V', 0x0D, 0x0A, 0x1A, 0x0A}, 9,
       "the high bit of the first byte was cleared (7-bit transfer)"},
  };
  size_t n = size < sizeof kSignature ? size : sizeof kSignature;
  // n == 0 is tested first: memcmp may not be given a null pointer, even for 0 bytes.
  if (n == 0 || std::memcmp(data, kSignature, n) == 0) {
    if (size < kFileHeaderSize)
      return fail(Status::kTruncatedFileHeader, size, "file_header",
                  "file ends after " + std::to_string(size) + " of the 12 file header bytes");
    return {};
  }
  for (const Damage& d : kDamages) {
    if (size >= d.size && std::memcmp(data, d.bytes, d.size) == 0)
      return fail(Status::kSignatureTransferDamage, 0, "file_header.signature",
                  std::string("signature damaged in transfer: ") + d.what);
  }
  if (size >= 5 && std::memcmp(data + 1, "MRSV", 4) == 0)
    return fail(Status::kSignatureTransferDamage, 0, "file_header.signature",
                "signature bytes were altered (text-mode or 7-bit transfer?)");
  return fail(Status::kBadSignature, 0, "file_header.signature", "not an MRSV file");
}

bool isChunkTypeSyntax(const ChunkType& type) {
  for (char ch : type.c)
    if (!((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z'))) return false;
  return true;
}

// spec: 2.5. A content header opens the file and says what the file holds.
bool isContentHeader(const ChunkType& type) {
  return type == kChunkGridHeader || type == kChunkMeshHeader || type == kChunkTetHeader;
}

std::string printable(const ChunkType& type) {
  std::string s;
  for (char ch : type.c) {
    unsigned char u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u < 0x7F) {
      s += ch;
    } else {
      static const char kHex[] = "0123456789abcdef";
      s += "\\x";
      s += kHex[u >> 4];
      s += kHex[u & 15];
    }
  }
  return s;
}

}  // namespace

bool isKnownCriticalChunk(const ChunkType& type) {
  return type == kChunkEnd || type == kChunkGridHeader || type == kChunkGridStored ||
         type == kChunkWaveletHeader || type == kChunkNodataMask || type == kChunkBand ||
         type == kChunkResidual || type == kChunkMeshHeader || type == kChunkBaseMesh ||
         type == kChunkSplits || type == kChunkTetHeader || type == kChunkTetBase || type == kChunkTetSplits ||
         type == kChunkTiling || type == kChunkTileIndex;
}

Error ContainerFramer::fileHeader(const uint8_t* data, size_t size, Container* out) {
  if (Error e = checkSignature(data, size); !e.ok()) return e;
  ByteReader header(data + sizeof kSignature, kFileHeaderSize - sizeof kSignature);
  out->version_major = header.u8();
  out->version_minor = header.u8();
  uint8_t header_flags = header.u8();
  // spec: 2.2. While version_major is 0 every draft is its own format.
  if (out->version_major != kVersionMajor || out->version_minor != kVersionMinor)
    return fail(Status::kUnsupportedVersion, 9, "file_header.version",
                "version " + std::to_string(out->version_major) + "." +
                    std::to_string(out->version_minor) + " is not supported (this decoder reads " +
                    std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor) + ")");
  if (header_flags != 0)
    return fail(Status::kReservedNonZero, 11, "file_header.header_flags",
                "reserved header_flags must be 0");
  return {};
}

Error ContainerFramer::chunkHeader(const uint8_t* header, uint64_t pos, ChunkView* chunk) {
  *chunk = ChunkView{};
  chunk->offset = pos;
  std::memcpy(chunk->chunk_type.c, header, 4);
  ByteReader length_reader(header + 4, 4);
  chunk->chunk_length = length_reader.u32();
  if (!isChunkTypeSyntax(chunk->chunk_type))
    return fail(Status::kBadChunkType, pos, "chunk_type",
                "'" + printable(chunk->chunk_type) + "' is not four ASCII letters");
  if (chunk->chunk_length > kMaxChunkPayload)
    return fail(Status::kOversizedChunk, pos + 4, chunk->chunk_type.str() + ".chunk_length",
                std::to_string(chunk->chunk_length) + " exceeds the limit of " +
                    std::to_string(kMaxChunkPayload) + " bytes");
  return {};
}

Error ContainerFramer::endsInsideChunk(uint64_t pos, uint64_t remaining, const ChunkView& chunk,
                                       Container* out) const {
  if (options_.allow_partial_tail) {
    out->ignored_tail_bytes = remaining;
    return {};
  }
  if (remaining < kChunkHeaderSize)
    return fail(Status::kTruncatedChunkHeader, pos, "chunk",
                "file ends " + std::to_string(remaining) + " bytes into an 8-byte chunk header");
  const uint64_t needed = uint64_t{kChunkHeaderSize} + chunk.chunk_length + kChunkCrcSize;
  return fail(Status::kChunkPastEnd, pos + 4, chunk.chunk_type.str() + ".chunk_length",
              "chunk needs " + std::to_string(needed) + " bytes but only " +
                  std::to_string(remaining) + " remain (file truncated or length damaged)");
}

Error ContainerFramer::trailingBytes(const Container& c, uint64_t extra) {
  return fail(Status::kTrailingBytes, c.end_chunk_offset + kChunkHeaderSize + kChunkCrcSize, "MEND",
              std::to_string(extra) + " bytes follow the MEND chunk");
}

Error ContainerFramer::wholeChunk(const uint8_t* bytes, ChunkView* chunk, Container* out) {
  const uint64_t pos = chunk->offset;
  chunk->payload = bytes + kChunkHeaderSize;
  ByteReader crc_reader(chunk->payload + chunk->chunk_length, 4);
  chunk->chunk_crc = crc_reader.u32();
  if (options_.verify_checksums) {
    uint32_t computed = crc32c(0, bytes, kChunkHeaderSize + chunk->chunk_length);
    if (computed != chunk->chunk_crc)
      return fail(Status::kChecksumMismatch, chunk->payloadOffset() + chunk->chunk_length,
                  chunk->chunk_type.str() + ".chunk_crc", "CRC-32C of the chunk does not match");
  }
  if (++count_ > kMaxChunks)
    return fail(Status::kTooManyChunks, pos, "chunk",
                "more than " + std::to_string(kMaxChunks) + " chunks");

  if (chunk->chunk_type == kChunkEnd) {
    if (chunk->chunk_length != 0)
      return fail(Status::kBadChunkLength, pos + 4, "MEND.chunk_length",
                  "MEND must have an empty payload");
    if (out->chunks.empty())
      return fail(Status::kChunkOrder, pos, "MEND", "a content header must precede MEND");
    out->complete = true;
    out->end_chunk_offset = pos;
    return {};
  }
  if (chunk->chunk_type.critical() && !isKnownCriticalChunk(chunk->chunk_type))
    return fail(Status::kUnknownCriticalChunk, pos, "chunk_type",
                "critical chunk '" + chunk->chunk_type.str() + "' is not known to this decoder");
  bool header_chunk = isContentHeader(chunk->chunk_type);
  if (out->chunks.empty() && !header_chunk)
    return fail(Status::kChunkOrder, pos, chunk->chunk_type.str(),
                "the first chunk must be a content header (GHDR, PHDR or THDR)");
  if (!out->chunks.empty() && header_chunk)
    return fail(Status::kChunkOrder, pos, chunk->chunk_type.str(), "a second content header");
  if (chunk->chunk_type == kChunkMeta) {
    if (seen_meta_) return fail(Status::kChunkOrder, pos, "meta", "more than one meta chunk");
    seen_meta_ = true;
  }
  out->chunks.push_back(*chunk);
  return {};
}

Error readContainer(const uint8_t* data, size_t size, const ContainerOptions& options,
                    Container* out) {
  // API misuse, not bad input: asserted in debug builds (spec Annex A.3).
  assert(out != nullptr && (data != nullptr || size == 0));
  *out = Container{};
  ContainerFramer framer(options);
  if (Error e = framer.fileHeader(data, size < kFileHeaderSize ? size : kFileHeaderSize, out); !e.ok())
    return e;
  uint64_t pos = kFileHeaderSize;
  while (pos < size) {
    const uint64_t remaining = size - pos;
    ChunkView chunk;
    if (remaining < kChunkHeaderSize) return framer.endsInsideChunk(pos, remaining, chunk, out);
    if (Error e = framer.chunkHeader(data + pos, pos, &chunk); !e.ok()) return e;
    if (uint64_t{kChunkHeaderSize} + chunk.chunk_length + kChunkCrcSize > remaining)
      return framer.endsInsideChunk(pos, remaining, chunk, out);
    if (Error e = framer.wholeChunk(data + pos, &chunk, out); !e.ok()) return e;
    pos = chunk.endOffset();
    if (out->complete)
      return pos == size ? Error{} : ContainerFramer::trailingBytes(*out, size - pos);
  }
  return {};  // a clean prefix: every chunk complete, MEND not yet seen
}

}  // namespace mrsv
