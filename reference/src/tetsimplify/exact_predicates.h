// Exact orientation and triangle-intersection predicates on quantised
// positions. Coordinates are in [0, 2^30), so differences fit in 31 bits, a
// 2x2 minor in 63 and a 3x3 determinant in 95: __int128 holds every value
// exactly, and the decoder, doing the same arithmetic, agrees bit for bit.
#pragma once

#include <array>
#include <cstdint>

#include "tetmesh/exact_orient.h"

namespace mrsv::tetsimplify {

using IPoint = std::array<int32_t, 3>;
using Int128 = __int128;

// The sign of det[b - a, c - a, d - a], exactly: the decoder's own predicate
// (tetmesh/exact_orient.h), so the simplifier and the decoder cannot disagree.
using mrsv::orient3d;

inline int sign(Int128 x) { return (x > 0) - (x < 0); }

// Whether the closed segment pq meets the closed triangle abc (abc not
// degenerate).
bool segmentMeetsTriangle(const IPoint& p, const IPoint& q, const IPoint& a, const IPoint& b, const IPoint& c);

// Whether two boundary triangles meet anywhere but in what they share: for
// triangles with no common vertex, whether they meet at all; with one common
// vertex, whether they meet elsewhere; with a common edge, whether they fold
// onto each other (coplanar, on the same side of it). Triangles are given by
// vertex ids (to find what they share) and the positions those ids index.
bool trianglesClash(const std::array<uint32_t, 3>& s, const std::array<uint32_t, 3>& t, const IPoint* positions);

}  // namespace mrsv::tetsimplify
