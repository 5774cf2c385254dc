// The state of a decoded PT stream, shared by the decoder, the level
// switching and the encoder (which runs the decoder's state to code each
// split against exactly what a decoder will hold).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/large_array.h"
#include "mrsv/progressive_tet_mesh.h"
#include "tetmesh/star_link.h"
#include "tetmesh/star_split.h"
#include "tetmesh/tet_complex.h"
#include "tetmesh/vertex_split.h"

namespace mrsv {

// What undoing and redoing split k needs: vt = base_vertex_count + k.
struct PtSplitRecord {
  uint32_t vs = 0;
  uint32_t moved_begin = 0;  // into Impl::moved: the tet slots that went to vt
  uint32_t moved_count = 0;
  uint32_t cut_begin = 0;  // into Impl::cuts: the cut as vertex numbers
  uint32_t cut_length = 0;
  bool closed = false;
};

struct ProgressiveTetMesh::Impl {
  PtHeader header;
  // Positions and scalars of every decoded vertex; tets and incidence of the
  // current level (vertices above it have no tets).
  TetComplex mesh;
  // Reserved whole from THDR, in large pages (common/large_array.h).
  LargeVector<PtSplitRecord> splits;
  LargeVector<uint32_t> moved;
  LargeVector<uint32_t> cuts;
  LargeVector<uint32_t> tet_count_after;  // tets after split k
  uint32_t level = 0;

  // Scratch reused by every split.
  Link link;          // the encoder's
  StarLink star_link;  // the decoder's
  SplitScratch scratch;
  std::vector<uint32_t> walk_local;
  std::vector<uint32_t> region;
  std::vector<uint32_t> walk_global;

  // Sets up the base mesh (mesh.positions, scalars, tets given): incidence
  // and the manifold checks of spec 7.4. Returns "" or the problem.
  std::string startFromBase();
  // Applies a new split at the finest level: vt's position and values are
  // appended to the mesh already; the cut is walk_local (of `link`, the link
  // of vs, a Link or a StarLink). Returns "" or the rule broken; on failure
  // vt is removed again.
  template <class LinkT>
  std::string applyNewSplit(const LinkT& link_of_vs, uint32_t vs, bool closed);
  // The same for the decoder: the cut is walk_local of star_link, the link
  // of vs (applyStarSplit() in place of splitRegion() and applySplit()).
  std::string applyDecodedSplit(uint32_t vs, bool closed);
  // Records the split just applied: region and walk_global hold its moved
  // tets and cut.
  void recordSplit(uint32_t vs, bool closed);
  void redo(uint32_t k);
  void undo(uint32_t k);
  // Starts loading what redo(k) and undo(k) change (lists, moved tets).
  void prefetchSplit(uint32_t k) const;
  // The tet lists of split k's vs and cut vertices, which undoing or redoing
  // it reads: asked for after prefetchSplit(k) has brought their records.
  void prefetchSplitLists(uint32_t k) const;
};

}  // namespace mrsv
