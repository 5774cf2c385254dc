// Progressive tetrahedral meshes: the PT stream (spec 7), decoded into a tet
// mesh that moves between levels by vertex splits and edge collapses without
// starting over (the paper's hierarchical switching).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/grid.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"
#include "mrsv/tet_mesh.h"

namespace mrsv {

// spec: 7.2 tet_header(), the THDR payload. Field names follow the spec.
constexpr size_t kTetHeaderFixedSize = 56;
constexpr size_t kTetFieldRecordSize = 40;
constexpr int kMaxTetFields = 8;
constexpr size_t kTetFieldNameSize = 16;
// B.6: the link of a vertex that is split has at most this many vertices.
constexpr uint32_t kMaxSplitLinkVertices = 1024;
struct PtField {
  uint8_t bits = 16;  // scalars are integers in [0, 2^bits)
  double origin = 0;
  double step = 1;
  std::string name;  // printable ASCII, at most 16 bytes
};
struct PtHeader {
  uint8_t position_bits = 16;
  uint32_t vertex_count = 0;
  uint32_t base_vertex_count = 0;
  uint32_t base_tet_count = 0;
  uint32_t tet_count = 0;  // tets of the full mesh
  uint32_t batch_count = 0;
  double origin[3] = {0, 0, 0};
  double position_step = 1;
  std::vector<PtField> fields;
  uint32_t splitCount() const { return vertex_count - base_vertex_count; }
};

Error parsePtHeader(const ChunkView& chunk, PtHeader* out);
std::vector<uint8_t> serializePtHeader(const PtHeader& header);

// A decoded progressive tet mesh: the base mesh and the splits decoded so
// far, shown at one level (the number of splits applied) that moves both ways.
class ProgressiveTetMesh {
 public:
  ProgressiveTetMesh();
  ~ProgressiveTetMesh();
  ProgressiveTetMesh(ProgressiveTetMesh&&) noexcept;
  ProgressiveTetMesh& operator=(ProgressiveTetMesh&&) noexcept;

  const PtHeader& header() const;
  uint32_t splitsDecoded() const;  // the finest level available
  uint32_t level() const;          // splits applied now
  uint32_t vertexCount() const;
  uint32_t tetCount() const;
  uint32_t tetCountAt(uint32_t level) const;
  // The finest level with at most `max_tets` tets (0 when even the base has more).
  uint32_t finestLevelWithin(uint64_t max_tets) const;
  // Moves to `level` (clamped to splitsDecoded()): splits to go finer, edge
  // collapses to go coarser, each in time proportional to the vertex's star.
  void setLevel(uint32_t level);

  // The current level, dequantised (position = origin + q * position_step).
  TetMesh mesh() const;
  // The current level's quantised positions, field values (field_count per
  // vertex, vertex-major) and tets (spec 7.8).
  std::vector<std::array<int32_t, 3>> quantizedPositions() const;
  std::vector<int32_t> quantizedScalars() const;
  std::vector<std::array<uint32_t, 4>> tets() const;

  struct Impl;
  Impl& state() { return *impl_; }
  const Impl& state() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct DecodedTetMesh {
  Container container;
  Metadata metadata;
  PtHeader header;
  uint32_t batches_decoded = 0;  // complete TSPL chunks among the bytes given
  bool has_mesh = false;         // TBAS was read
  bool stopped_early = false;    // DecodeOptions' stop ended it before the bytes did
  ProgressiveTetMesh mesh;       // at its finest decoded level
};

// True when the file's first chunk is THDR.
bool isProgressiveTetStream(const uint8_t* data, size_t size);

// One-shot decode of a PT stream or a prefix of one (the streaming decoder of
// stream_decoder.h fed all the bytes at once). Never throws; on failure
// returns the first broken rule.
Error decodeProgressiveTetMesh(const uint8_t* data, size_t size, const DecodeOptions& options,
                               DecodedTetMesh* out);

// spec: 7.8 canonical output of the mesh at its current level.
std::vector<uint8_t> canonicalTetMeshOutput(const ProgressiveTetMesh& mesh);

}  // namespace mrsv
