// The MRSV container: file header and chunk framing. spec: 2.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/limits.h"
#include "mrsv/status.h"

namespace mrsv {

// spec: 2.2 file_header(): signature, version_major, version_minor, header_flags.
constexpr uint8_t kSignature[9] = {0x8E, 'M', 'R', 'S', 'V', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr size_t kFileHeaderSize = 12;
constexpr uint8_t kVersionMajor = 0;
constexpr uint8_t kVersionMinor = 1;

// spec: 2.3 chunk(): chunk_type[4], chunk_length u32, payload, chunk_crc u32.
constexpr size_t kChunkHeaderSize = 8;
constexpr size_t kChunkCrcSize = 4;

// A four-letter chunk type. Upper-case first letter: critical (spec 2.4).
struct ChunkType {
  char c[4];
  bool critical() const { return c[0] >= 'A' && c[0] <= 'Z'; }
  bool operator==(const ChunkType& o) const {
    return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2] && c[3] == o.c[3];
  }
  bool operator!=(const ChunkType& o) const { return !(*this == o); }
  std::string str() const { return std::string(c, 4); }
};

// spec: 2.5, the chunk types of this version.
constexpr ChunkType kChunkEnd{{'M', 'E', 'N', 'D'}};
constexpr ChunkType kChunkMeta{{'m', 'e', 't', 'a'}};
constexpr ChunkType kChunkGridHeader{{'G', 'H', 'D', 'R'}};
constexpr ChunkType kChunkGridStored{{'G', 'R', 'A', 'W'}};
constexpr ChunkType kChunkWaveletHeader{{'W', 'H', 'D', 'R'}};
constexpr ChunkType kChunkNodataMask{{'G', 'M', 'S', 'K'}};
constexpr ChunkType kChunkBand{{'G', 'B', 'N', 'D'}};
constexpr ChunkType kChunkResidual{{'G', 'R', 'E', 'S'}};
constexpr ChunkType kChunkMeshHeader{{'P', 'H', 'D', 'R'}};
constexpr ChunkType kChunkBaseMesh{{'P', 'B', 'A', 'S'}};
constexpr ChunkType kChunkSplits{{'P', 'S', 'P', 'L'}};
constexpr ChunkType kChunkTetHeader{{'T', 'H', 'D', 'R'}};
constexpr ChunkType kChunkTetBase{{'T', 'B', 'A', 'S'}};
constexpr ChunkType kChunkTetSplits{{'T', 'S', 'P', 'L'}};
constexpr ChunkType kChunkTiling{{'T', 'I', 'N', 'F'}};     // spec 11.2
constexpr ChunkType kChunkTileIndex{{'T', 'I', 'D', 'X'}};  // spec 11.3

// True for the critical types this decoder implements.
bool isKnownCriticalChunk(const ChunkType& type);

// One framed chunk, borrowed from the file's bytes.
struct ChunkView {
  ChunkType chunk_type{};
  uint32_t chunk_length = 0;
  uint32_t chunk_crc = 0;        // as stored
  uint64_t offset = 0;           // offset of chunk_type in the file
  const uint8_t* payload = nullptr;
  uint64_t payloadOffset() const { return offset + kChunkHeaderSize; }
  uint64_t endOffset() const { return offset + kChunkHeaderSize + chunk_length + kChunkCrcSize; }
};

struct ContainerOptions {
  // Fuzzing builds may turn this off so the fuzzer reaches the chunk parsers.
  bool verify_checksums = true;
  // Treat an incomplete last chunk as absent instead of an error: the way to
  // read a stream that is still arriving, or a deliberate byte prefix.
  bool allow_partial_tail = false;
};

// The framing of a whole file (or of a prefix of one).
struct Container {
  uint8_t version_major = 0;
  uint8_t version_minor = 0;
  std::vector<ChunkView> chunks;  // in file order, MEND excluded
  bool complete = false;          // MEND was read: the stream is not a prefix
  uint64_t end_chunk_offset = 0;  // offset of MEND when complete
  uint64_t ignored_tail_bytes = 0;  // bytes of an incomplete chunk dropped by allow_partial_tail
};

// Checks the file header and the framing rules of spec 2.2-2.5: signature,
// version, chunk lengths and checksums, chunk type syntax, unknown critical
// chunks, MEND and trailing bytes, the header-chunk-first rule and at most one
// meta chunk. Chunk payloads are not interpreted.
Error readContainer(const uint8_t* data, size_t size, const ContainerOptions& options,
                    Container* out);

// Appends chunks to a file image; finish() adds MEND. Used by encoders.
class ContainerWriter {
 public:
  ContainerWriter();
  void addChunk(const ChunkType& type, const std::vector<uint8_t>& payload);
  // The file so far: a stream prefix (no MEND yet).
  const std::vector<uint8_t>& image() const { return bytes_; }
  // Returns the finished file; the writer is left empty.
  std::vector<uint8_t> finish();

 private:
  std::vector<uint8_t> bytes_;
};

}  // namespace mrsv
