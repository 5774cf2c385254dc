// spec 9.5: the tile border rule. Each side of the grid is cut by a 1-D
// dyadic subdivision that reads only that side's samples; the quadtree meshes
// the grid without its outermost ring of samples, and each side's strip of the
// ring is closed by zipping the side's cut points to the quadtree's boundary
// vertices. Two tiles sharing a side read the same samples, so they put the
// same vertices on it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "reconstruct/quadtree_error.h"

namespace mrsv::quadtree {

// The cut points 0 = c_0 < ... < c_n = length of the side whose samples are
// grid points first + k * step, k = 0..length (spec 9.5).
std::vector<uint32_t> sideCuts(const ErrorTest& test, uint64_t first, uint64_t step, uint32_t length);

// Triangulates the strip between two parallel grid lines one apart: `outer`
// and `inner` are the vertices on each line (grid points, sorted along the
// line, first and last points joined to the other line's). Appends
// counter-clockwise triangles of grid points to `out`.
void zipStrip(const std::vector<std::array<uint32_t, 2>>& outer,
              const std::vector<std::array<uint32_t, 2>>& inner, int along,
              std::vector<std::array<std::array<uint32_t, 2>, 3>>* out);

}  // namespace mrsv::quadtree
