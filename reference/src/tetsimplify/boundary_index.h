// A uniform grid over the boundary triangles, for the self-intersection test
// of collapses that move the boundary (paper 6.2). A face is named by its
// corner id 4 t + f (the face of tet t opposite corner f). Entries are only
// ever added: a collapse re-adds the boundary faces it changed, and a query
// drops entries whose face is no longer on the boundary (or is, but has since
// moved and been re-added elsewhere, which the query finds there too). The
// grid is rebuilt when stale entries outnumber live ones, with cells sized to
// the boundary's current mean edge.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tetsimplify/tet_complex.h"

namespace mrsv::tetsimplify {

class BoundaryIndex {
 public:
  void build(const TetComplex& complex);
  // Adds v's boundary faces (after a collapse that changed them).
  void addFacesAround(TetComplex& complex, uint32_t v);
  // Whether triangle `tri` (vertex ids; positions from the complex) clashes
  // with a boundary face of the complex that does not hold `ignored` (the
  // vertex being removed, whose faces are about to change).
  bool clashes(const TetComplex& complex, const std::array<uint32_t, 3>& tri, uint32_t ignored);

 private:
  void add(const TetComplex& complex, uint32_t face);
  template <typename F>
  void forEachCell(const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi, F&& f);

  std::array<int64_t, 3> origin_{};
  int64_t cell_ = 1;
  std::array<int32_t, 3> dims_{};
  std::vector<std::vector<uint32_t>> cells_;
  std::vector<uint32_t> seen_;  // per face id, the query that last tested it
  uint32_t query_ = 0;
  uint64_t entries_ = 0;
  uint64_t entries_at_build_ = 0;
};

}  // namespace mrsv::tetsimplify
