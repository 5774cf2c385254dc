// The PT stream writer (spec 7; 7.9 informative): a quantised tet mesh and
// the batches of half-edge collapses that simplify it, written as a base
// mesh and batches of vertex splits, coarse to fine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/status.h"
#include "mrsv/tet_mesh.h"
#include "tetmesh/tet_complex.h"

namespace mrsv {

// A tet mesh on the integer grid of a PT header: positions in
// [0, 2^position_bits), field values in [0, 2^bits), every tet positive.
struct QuantizedTets {
  PtHeader header;  // position_bits, origin, position_step, fields; counts are the writer's
  std::vector<Point3i> positions;
  std::vector<int32_t> scalars;  // fields.size() per vertex
  std::vector<Tet> tets;
};

// Quantises `mesh` onto 2^position_bits steps over its bounding box (one step
// for every axis) and each field onto 2^field_bits steps over its range (or
// exactly, with step 1, when its values are integers spanning fewer). Fails
// naming the tet when one is not positive after quantisation.
Error quantizeTetMesh(const TetMesh& mesh, int position_bits, int field_bits, QuantizedTets* out);

// Half-edge collapse: vt merges into vs, which keeps its position and values.
struct PtCollapse {
  uint32_t vs, vt;
};

struct PtStreamStats {
  uint64_t header_bytes = 0, base_bytes = 0, split_bytes = 0;
  uint32_t batches = 0, splits = 0;
  uint64_t base_vertices = 0, base_tets = 0;
  // Estimated bits of the splits by what they code: the split flags and the
  // cuts are the connectivity, vt's position and field values the geometry.
  double flag_bits = 0, cut_bits = 0, value_bits = 0;
  // Group and split flags coded (7.7.1): the decoder's decisions before its splits.
  uint64_t flag_decisions = 0;
};

// Writes the PT stream of `mesh` simplified by `batches` (batches[0] is
// collapsed first from the full mesh; the collapses of one batch have
// pairwise disjoint stars, so their splits may be decoded in vertex order).
// Every split is run through the decoder's own state, so a stream that is
// written decodes. Fails naming the batch and collapse that breaks a rule.
Error writePtStream(const QuantizedTets& mesh, const std::vector<std::vector<PtCollapse>>& batches,
                    std::vector<uint8_t>* out, PtStreamStats* stats = nullptr);

}  // namespace mrsv
