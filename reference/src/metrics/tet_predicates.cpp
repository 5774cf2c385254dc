// Exact orientation with CGAL's filtered kernel; kept in one translation unit
// so that the other tet metrics need not compile CGAL's kernel headers.
#include "metrics/tet_predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace mrsv {

int exactOrientation(const std::array<double, 3>& a, const std::array<double, 3>& b,
                     const std::array<double, 3>& c, const std::array<double, 3>& d) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  // CGAL's orientation(p, q, r, s) is the sign of det[q - p, r - p, s - p].
  return static_cast<int>(CGAL::orientation(Point(a[0], a[1], a[2]), Point(b[0], b[1], b[2]),
                                            Point(c[0], c[1], c[2]), Point(d[0], d[1], d[2])));
}

}  // namespace mrsv
