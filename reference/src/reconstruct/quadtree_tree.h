// The restricted quadtree of spec 9.3: dyadic cells over a rectangle of grid
// intervals, split with the 2:1 balance of the paper's m to m-2 criterion, and
// the look-up table that triangulates a leaf from the midpoints its neighbours
// need (paper refs [11, 12]). Shared by the max-error and wavelet criteria.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrsv::quadtree {

constexpr uint8_t kAbsent = 0, kLeaf = 1, kSplit = 2;  // cell states

// Sides of a cell, the bits of its midpoint mask: spec 9.3.
enum Side : int { kBottom = 0, kRight = 1, kTop = 2, kLeft = 3 };

// The cells of level l have size 2^l; cell (i, j) of level l covers grid
// intervals [ox + i 2^l, ox + (i+1) 2^l] x [oy + j 2^l, oy + (j+1) 2^l]. Level
// `top` has the single root cell (0, 0), 2^top >= both lengths. A cell is
// inside when it lies within the rectangle [ox, ox + lx] x [oy, oy + ly].
class Tree {
 public:
  void init(uint32_t ox, uint32_t oy, uint32_t lx, uint32_t ly);

  int top() const { return top_; }
  uint32_t originX() const { return ox_; }
  uint32_t originY() const { return oy_; }
  uint32_t cellsX(int l) const { return nx_[l]; }
  uint32_t cellsY(int l) const { return ny_[l]; }
  uint8_t state(int l, uint32_t i, uint32_t j) const { return state_[l][size_t{j} * nx_[l] + i]; }
  void setState(int l, uint32_t i, uint32_t j, uint8_t s) { state_[l][size_t{j} * nx_[l] + i] = s; }
  bool inside(int l, uint32_t i, uint32_t j) const {
    return (uint64_t{i} + 1) << l <= lx_ && (uint64_t{j} + 1) << l <= ly_;
  }
  // spec 9.3: bit s set when the same-level cell across side s is split.
  // Inline: the rounds and the mesh ask it for every leaf.
  int midpointMask(int l, uint32_t i, uint32_t j) const {
    const uint32_t nx = nx_[l];
    const uint8_t* cell = state_[l].data() + (size_t{j} * nx + i);
    const std::ptrdiff_t up = nx;
    return (j > 0 && cell[-up] == kSplit ? 1 << kBottom : 0) | (i + 1 < nx && cell[1] == kSplit ? 1 << kRight : 0) |
           (j + 1 < ny_[l] && cell[up] == kSplit ? 1 << kTop : 0) | (i > 0 && cell[-1] == kSplit ? 1 << kLeft : 0);
  }

  // Splits leaf (l, i, j) and then every coarser leaf the 2:1 balance needs
  // split (spec 9.3). touched(l, i, j) is called for every leaf that is new or
  // whose midpoint mask changed, possibly more than once.
  template <class Touched>
  void split(int l, uint32_t i, uint32_t j, Touched&& touched);

 private:
  uint32_t ox_ = 0, oy_ = 0, lx_ = 0, ly_ = 0;
  int top_ = 0;
  std::vector<uint32_t> nx_, ny_;
  std::vector<std::vector<uint8_t>> state_;
};

// spec 9.3 table 9-1. A leaf's polygon points, counter-clockwise from its
// lower-left corner: 0 BL, 1 B, 2 BR, 3 R, 4 TR, 5 T, 6 TL, 7 L (odd: the edge
// midpoints), and 8 C, its centre, at offsets kPointOffset (in half cell sizes).
constexpr uint8_t kPointOffset[9][2] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2},
                                        {1, 2}, {0, 2}, {0, 1}, {1, 1}};
constexpr uint8_t kCentre = 8;
struct CellTriangles {
  int count;
  uint8_t point[8][3];  // counter-clockwise
};
// The triangles of a leaf with midpoint mask `mask`; `rising` is the diagonal
// choice of mask 0 (BL-TR when true, BR-TL otherwise).
const CellTriangles& cellTriangles(int mask, bool rising);

// spec 9.3 table 9-2: the candidate triangulations of a leaf with midpoint
// mask `mask`, in the order the max-error criterion tries them (9.4): the
// table 9-1 entry first, then every other triangulation of the polygon with
// no flat triangle, then the fan from the centre. `triangle` lists the
// distinct triangles of all candidates; each candidate names its triangles by
// their index there, so that a leaf's test reads each triangle's samples once.
struct CellCandidates {
  std::vector<std::array<uint8_t, 3>> triangle;  // counter-clockwise
  struct Candidate {
    uint8_t count;
    uint8_t triangle[8];  // indices into `triangle`
  };
  std::vector<Candidate> candidate;
};
const CellCandidates& cellCandidates(int mask, bool rising);
inline bool risingDiagonal(uint32_t i, uint32_t j) { return ((i ^ j) & 1) == 0; }

template <class Touched>
void Tree::split(int l, uint32_t i, uint32_t j, Touched&& touched) {
  if (state(l, i, j) != kLeaf || l == 0) return;
  setState(l, i, j, kSplit);
  const int c = l - 1;
  for (uint32_t dj = 0; dj < 2; ++dj)
    for (uint32_t di = 0; di < 2; ++di) {
      const uint32_t ci = 2 * i + di, cj = 2 * j + dj;
      if (ci < nx_[c] && cj < ny_[c]) {
        setState(c, ci, cj, kLeaf);
        touched(c, ci, cj);
      }
    }
  static constexpr int kStep[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  for (int side = 0; side < 4; ++side) {
    const int64_t ni = int64_t{i} + kStep[side][0], nj = int64_t{j} + kStep[side][1];
    if (ni < 0 || nj < 0 || ni >= nx_[l] || nj >= ny_[l]) continue;
    const uint32_t ui = static_cast<uint32_t>(ni), uj = static_cast<uint32_t>(nj);
    // The neighbour's mask gains this side's midpoint.
    if (state(l, ui, uj) == kLeaf) touched(l, ui, uj);
    // 2:1 balance: the parent-sized cell across this side must be split.
    if (l < top_ && (ui >> 1 != i >> 1 || uj >> 1 != j >> 1) && state(l + 1, ui >> 1, uj >> 1) == kLeaf)
      split(l + 1, ui >> 1, uj >> 1, touched);
  }
}

}  // namespace mrsv::quadtree
