// Mesh repair and validation: what turns a mesh as read from a file into the
// oriented 2-manifold (boundaries allowed) that the PM encoder takes.
//
// Definitions. An edge is an unordered pair of vertex indices used by at
// least one triangle. A triangle (a, b, c) traverses its edges a->b, b->c,
// c->a. An edge is manifold when at most two triangles use it, and
// consistently oriented when its two triangles traverse it in opposite
// directions. The fans of a vertex v are the classes of the triangles at v
// under "share an edge (v, x) that exactly these two triangles use"; a vertex
// is manifold when its triangles form one fan (a disk or a half-disk).
//
// repairMesh() applies these rules, in this order:
//  1. Degenerate triangles (a repeated corner index) are dropped.
//  2. Duplicate triangles (the same three vertices, in either orientation)
//     are dropped; the first one in triangle order stays.
//  3. An edge used by more than two triangles is an error naming its two
//     vertex indices, unless `detach_overfull_edges` is set. Then, on every
//     such edge, the two triangles first in triangle order stay and every
//     other triangle is detached: it gets its own copies of its three
//     vertices and so becomes a one-triangle component.
//  4. Orientation, per component (triangles connected across manifold
//     edges): if the triangles can be oriented so that every shared edge is
//     consistently oriented, the triangles that disagree with the larger
//     class are flipped (b and c swapped; on a tie the component's first
//     triangle keeps its orientation). A component that cannot be oriented
//     (a Moebius band, a Klein bottle) is an error, unless
//     `allow_non_orientable` is set, which leaves it as it is. A closed
//     component (no boundary edge) whose triangles then face inwards
//     (negative enclosed volume) is counted, and turned inside out as a
//     whole if `orient_closed_outward` is set. That is off by default: the
//     inner shell of a hollow solid rightly faces inwards.
//  5. Each non-manifold vertex is split into one vertex per fan, all at the
//     same position (and with the same scalar). The fan holding the vertex's
//     first corner in triangle order keeps the index; the others get new
//     vertices appended at the end, in the order their first corners appear.
//  6. Vertices used by no triangle are dropped; the rest keep their order.
// Triangles keep their relative order throughout. After a successful repair
// (without allow_non_orientable) the mesh passes isOrientedManifold().
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv {

struct MeshRepairOptions {
  bool detach_overfull_edges = false;
  bool allow_non_orientable = false;
  bool orient_closed_outward = false;
};

// What repairMesh() found and did; the tools print it with describe().
struct MeshRepairReport {
  size_t input_vertices = 0;
  size_t input_triangles = 0;
  size_t degenerate_triangles = 0;     // dropped (rule 1)
  size_t duplicate_triangles = 0;      // dropped (rule 2)
  size_t overfull_edges = 0;           // edges with more than two triangles (rule 3)
  size_t detached_triangles = 0;       // rule 3 with detach_overfull_edges
  size_t inconsistent_edges = 0;       // shared edges traversed the same way before rule 4
  size_t flipped_triangles = 0;        // rule 4, in total
  size_t components = 0;               // connected across manifold edges
  size_t non_orientable_components = 0;
  size_t inward_closed_components = 0;  // closed, facing inwards after rule 4
  bool inward_closed_turned = false;    // ... and turned outward (orient_closed_outward)
  size_t nonmanifold_vertices = 0;     // vertices with more than one fan (rule 5)
  size_t vertices_added_by_split = 0;  // rule 5
  size_t unused_vertices = 0;          // dropped (rule 6)
  size_t boundary_edges = 0;           // edges with one triangle, in the result
  size_t output_vertices = 0;
  size_t output_triangles = 0;
};

// One line, e.g. "35947 -> 34834 vertices, 69451 -> 69451 triangles; dropped
// 1113 unused vertices; 223 boundary edges, 1 component".
std::string describe(const MeshRepairReport& report);

// Applies rules 1-6 above. `vertex_origin`, if given, receives for each
// output vertex the input vertex it copies (so per-vertex data kept outside
// the mesh can follow); mesh->scalars, when it has one value per vertex,
// follows by itself. On failure returns false, leaves `mesh` unchanged and
// sets `error` to one line naming the broken rule and where (input indices).
bool repairMesh(TriangleMesh* mesh, const MeshRepairOptions& options, MeshRepairReport* report,
                std::vector<uint32_t>* vertex_origin, std::string* error);

// Rule 6 alone: drops the vertices no triangle uses. Returns how many were
// dropped; `vertex_origin` as for repairMesh().
size_t dropUnusedVertices(TriangleMesh* mesh, std::vector<uint32_t>* vertex_origin);

// True when every index is in range, no triangle is degenerate, every edge is
// manifold and consistently oriented, and every vertex is manifold. Unused
// vertices are allowed. Otherwise false, with `message` (if given) naming the
// first problem found.
bool isOrientedManifold(const TriangleMesh& mesh, std::string* message);

}  // namespace mrsv
