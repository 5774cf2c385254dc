// The PM stream encoder (spec 6.9, informative): quantises the mesh, replays
// the simplifier's collapses to find the base mesh, and writes the vertex
// splits in decoding order, batch by batch.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"
#include "mrsv/metadata.h"
#include "simplify/simplify.h"

namespace mrsv {

struct PmEncodeOptions {
  uint8_t position_bits = 16;  // per coordinate, over the bounding box's longest side
  uint8_t scalar_bits = 16;    // used when the mesh has scalars
  Placement placement = Placement::kEndpoint;  // as the simplifier ran
  // Free placement: the bits of detail of a move of vs along its plane per
  // longest edge of its ring (spec 6.7.3 step 1; 0: every quantisation step;
  // 4 by decision D33). Endpoint placement writes 0.
  uint8_t move_detail = 4;
};

struct PmEncodeReport {
  uint64_t base_bytes = 0;   // PBAS payload
  uint64_t split_bytes = 0;  // all PSPL payloads
  uint32_t base_vertices = 0, base_triangles = 0, splits = 0, batches = 0;
};

// `mesh` must be the mesh the simplifier ran on. Returns false with one line
// in `error` when the collapses do not fit the mesh (a simplifier bug) or
// the stream would break a limit of Annex B.
bool encodeProgressiveMesh(const TriangleMesh& mesh, const SimplifyResult& collapses,
                           const PmEncodeOptions& options, const Metadata& metadata,
                           std::vector<uint8_t>* out, PmEncodeReport* report, std::string* error);

}  // namespace mrsv
