// Progressive meshes: the PM stream (spec 6), decoded into a mesh that moves
// between levels by vertex splits and edge collapses without starting over.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/grid.h"
#include "mrsv/mesh.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"

namespace mrsv {

// spec: 6.2 mesh_header(), the PHDR payload. Field names follow the spec.
constexpr size_t kMeshHeaderSize = 72;
constexpr uint8_t kPlacementEndpoint = 0;  // a split does not move vs
constexpr uint8_t kPlacementFree = 1;      // a split also codes how far vs moves
struct PmHeader {
  uint8_t placement = kPlacementEndpoint;
  uint8_t position_bits = 14;
  uint8_t scalar_bits = 0;  // 0: no per-vertex scalar
  // Placement 1: 0, or 1 to 30, the bits of detail the tangential part of a
  // move of vs keeps per longest edge of its ring (spec 6.7.3 step 1).
  uint8_t move_detail = 0;
  uint32_t vertex_count = 0;
  uint32_t base_vertex_count = 0;
  uint32_t base_triangle_count = 0;
  uint32_t batch_count = 0;
  double origin[3] = {0, 0, 0};
  double position_step = 1;
  double scalar_origin = 0;
  double scalar_step = 0;
  uint32_t splitCount() const { return vertex_count - base_vertex_count; }
};

Error parsePmHeader(const ChunkView& chunk, PmHeader* out);
std::vector<uint8_t> serializePmHeader(const PmHeader& header);

// A decoded progressive mesh: the base mesh and the splits decoded so far,
// shown at one level (the number of splits applied) that can move both ways.
class ProgressiveMesh {
 public:
  ProgressiveMesh();
  ~ProgressiveMesh();
  ProgressiveMesh(ProgressiveMesh&&) noexcept;
  ProgressiveMesh& operator=(ProgressiveMesh&&) noexcept;

  const PmHeader& header() const;
  uint32_t splitsDecoded() const;  // the finest level available
  uint32_t level() const;          // splits applied now
  uint32_t vertexCount() const;
  uint32_t triangleCount() const;
  // Vertex and triangle counts of any level up to splitsDecoded(), without moving.
  uint32_t vertexCountAt(uint32_t level) const;
  uint32_t triangleCountAt(uint32_t level) const;

  // The finest level with at most `max_triangles` triangles (0 when even the
  // base mesh has more): one pass over the splits.
  uint32_t finestLevelWithin(uint64_t max_triangles) const;

  // Moves to `level` (clamped to splitsDecoded()): vertex splits to go finer,
  // edge collapses to go coarser, each O(degree).
  void setLevel(uint32_t level);

  // The current level, dequantised (position = origin + q * position_step).
  TriangleMesh mesh() const;
  // The current level's quantised positions and triangles (spec 6.8).
  const std::vector<std::array<int32_t, 3>>& quantizedPositions() const;
  std::vector<std::array<uint32_t, 3>> triangles() const;
  const std::vector<int32_t>& quantizedScalars() const;

  // The library's own view of the state (decoder and encoder; opaque outside).
  struct Impl;
  Impl& state() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct DecodedMesh {
  Container container;
  Metadata metadata;
  PmHeader header;
  uint32_t batches_decoded = 0;  // complete PSPL chunks among the bytes given
  bool has_mesh = false;         // PBAS was read
  bool stopped_early = false;    // DecodeOptions' stop ended it before the bytes did
  ProgressiveMesh mesh;          // at its finest decoded level
};

// True when the file's first chunk is PHDR (a PM stream rather than a grid).
bool isProgressiveMeshStream(const uint8_t* data, size_t size);

// One-shot decode of a PM stream or a prefix of one (the streaming decoder of
// stream_decoder.h fed all the bytes at once). Never throws; on failure
// returns the first broken rule.
Error decodeProgressiveMesh(const uint8_t* data, size_t size, const DecodeOptions& options,
                            DecodedMesh* out);

// spec: 6.8 canonical output of the mesh at its current level.
std::vector<uint8_t> canonicalMeshOutput(const ProgressiveMesh& mesh);

}  // namespace mrsv
