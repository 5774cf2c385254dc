// The state of a decoded progressive mesh (spec 6.6): connectivity, quantised
// positions and scalars, and every split decoded so far, so that the level
// can move both ways. Shared by the decoder and the encoder, which replays
// its own stream through it.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/corner_table.h"
#include "pm/pm_coding.h"
#include "mrsv/progressive_mesh.h"

namespace mrsv {

// One vertex split as decoded: enough to apply it again after undoing it.
struct SplitRecord {
  uint32_t vs = 0;
  uint32_t a = 0, b = 0;  // ring positions (spec 6.6.2)
  CornerTable::SplitShape shape;
  std::array<int32_t, 3> vt_position{};
  std::array<int32_t, 3> vs_move{};  // placement 1 only
  int32_t vt_scalar = 0;
};

// spec 6.7.1: where a batch stands while its splits are coded.
struct BatchCursor {
  uint32_t start = 0;    // N_0, the vertex count when the batch began
  int64_t prev_vs = -1;  // the previous split vertex of the batch
  uint32_t stamp = 0;    // marks the vertices this batch has locked
};

struct ProgressiveMesh::Impl {
  PmHeader header;
  CornerTable table;
  std::vector<std::array<int32_t, 3>> positions;
  std::vector<int32_t> scalars;
  std::vector<SplitRecord> splits;
  uint32_t level = 0;  // splits applied
  CornerTable::Ring ring;  // scratch

  // spec 6.7.1: the ring neighbours of a batch's split vertices cannot be
  // split in the same batch and have no split flag (lock_stamp[v] == the
  // batch's stamp).
  std::vector<uint32_t> lock_stamp;
  uint32_t batches_begun = 0;
  // spec 6.7.1: min(neighbour count, 15) of every vertex, the context of its
  // split flag. Kept by codeSplit() as splits are coded (only coding needs it,
  // and coding only goes up), so that no ring is walked for a flag.
  std::vector<uint8_t> flag_context;

  BatchCursor beginBatch() {
    lock_stamp.resize(table.vertexCount(), 0);
    if (flag_context.empty()) {  // the first batch: count the base mesh's neighbours
      flag_context.reserve(splits.capacity() + table.vertexCount());
      for (uint32_t v = 0; v < table.vertexCount(); ++v) {
        table.ring(v, &ring);
        flag_context.push_back(flagContext(ring.neighbours.size()));
      }
    }
    return BatchCursor{table.vertexCount(), -1, ++batches_begun};
  }
  static uint8_t flagContext(size_t neighbours) {
    return static_cast<uint8_t>(std::min<size_t>(neighbours, pm::kFlagContexts - 1));
  }

  // The ring of v into `ring`. The positions (and scalars) of its neighbours
  // are asked into cache at once: the split predicts vt from some of them a
  // little later, after decoding the ring positions, and on a large mesh they
  // are scattered over memory.
  void findRing(uint32_t v) {
    table.ring(v, &ring);
    for (uint32_t w : ring.neighbours) {
      __builtin_prefetch(&positions[w]);
      if (header.scalar_bits) __builtin_prefetch(&scalars[w]);
    }
  }
  // Makes room for the base mesh and `count` splits, each adding one vertex
  // and at most two triangles: decoding then appends without reallocating.
  void reserveForSplits(uint64_t count) {
    const uint64_t vertices = header.base_vertex_count + count;
    splits.reserve(count);
    positions.reserve(vertices);
    if (header.scalar_bits) scalars.reserve(vertices);
    table.reserve(vertices, header.base_triangle_count + 2 * count);
  }
  // Applies splits[level], whose vs has ring `vs_ring` now.
  void applySplit(const CornerTable::Ring& vs_ring);
  // Applies splits[level] (finding the ring first).
  void refineOne() {
    table.ring(splits[level].vs, &ring);
    applySplit(ring);
  }
  // Undoes splits[level - 1].
  void coarsenOne();
};

}  // namespace mrsv
