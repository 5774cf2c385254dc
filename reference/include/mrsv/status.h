// Status codes of the MRSV reference library.
//
// spec: Annex A (status codes). The numbers are stable: they are part of the
// specification and of the conformance suite, never renumbered or reused.
#pragma once

#include <cstdint>
#include <string>

namespace mrsv {

enum class Status : int {
  kOk = 0,

  // File header (spec: 2.2)
  kTruncatedFileHeader = 101,
  kBadSignature = 102,
  kSignatureTransferDamage = 103,
  kUnsupportedVersion = 104,
  kReservedNonZero = 105,

  // Chunk framing (spec: 2.3, 2.4)
  kTruncatedChunkHeader = 110,
  kChunkPastEnd = 111,
  kOversizedChunk = 112,
  kChecksumMismatch = 113,
  kBadChunkType = 114,
  kUnknownCriticalChunk = 115,
  kChunkOrder = 116,
  kBadChunkLength = 117,
  kTrailingBytes = 118,
  kTooManyChunks = 119,

  // Metadata chunk (spec: 2.6)
  kBadMetadata = 130,

  // Grid header and samples (spec: 3)
  kBadGridHeader = 201,
  kUnsupportedCoding = 202,
  kSampleDataMismatch = 203,
  kBadWaveletHeader = 204,
  kBadBandHeader = 205,
  kBadEntropyPayload = 206,
  kBadTiling = 207,      // spec 11.2
  kBadTileIndex = 208,   // spec 11.3

  // Progressive meshes (spec: 6)
  kBadMeshHeader = 301,
  kBadBaseMesh = 302,
  kBadVertexSplit = 303,
  kSplitCountMismatch = 304,

  // Resources and environment (spec: Annex A.3); not caused by a stream rule
  kResourceLimit = 901,
  kIoError = 902,
  kInvalidArgument = 903,
  kUnsupportedProfile = 904,  // a valid stream of a profile (spec 1.6) the decoder does not implement
};

// Stable lower_snake_case name of a status, e.g. "chunk_past_end".
const char* statusName(Status status);

// "E111" style code as printed by the tools and matched by the conformance runner.
std::string statusCode(Status status);

// One decoding or validation failure: what rule, where, and why.
struct Error {
  Status status = Status::kOk;
  uint64_t offset = 0;    // byte offset in the file where the broken rule was detected
  std::string field;      // syntax element or chunk concerned, e.g. "GHDR.size_x"
  std::string message;    // the rule that was broken, one line, no trailing period

  bool ok() const { return status == Status::kOk; }
  // "offset 40: E111 chunk_past_end: GRAW: ..." (no file name; tools prefix it).
  std::string describe() const;
};

}  // namespace mrsv
