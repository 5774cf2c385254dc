// spec: 9.3 the restricted quadtree and its look-up table.
#include "reconstruct/quadtree_tree.h"

namespace mrsv::quadtree {

void Tree::init(uint32_t ox, uint32_t oy, uint32_t lx, uint32_t ly) {
  ox_ = ox, oy_ = oy, lx_ = lx, ly_ = ly;
  top_ = 0;
  while ((uint64_t{1} << top_) < lx || (uint64_t{1} << top_) < ly) ++top_;
  nx_.assign(top_ + 1, 0);
  ny_.assign(top_ + 1, 0);
  state_.assign(top_ + 1, {});
  for (int l = 0; l <= top_; ++l) {
    // The cells that start inside the rectangle: ceil(length / 2^l), at least 1.
    nx_[l] = static_cast<uint32_t>(((uint64_t{lx} + (uint64_t{1} << l) - 1) >> l));
    ny_[l] = static_cast<uint32_t>(((uint64_t{ly} + (uint64_t{1} << l) - 1) >> l));
    if (nx_[l] == 0) nx_[l] = 1;
    if (ny_[l] == 0) ny_[l] = 1;
    state_[l].assign(size_t{nx_[l]} * ny_[l], kAbsent);
  }
  state_[top_][0] = kLeaf;
}

uint8_t Tree::across(int l, uint32_t i, uint32_t j, int side) const {
  switch (side) {
    case kBottom: return j == 0 ? kAbsent : state(l, i, j - 1);
    case kRight: return i + 1 >= nx_[l] ? kAbsent : state(l, i + 1, j);
    case kTop: return j + 1 >= ny_[l] ? kAbsent : state(l, i, j + 1);
    default: return i == 0 ? kAbsent : state(l, i - 1, j);
  }
}

int Tree::midpointMask(int l, uint32_t i, uint32_t j) const {
  int mask = 0;
  for (int side = 0; side < 4; ++side)
    if (across(l, i, j, side) == kSplit) mask |= 1 << side;
  return mask;
}

namespace {

// Table 9-1, built once: mask 0 is two triangles on the diagonal; any other
// mask is a fan from its first midpoint in the order B, R, T, L over the
// polygon's present points (a fan from a midpoint never has three collinear
// points: the only points collinear with it are its own edge's corners, which
// are its polygon neighbours).
struct Table {
  CellTriangles entry[2][16];
  Table() {
    for (int rising = 0; rising < 2; ++rising)
      for (int mask = 0; mask < 16; ++mask) {
        CellTriangles& t = entry[rising][mask];
        t = {};
        if (mask == 0) {
          t.count = 2;
          const uint8_t a[2][3] = {{0, 2, 6}, {2, 4, 6}}, b[2][3] = {{0, 2, 4}, {0, 4, 6}};
          for (int k = 0; k < 2; ++k)
            for (int v = 0; v < 3; ++v) t.point[k][v] = rising ? b[k][v] : a[k][v];
          continue;
        }
        int apex = 0;
        while (!(mask >> apex & 1)) ++apex;
        const int start = 2 * apex + 1;
        uint8_t polygon[8];
        int n = 0;
        for (int k = 0; k < 8; ++k) {
          const int p = (start + k) & 7;
          if ((p & 1) == 0 || (mask >> (p >> 1) & 1)) polygon[n++] = static_cast<uint8_t>(p);
        }
        t.count = n - 2;
        for (int k = 1; k + 1 < n; ++k) {
          t.point[k - 1][0] = polygon[0];
          t.point[k - 1][1] = polygon[k];
          t.point[k - 1][2] = polygon[k + 1];
        }
      }
  }
};

}  // namespace

const CellTriangles& cellTriangles(int mask, bool rising) {
  static const Table table;
  return table.entry[rising ? 1 : 0][mask & 15];
}

}  // namespace mrsv::quadtree
