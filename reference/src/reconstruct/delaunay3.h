// The Delaunay tetrahedralization of grid points in a box, built by
// incremental insertion (Bowyer-Watson) with exact predicates and symbolic
// perturbation (delaunay3_predicates.h), so that it depends on the point set
// only, never on the insertion order. spec: 10.2 and 10.3.
//
// The hull is closed by an infinite vertex (vertex 0): every face of the
// hull is in one finite tet and one infinite cell, and an infinite cell is in
// conflict with a point beyond its face, or in the face's plane and inside
// its circle (perturbed). The box's 8 corners go in first, so every later
// point lies in the closed box and the hull is the box.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "reconstruct/delaunay3_predicates.h"

namespace mrsv::reconstruct {

class Delaunay3 {
 public:
  static constexpr uint32_t kInfinite = 0;
  static constexpr uint32_t kNone = UINT32_MAX;
  // Largest side: coordinates stay below 2^15 (the predicates' bound).
  static constexpr uint32_t kMaxSide = 1u << 15;

  // Corners v[0..3] (positively oriented; for an infinite cell, as if the
  // infinite vertex were a point beyond its face), n[i] the cell across the
  // face opposite v[i]. A free slot has v[0] == kNone.
  struct Cell {
    uint32_t v[4];
    uint32_t n[4];
  };

  // The tetrahedralization of the 8 corners of [0, sx - 1] x [0, sy - 1] x
  // [0, sz - 1]. False with one line in `error` when a side is below 2 or
  // above kMaxSide.
  bool init(uint32_t sx, uint32_t sy, uint32_t sz, std::string* error);

  // Inserts p (in the closed box, not yet a vertex); the walk to it starts
  // at `start` (kNone: the last cell made). Returns p's vertex.
  uint32_t insert(const GridPoint& p, uint32_t start = kNone);
  // Same, with `cell` a finite cell known to contain p (closed): no walk.
  uint32_t insertInCell(const GridPoint& p, uint32_t cell);
  // A finite cell containing p (closed), or the infinite cell whose face p
  // lies beyond, by a visibility walk from `start`.
  uint32_t locate(const GridPoint& p, uint32_t start) const;

  // The cells the last insert freed and made (slots may be reused: a slot
  // can be in both lists).
  const std::vector<uint32_t>& removedCells() const { return conflict_; }
  const std::vector<uint32_t>& createdCells() const { return created_; }

  size_t cellSlots() const { return cells_.size(); }
  const Cell& cell(uint32_t c) const { return cells_[c]; }
  bool isLive(uint32_t c) const { return cells_[c].v[0] != kNone; }
  bool isFinite(uint32_t c) const {
    const uint32_t* v = cells_[c].v;
    return v[0] != kInfinite && v[1] != kInfinite && v[2] != kInfinite && v[3] != kInfinite;
  }
  uint64_t finiteCellCount() const { return finite_cells_; }
  // Vertices, the infinite one included (vertex 0, no point).
  uint32_t vertexSlots() const { return static_cast<uint32_t>(points_.size()); }
  const GridPoint& point(uint32_t v) const { return points_[v]; }
  // A live cell with v as a corner (vertex v > 0).
  uint32_t cellOf(uint32_t v) const { return vertex_cell_[v]; }

 private:
  bool inConflict(uint32_t c, const GridPoint& p) const;
  uint32_t insertFrom(const GridPoint& p, uint32_t first_conflict);
  uint32_t newCellSlot();

  std::vector<GridPoint> points_;
  std::vector<uint32_t> vertex_cell_;
  std::vector<Cell> cells_;
  std::vector<uint32_t> free_;
  uint64_t finite_cells_ = 0;
  bool small_ = true;  // every coordinate below 2^11: 64-bit insphere
  uint32_t last_cell_ = 0;
  mutable uint32_t walk_seed_ = 0x9e3779b9u;

  // Scratch of one insertion, kept to avoid allocations.
  std::vector<uint32_t> mark_;  // per cell: stamp_ (in conflict) or stamp_ + 1 (not)
  uint32_t stamp_ = 0;
  std::vector<uint32_t> conflict_, created_, stack_;
  struct Boundary {
    uint32_t v[4];
    uint32_t outside;    // the cell across the face
    uint32_t old_cell;   // the conflict cell the face was on
    int slot;            // p's slot in v
  };
  std::vector<Boundary> boundary_;
  struct EdgeEntry {
    uint64_t key;
    uint32_t cell;
    int face;
  };
  std::vector<EdgeEntry> edges_;
};

}  // namespace mrsv::reconstruct
