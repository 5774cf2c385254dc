// Self-intersections of a boundary surface with CGAL's Polygon Mesh
// Processing (box intersection to find candidate pairs, exact predicates to
// decide them).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <boost/iterator/function_output_iterator.hpp>

#include "mrsv/tet_metrics.h"

namespace mrsv {

uint64_t countBoundarySelfIntersections(const TriangleMesh& boundary) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  if (boundary.triangles.empty()) return 0;
  std::vector<Kernel::Point_3> points;
  points.reserve(boundary.positions.size());
  for (const auto& p : boundary.positions) points.emplace_back(p[0], p[1], p[2]);
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(boundary.triangles.size());
  for (const auto& t : boundary.triangles) faces.push_back({t[0], t[1], t[2]});
  // A boundary that is not a 2-manifold (a pinched vertex or an edge in more
  // than two faces) cannot be a Surface_mesh as it is: CGAL duplicates the
  // offending vertices, after which faces meeting only there intersect.
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) PMP::orient_polygon_soup(points, faces);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  uint64_t count = 0;
  // Counted as they come: the pairs of a badly broken mesh need no storage.
  PMP::self_intersections(
      mesh, boost::make_function_output_iterator(
                [&count](const std::pair<Mesh::Face_index, Mesh::Face_index>&) { ++count; }));
  return count;
}

}  // namespace mrsv
