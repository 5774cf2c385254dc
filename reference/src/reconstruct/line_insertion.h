// 1-D vertex insertion (paper 5.1; spec 8.6): the recursive split of a
// polyline of samples, used for the sides of a grid so that two grids that
// share a side get the same vertices on it.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mrsv/grid_mesh.h"

namespace mrsv::reconstruct {

// `positions` are increasing coordinates along a line and `values` the samples
// there; `kept` marks the positions that are vertices already (the first and
// the last at least). Between each two consecutive kept positions i < j the
// position k in between with the largest error |v_k - (v_i (j - k) + v_j (k - i)) / (j - i)|
// (the smallest k on a tie) is kept when its error exceeds bound_num /
// bound_den, and both halves are treated the same way. Marks what it keeps in
// `kept`.
void insertAlongLine(const std::vector<int64_t>& positions, const std::vector<int64_t>& values,
                     __int128 bound_num, int64_t bound_den, std::vector<uint8_t>* kept);

}  // namespace mrsv::reconstruct
