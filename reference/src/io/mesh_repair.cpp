// Mesh repair and validation; the rules are in mesh_repair.h.
#include "mrsv/mesh_repair.h"

#include <algorithm>
#include <numeric>

namespace mrsv {
namespace {

using Triangle = std::array<uint32_t, 3>;
constexpr uint32_t kNone = UINT32_MAX;
// Corners are numbered 3 * triangle + k in 32 bits, and one more (kNone) is reserved.
constexpr size_t kMaxTriangles = (UINT32_MAX - 1) / 3;

// One traversal of an edge by a triangle: from corner `corner` to the next.
struct EdgeUse {
  uint64_t key;  // (smaller vertex << 32) | larger vertex
  uint32_t triangle;
  uint8_t corner;
  bool ascending;  // traversed from the smaller vertex to the larger
};

// Every edge use, grouped by edge and, within an edge, in triangle order.
std::vector<EdgeUse> edgeUses(const std::vector<Triangle>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(triangles.size() * 3);
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (uint8_t k = 0; k < 3; ++k) {
      uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      uint64_t lo = std::min(a, b), hi = std::max(a, b);
      uses.push_back({lo << 32 | hi, t, k, a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.triangle != y.triangle ? x.triangle < y.triangle
                                                                      : x.corner < y.corner;
  });
  return uses;
}

// Calls f(first, count) for each run of uses of one edge.
template <typename F>
void forEachEdge(const std::vector<EdgeUse>& uses, F f) {
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    f(i, j - i);
    i = j;
  }
}

std::string edgeName(uint64_t key) {
  return "(" + std::to_string(key >> 32) + ", " + std::to_string(key & 0xffffffffu) + ")";
}

struct DisjointSets {
  explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  // The smaller root wins, so a class's root is its first member.
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
  }
  std::vector<uint32_t> parent;
};

uint32_t cornerOf(const Triangle& t, uint32_t vertex) {
  return t[0] == vertex ? 0 : t[1] == vertex ? 1 : 2;
}

// Joins, at both ends of every edge used by exactly two triangles, the two
// triangles' corners there: the classes of corners are then the fans.
DisjointSets fanClasses(const std::vector<Triangle>& triangles, const std::vector<EdgeUse>& uses) {
  DisjointSets corners(triangles.size() * 3);
  forEachEdge(uses, [&](size_t first, size_t count) {
    if (count != 2) return;
    const EdgeUse& u = uses[first];
    const EdgeUse& w = uses[first + 1];
    for (uint32_t vertex : {static_cast<uint32_t>(u.key >> 32), static_cast<uint32_t>(u.key)}) {
      corners.unite(3 * u.triangle + cornerOf(triangles[u.triangle], vertex),
                    3 * w.triangle + cornerOf(triangles[w.triangle], vertex));
    }
  });
  return corners;
}

// Six times the volume a closed component encloses, positive when its
// triangles face outwards. Measured from one of its own vertices, which keeps
// the terms small for a mesh far from the origin (the sum does not depend on
// the point for a closed surface).
double signedVolume(const std::vector<std::array<double, 3>>& positions,
                    const std::vector<uint32_t>& origin, const std::vector<Triangle>& triangles,
                    const std::vector<uint32_t>& members) {
  const std::array<double, 3>& o = positions[origin[triangles[members[0]][0]]];
  double sum = 0;
  for (uint32_t t : members) {
    std::array<double, 3> p[3];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = positions[origin[triangles[t][k]]][c] - o[c];
    sum += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
           p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
           p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  return sum;
}

}  // namespace

size_t dropUnusedVertices(TriangleMesh* mesh, std::vector<uint32_t>* vertex_origin) {
  std::vector<uint32_t> new_index(mesh->positions.size(), kNone);
  for (const Triangle& t : mesh->triangles)
    for (uint32_t v : t) new_index[v] = 0;
  std::vector<uint32_t> origin;
  origin.reserve(mesh->positions.size());
  for (uint32_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] == kNone) continue;
    new_index[v] = static_cast<uint32_t>(origin.size());
    origin.push_back(v);
  }
  const size_t dropped = mesh->positions.size() - origin.size();
  for (Triangle& t : mesh->triangles)
    for (uint32_t& v : t) v = new_index[v];
  const bool with_scalars = mesh->scalars.size() == mesh->positions.size();
  for (size_t i = 0; i < origin.size(); ++i) {
    mesh->positions[i] = mesh->positions[origin[i]];
    if (with_scalars) mesh->scalars[i] = mesh->scalars[origin[i]];
  }
  mesh->positions.resize(origin.size());
  if (with_scalars) mesh->scalars.resize(origin.size());
  if (vertex_origin) *vertex_origin = std::move(origin);
  return dropped;
}

std::string describe(const MeshRepairReport& r) {
  std::string s = std::to_string(r.input_vertices) + " -> " + std::to_string(r.output_vertices) +
                  " vertices, " + std::to_string(r.input_triangles) + " -> " +
                  std::to_string(r.output_triangles) + " triangles";
  auto item = [&s](size_t n, const char* what) {
    if (n) s += "; " + std::to_string(n) + " " + what;
  };
  item(r.unused_vertices, "unused vertices dropped");
  item(r.degenerate_triangles, "degenerate triangles dropped");
  item(r.duplicate_triangles, "duplicate triangles dropped");
  item(r.overfull_edges, "edges with more than two triangles");
  item(r.detached_triangles, "triangles detached from them");
  item(r.inconsistent_edges, "inconsistently oriented edges");
  item(r.flipped_triangles, "triangles flipped");
  item(r.non_orientable_components, "non-orientable components");
  item(r.inward_closed_components, r.inward_closed_turned ? "inside-out closed components turned outward"
                                                          : "inside-out closed components (left as they are)");
  item(r.nonmanifold_vertices, "non-manifold vertices");
  item(r.vertices_added_by_split, "vertices added by splitting them");
  s += "; " + std::to_string(r.boundary_edges) + " boundary edges, " +
       std::to_string(r.components) + (r.components == 1 ? " component" : " components");
  return s;
}

bool repairMesh(TriangleMesh* mesh, const MeshRepairOptions& options, MeshRepairReport* report,
                std::vector<uint32_t>* vertex_origin, std::string* error) {
  MeshRepairReport r;
  r.input_vertices = mesh->positions.size();
  r.input_triangles = mesh->triangles.size();
  const size_t n = mesh->positions.size();
  if (!mesh->scalars.empty() && mesh->scalars.size() != n) {
    *error = std::to_string(mesh->scalars.size()) + " scalars for " + std::to_string(n) + " vertices";
    return false;
  }
  // Every corner may get its own copy of its vertex; all must stay below kNone.
  if (mesh->triangles.size() > kMaxTriangles || n + 3 * mesh->triangles.size() >= kNone) {
    *error = std::to_string(n) + " vertices and " + std::to_string(mesh->triangles.size()) +
             " triangles are too many to repair (vertices + 3 x triangles must stay below 2^32-1)";
    return false;
  }
  for (size_t t = 0; t < mesh->triangles.size(); ++t)
    for (uint32_t v : mesh->triangles[t])
      if (v >= n) {
        *error = "triangle " + std::to_string(t) + ": vertex index " + std::to_string(v) +
                 " is out of range (" + std::to_string(n) + " vertices)";
        return false;
      }

  // Rules 1 and 2. `source` keeps each remaining triangle's input index for messages.
  std::vector<Triangle> triangles;
  std::vector<uint32_t> source;
  {
    std::vector<std::pair<Triangle, uint32_t>> sorted;
    sorted.reserve(mesh->triangles.size());
    for (uint32_t t = 0; t < mesh->triangles.size(); ++t) {
      Triangle tri = mesh->triangles[t];
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
        ++r.degenerate_triangles;
        continue;
      }
      std::sort(tri.begin(), tri.end());
      sorted.push_back({tri, t});
    }
    std::sort(sorted.begin(), sorted.end());
    std::vector<bool> keep(mesh->triangles.size(), false);
    for (size_t i = 0; i < sorted.size(); ++i) {
      if (i > 0 && sorted[i].first == sorted[i - 1].first) {
        ++r.duplicate_triangles;
        continue;
      }
      keep[sorted[i].second] = true;
    }
    for (uint32_t t = 0; t < mesh->triangles.size(); ++t)
      if (keep[t]) {
        triangles.push_back(mesh->triangles[t]);
        source.push_back(t);
      }
  }

  // Vertices appended by rules 3 and 5 copy the vertex named in `origin`.
  std::vector<uint32_t> origin(n);
  std::iota(origin.begin(), origin.end(), 0u);
  auto copyOf = [&origin](uint32_t v) {
    origin.push_back(origin[v]);
    return static_cast<uint32_t>(origin.size() - 1);
  };

  // Rule 3.
  std::vector<EdgeUse> uses = edgeUses(triangles);
  {
    std::string first_overfull;
    std::vector<bool> detach(triangles.size(), false);
    forEachEdge(uses, [&](size_t first, size_t count) {
      if (count <= 2) return;
      ++r.overfull_edges;
      if (first_overfull.empty()) {
        first_overfull = "edge " + edgeName(uses[first].key) + " is used by " +
                         std::to_string(count) + " triangles (";
        for (size_t i = 0; i < count; ++i)
          first_overfull += (i ? ", " : "") + std::to_string(source[uses[first + i].triangle]);
        first_overfull += ")";
      }
      for (size_t i = 2; i < count; ++i) detach[uses[first + i].triangle] = true;
    });
    if (r.overfull_edges && !options.detach_overfull_edges) {
      *error = first_overfull + "; " + std::to_string(r.overfull_edges) +
               " such edges (a manifold edge has at most two; the detach option separates the others)";
      return false;
    }
    for (uint32_t t = 0; t < triangles.size(); ++t) {
      if (!detach[t]) continue;
      ++r.detached_triangles;
      for (uint32_t& v : triangles[t]) v = copyOf(v);
    }
    if (r.detached_triangles) uses = edgeUses(triangles);
  }

  // Rule 4. neighbour[3t+k] is the triangle across t's edge from corner k,
  // and same_way[3t+k] says whether it traverses that edge in t's direction.
  std::vector<uint32_t> neighbour(triangles.size() * 3, kNone);
  std::vector<bool> same_way(triangles.size() * 3, false);
  forEachEdge(uses, [&](size_t first, size_t count) {
    if (count == 1) ++r.boundary_edges;
    if (count != 2) return;
    const EdgeUse& u = uses[first];
    const EdgeUse& w = uses[first + 1];
    neighbour[3 * u.triangle + u.corner] = w.triangle;
    neighbour[3 * w.triangle + w.corner] = u.triangle;
    same_way[3 * u.triangle + u.corner] = same_way[3 * w.triangle + w.corner] =
        u.ascending == w.ascending;
    if (u.ascending == w.ascending) ++r.inconsistent_edges;
  });
  {
    // flip[t]: whether t must be reversed to agree with its component's first triangle.
    std::vector<uint8_t> flip(triangles.size(), 2);  // 2: not reached yet
    std::vector<uint32_t> members;
    for (uint32_t seed = 0; seed < triangles.size(); ++seed) {
      if (flip[seed] != 2) continue;
      ++r.components;
      members.clear();
      members.push_back(seed);
      flip[seed] = 0;
      bool orientable = true;
      bool closed = true;
      for (size_t i = 0; i < members.size(); ++i) {
        uint32_t t = members[i];
        for (uint32_t k = 0; k < 3; ++k) {
          uint32_t o = neighbour[3 * t + k];
          if (o == kNone) {
            closed = false;
            continue;
          }
          uint8_t wanted = static_cast<uint8_t>(flip[t] ^ (same_way[3 * t + k] ? 1 : 0));
          if (flip[o] == 2) {
            flip[o] = wanted;
            members.push_back(o);
          } else if (flip[o] != wanted) {
            orientable = false;
          }
        }
      }
      if (!orientable) {
        ++r.non_orientable_components;
        if (!options.allow_non_orientable) {
          *error = "the component of triangle " + std::to_string(source[seed]) + " (" +
                   std::to_string(members.size()) +
                   " triangles) cannot be oriented consistently (a Moebius band or Klein bottle)";
          return false;
        }
        continue;
      }
      size_t reversed = 0;
      for (uint32_t t : members) reversed += flip[t];
      uint8_t flip_when = reversed * 2 > members.size() ? 0 : 1;
      for (uint32_t t : members)
        if (flip[t] == flip_when) std::swap(triangles[t][1], triangles[t][2]);
      if (closed && signedVolume(mesh->positions, origin, triangles, members) < 0) {
        ++r.inward_closed_components;
        if (options.orient_closed_outward) {
          r.inward_closed_turned = true;
          for (uint32_t t : members) std::swap(triangles[t][1], triangles[t][2]);
          flip_when ^= 1;
        }
      }
      for (uint32_t t : members) r.flipped_triangles += flip[t] == flip_when;
    }
  }

  // Rule 5. Flipping changed no edge's set of triangles, so `uses` still
  // gives the fans (fanClasses() reads the edge's ends from its key, not from
  // corner numbers, which flipping moved).
  {
    DisjointSets corners = fanClasses(triangles, uses);
    std::vector<uint32_t> fan_vertex(triangles.size() * 3, kNone);
    std::vector<uint8_t> claimed(origin.size(), 0);  // 1: taken by a fan, 2: also split
    for (uint32_t t = 0; t < triangles.size(); ++t)
      for (uint32_t k = 0; k < 3; ++k) {
        uint32_t fan = corners.find(3 * t + k);
        uint32_t& v = triangles[t][k];
        if (fan_vertex[fan] == kNone) {
          if (!claimed[v]) {
            claimed[v] = 1;
            fan_vertex[fan] = v;
          } else {
            if (claimed[v] == 1) ++r.nonmanifold_vertices;
            claimed[v] = 2;
            fan_vertex[fan] = copyOf(v);
            ++r.vertices_added_by_split;
          }
        }
        v = fan_vertex[fan];
      }
  }

  // Rule 6, then the vertices in their final order.
  TriangleMesh out;
  out.triangles = std::move(triangles);
  out.positions.resize(origin.size());
  for (size_t v = 0; v < origin.size(); ++v) out.positions[v] = mesh->positions[origin[v]];
  std::vector<uint32_t> kept;
  r.unused_vertices = dropUnusedVertices(&out, &kept);
  // Copies made for detached or split corners are never unused; only input vertices count.
  for (uint32_t& v : kept) v = origin[v];
  if (!mesh->scalars.empty()) {
    out.scalars.resize(kept.size());
    for (size_t v = 0; v < kept.size(); ++v) out.scalars[v] = mesh->scalars[kept[v]];
  }
  r.output_vertices = out.positions.size();
  r.output_triangles = out.triangles.size();
  *mesh = std::move(out);
  if (vertex_origin) *vertex_origin = std::move(kept);
  if (report) *report = r;
  return true;
}

bool isOrientedManifold(const TriangleMesh& mesh, std::string* message) {
  auto fail = [message](const std::string& text) {
    if (message) *message = text;
    return false;
  };
  const size_t n = mesh.positions.size();
  if (mesh.triangles.size() > kMaxTriangles)
    return fail(std::to_string(mesh.triangles.size()) + " triangles (at most " +
                std::to_string(kMaxTriangles) + ")");
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (uint32_t v : tri)
      if (v >= n)
        return fail("triangle " + std::to_string(t) + ": vertex index " + std::to_string(v) +
                    " is out of range (" + std::to_string(n) + " vertices)");
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
      return fail("triangle " + std::to_string(t) + " is degenerate (a repeated vertex)");
  }
  std::vector<EdgeUse> uses = edgeUses(mesh.triangles);
  std::string problem;
  forEachEdge(uses, [&](size_t first, size_t count) {
    if (!problem.empty()) return;
    const EdgeUse& u = uses[first];
    if (count > 2)
      problem = "edge " + edgeName(u.key) + " is used by " + std::to_string(count) + " triangles";
    else if (count == 2 && u.ascending == uses[first + 1].ascending)
      problem = "edge " + edgeName(u.key) + ": triangles " + std::to_string(u.triangle) + " and " +
                std::to_string(uses[first + 1].triangle) +
                " traverse it in the same direction (inconsistent orientation)";
  });
  if (!problem.empty()) return fail(problem);
  DisjointSets corners = fanClasses(mesh.triangles, uses);
  std::vector<uint32_t> first_fan(n, kNone);
  for (uint32_t c = 0; c < mesh.triangles.size() * 3; ++c) {
    uint32_t v = mesh.triangles[c / 3][c % 3];
    uint32_t fan = corners.find(c);
    if (first_fan[v] == kNone) first_fan[v] = fan;
    else if (first_fan[v] != fan)
      return fail("vertex " + std::to_string(v) +
                  " is non-manifold: its triangles form more than one fan (e.g. triangles " +
                  std::to_string(first_fan[v] / 3) + " and " + std::to_string(c / 3) + ")");
  }
  if (message) message->clear();
  return true;
}

}  // namespace mrsv
