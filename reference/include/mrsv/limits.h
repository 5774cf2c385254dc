// Limits of the MRSV format. spec: Annex B (limits).
//
// A conforming stream stays within every limit; a decoder checks each count
// against these and against the bytes that remain before it allocates.
#pragma once

#include <cstdint>

namespace mrsv {

constexpr uint32_t kMaxChunkPayload = 1u << 30;   // B.1: bytes in one chunk payload
constexpr uint32_t kMaxChunks = 1u << 20;         // B.1: chunks in one file, MEND included
constexpr uint32_t kMaxMetadataPayload = 1u << 16;  // B.2: bytes in the meta payload
constexpr uint32_t kMaxMetadataKey = 64;            // B.2: bytes in one key
constexpr uint32_t kMaxMetadataEntries = 1024;      // B.2
constexpr uint32_t kMaxGridAxis = 1u << 24;         // B.3: samples along one axis
constexpr uint64_t kMaxGridSamples = uint64_t{1} << 32;  // B.3: samples in one grid
constexpr uint32_t kMaxMeshVertices = 1u << 28;     // B.5: PHDR.vertex_count
constexpr uint32_t kMaxBaseTriangles = 1u << 29;    // B.5: PHDR.base_triangle_count
constexpr uint32_t kMaxRingSize = 1024;             // B.5: neighbours of a vertex that is split
constexpr uint8_t kMaxPositionBits = 30;            // B.5: PHDR.position_bits and scalar_bits

// Default for DecodeOptions::max_output_bytes: what the reference decoder
// agrees to allocate for one decoded grid unless the caller says otherwise.
constexpr uint64_t kDefaultMaxOutputBytes = uint64_t{4} << 30;

}  // namespace mrsv
