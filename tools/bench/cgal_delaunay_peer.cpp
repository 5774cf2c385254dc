// CGAL's 3-D Delaunay triangulation as a timing peer (see cgal_delaunay_peer.h).
#include "cgal_delaunay_peer.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>

namespace mrsv::bench {

double cgalDelaunaySeconds(const std::vector<std::array<double, 3>>& points, size_t* tets) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_3> in;
  in.reserve(points.size());
  for (const auto& p : points) in.emplace_back(p[0], p[1], p[2]);
  const auto start = std::chrono::steady_clock::now();
  CGAL::Delaunay_triangulation_3<Kernel> triangulation(in.begin(), in.end());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  *tets = triangulation.number_of_finite_cells();
  return seconds;
}

}  // namespace mrsv::bench
