// What the mesh benchmarks share (simplify_bench.cpp, mesh_peers.cpp): reading a
// mesh as the PM encoder does, the mesh MRSV's collapses leave, and the CGAL
// Lindstrom-Turk peer. Kept in one place so that both benchmarks run exactly the
// same peer and the same input.
#pragma once

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "simplify/simplify.h"

namespace mrsv::bench {

inline double secondsSince(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Reads and repairs `path` with the default rules, as `mrsv encode` does, so
// that every simplifier starts from the mesh MRSV's encoder starts from.
inline bool readRepairedMesh(const std::string& path, TriangleMesh* mesh, MeshRepairReport* report,
                             std::string* error) {
  std::vector<uint32_t> origin;
  if (!readMeshFile(path, "", mesh, error)) return false;
  if (!repairMesh(mesh, MeshRepairOptions{}, report, &origin, error)) {
    *error = path + ": " + *error;
    return false;
  }
  return true;
}

// The mesh that `result`'s collapses leave of `mesh`, unused vertices dropped.
// Positions are the simplifier's own (not quantised as in a PM stream).
inline TriangleMesh meshAfterCollapses(const TriangleMesh& mesh, const SimplifyResult& result) {
  TriangleMesh out;
  out.positions = mesh.positions;
  std::vector<uint32_t> into(mesh.positions.size());
  for (uint32_t v = 0; v < into.size(); ++v) into[v] = v;
  for (const auto& batch : result.batches) {
    for (const auto& c : batch) {
      into[c.removed] = c.kept;
      out.positions[c.kept] = c.kept_position;
    }
  }
  auto root = [&](uint32_t v) {
    while (into[v] != v) v = into[v];
    return v;
  };
  for (const auto& t : mesh.triangles) {
    const std::array<uint32_t, 3> m = {root(t[0]), root(t[1]), root(t[2])};
    if (m[0] != m[1] && m[1] != m[2] && m[2] != m[0]) out.triangles.push_back(m);
  }
  dropUnusedVertices(&out, nullptr);
  return out;
}

// CGAL 5.5 has no face-count stop predicate (Count_stop_predicate counts edges,
// and edges per face depend on the boundary), so this one asks the mesh: a
// collapse removes one or two faces, so the result has target or target - 1.
struct FaceCountStop {
  uint64_t target;
  template <typename F, typename Profile>
  bool operator()(const F&, const Profile& profile, std::size_t, std::size_t) const {
    return profile.surface_mesh().number_of_faces() <= target;
  }
};

struct LindstromTurkRun {
  double build_seconds = 0.0;     // index arrays -> CGAL::Surface_mesh
  double collapse_seconds = 0.0;  // edge_collapse alone
  int collapses = 0;
  size_t rejected_faces = 0;      // faces Surface_mesh::add_face refused (none on a repaired mesh)
};

// CGAL's edge_collapse with Lindstrom-Turk cost and placement (named explicitly
// rather than relied on as the default), stopped at `target_triangles` faces.
inline LindstromTurkRun simplifyLindstromTurk(const TriangleMesh& mesh, uint64_t target_triangles,
                                              TriangleMesh* out) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  using SurfaceMesh = CGAL::Surface_mesh<Point>;
  namespace SMS = CGAL::Surface_mesh_simplification;
  LindstromTurkRun run;
  auto start = std::chrono::steady_clock::now();
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vs;
  vs.reserve(mesh.positions.size());
  for (const auto& p : mesh.positions) vs.push_back(sm.add_vertex(Point(p[0], p[1], p[2])));
  for (const auto& t : mesh.triangles) {
    if (sm.add_face(vs[t[0]], vs[t[1]], vs[t[2]]) == SurfaceMesh::null_face()) ++run.rejected_faces;
  }
  run.build_seconds = secondsSince(start);
  start = std::chrono::steady_clock::now();
  run.collapses = SMS::edge_collapse(sm, FaceCountStop{target_triangles},
                                     CGAL::parameters::get_cost(SMS::LindstromTurk_cost<SurfaceMesh>())
                                         .get_placement(SMS::LindstromTurk_placement<SurfaceMesh>()));
  run.collapse_seconds = secondsSince(start);

  sm.collect_garbage();
  *out = TriangleMesh{};
  out->positions.reserve(sm.number_of_vertices());
  for (auto v : sm.vertices()) {
    const Point& p = sm.point(v);
    out->positions.push_back({p.x(), p.y(), p.z()});
  }
  // After collect_garbage() the vertex indices are 0..n-1, in the order above.
  for (auto f : sm.faces()) {
    std::array<uint32_t, 3> t{};
    int i = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (i < 3) t[i] = static_cast<uint32_t>(v.idx());
      ++i;
    }
    out->triangles.push_back(t);
  }
  dropUnusedVertices(out, nullptr);
  return run;
}

}  // namespace mrsv::bench
