// Exact orientation of four points, for the tet metrics' inside tests and
// their inverted-tet counts (CGAL's filtered predicates: a double evaluation
// with an error bound, exact arithmetic only when that cannot decide).
#pragma once

#include <array>

namespace mrsv {

// The sign (-1, 0, +1) of det[b - a, c - a, d - a], exactly: +1 when the tet
// (a, b, c, d) is positively oriented in TetMesh's sense.
int exactOrientation(const std::array<double, 3>& a, const std::array<double, 3>& b,
                     const std::array<double, 3>& c, const std::array<double, 3>& d);

}  // namespace mrsv
