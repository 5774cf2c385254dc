// Tests of the tet simplifier (issue 21, paper 6.1 and 6.2). Every collapse
// of every batch is replayed on an independent, deliberately plain tet list,
// and after each batch the mesh is checked from scratch: exact orientation,
// a 3-manifold with boundary (faces in one tet or two with opposite
// orientations, vertex links spheres or disks), the Euler characteristic, a
// boundary free of self-intersections (all pairs of boundary triangles that
// share a grid cell), and the independence of the batch's collapses. Each
// collapse is also checked against the PT decoder's split rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "tet_test_meshes.h"
#include "tetsimplify/exact_predicates.h"
#include "tetsimplify/tet_simplify.h"

namespace mrsv {
namespace {

using tetsimplify::IPoint;
using tetsimplify::orient3d;
using tetsimplify::trianglesClash;
using Tet = std::array<uint32_t, 4>;
using Tri = std::array<uint32_t, 3>;

constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

QuantizedTetMesh loadMedit(const std::string& name) {
  QuantizedTetMesh mesh;
  std::string error;
  EXPECT_TRUE(test::readMeditTets(std::string(MRSV_SHARED_DATA) + "/tet/" + name, &mesh, &error)) << error;
  return mesh;
}

QuantizedTetMesh loadCt() {
  QuantizedTetMesh mesh;
  std::string error;
  EXPECT_TRUE(test::paperCtCrop(&mesh, &error)) << error;
  EXPECT_EQ(mesh.tets.size(), 178746u);
  return mesh;
}

// ------------------------------------------------------------ the checker --

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

struct Replay {
  std::vector<IPoint> positions;
  std::vector<Tet> tets;
  std::vector<uint8_t> alive;
  std::vector<std::vector<uint32_t>> star;  // may hold dead tets
  uint64_t live_tets = 0;

  explicit Replay(const QuantizedTetMesh& mesh) : positions(mesh.positions), tets(mesh.tets) {
    alive.assign(tets.size(), 1);
    live_tets = tets.size();
    star.resize(positions.size());
    for (uint32_t t = 0; t < tets.size(); ++t) {
      for (uint32_t v : tets[t]) star[v].push_back(t);
    }
  }
  static bool holds(const Tet& t, uint32_t v) { return std::find(t.begin(), t.end(), v) != t.end(); }
  std::vector<uint32_t> liveStar(uint32_t v) const {
    std::vector<uint32_t> s;
    for (uint32_t t : star[v]) {
      if (alive[t]) s.push_back(t);
    }
    return s;
  }
  void collapse(uint32_t vs, uint32_t vt) {
    for (uint32_t t : liveStar(vt)) {
      if (holds(tets[t], vs)) {
        alive[t] = 0;
        --live_tets;
      } else {
        *std::find(tets[t].begin(), tets[t].end(), vt) = vs;
        star[vs].push_back(t);
      }
    }
    star[vt].clear();
  }
  // Faces of v's star holding v that no other tet of the star holds.
  std::vector<Tri> boundaryFacesAt(uint32_t v) const {
    std::map<Tri, int> count;
    for (uint32_t t : liveStar(v)) {
      for (int f = 0; f < 4; ++f) {
        if (tets[t][f] == v) continue;
        ++count[sorted({tets[t][kFace[f][0]], tets[t][kFace[f][1]], tets[t][kFace[f][2]]})];
      }
    }
    std::vector<Tri> out;
    for (const auto& [tri, n] : count) {
      if (n == 1) out.push_back(tri);
    }
    return out;
  }
};

// The PT decoder's split rule, on the mesh after the collapse: the ring of
// (vs, vt) is a simple cycle in vs's link (vs inside) or a simple path whose
// inner vertices and edges are inside vs's link disk and whose ends are on its
// rim (vs on the boundary).
void expectSplitRule(const Replay& r, uint32_t vs, const std::vector<std::array<uint32_t, 2>>& ring,
                     const std::string& where) {
  std::map<uint32_t, int> degree;
  for (const auto& e : ring) {
    ++degree[e[0]];
    ++degree[e[1]];
  }
  // Connected: walk the edges from one vertex.
  std::map<uint32_t, std::vector<uint32_t>> adj;
  for (const auto& e : ring) {
    adj[e[0]].push_back(e[1]);
    adj[e[1]].push_back(e[0]);
  }
  std::vector<uint32_t> stack = {ring[0][0]};
  std::map<uint32_t, bool> seen = {{ring[0][0], true}};
  while (!stack.empty()) {
    const uint32_t v = stack.back();
    stack.pop_back();
    for (uint32_t u : adj[v]) {
      if (!seen[u]) {
        seen[u] = true;
        stack.push_back(u);
      }
    }
  }
  ASSERT_EQ(seen.size(), degree.size()) << where << ": ring not connected";
  const std::vector<Tri> rim_faces = r.boundaryFacesAt(vs);
  std::map<uint32_t, bool> on_rim;  // vs x is a boundary edge
  std::map<std::array<uint32_t, 2>, bool> rim_edge;  // vs p q is a boundary face
  for (const Tri& f : rim_faces) {
    std::array<uint32_t, 2> o;
    int n = 0;
    for (uint32_t x : f) {
      if (x != vs) o[n++] = x;
    }
    on_rim[o[0]] = on_rim[o[1]] = true;
    rim_edge[{std::min(o[0], o[1]), std::max(o[0], o[1])}] = true;
  }
  if (rim_faces.empty()) {
    for (const auto& [v, d] : degree) ASSERT_EQ(d, 2) << where << ": interior ring is not a simple cycle";
    return;
  }
  int ends = 0;
  for (const auto& [v, d] : degree) {
    ASSERT_TRUE(d == 1 || d == 2) << where << ": ring is not a simple path";
    if (d == 1) {
      ++ends;
      EXPECT_TRUE(on_rim[v]) << where << ": path end " << v << " not on vs's rim";
    } else {
      EXPECT_FALSE(on_rim[v]) << where << ": inner path vertex " << v << " on vs's rim";
    }
  }
  ASSERT_EQ(ends, 2) << where << ": boundary ring is not a path";
  for (const auto& e : ring) {
    const std::array<uint32_t, 2> key = {std::min(e[0], e[1]), std::max(e[0], e[1])};
    EXPECT_FALSE(rim_edge[key]) << where << ": path edge on vs's rim";
  }
}

struct FaceKey {
  Tri v;        // sorted
  bool parity;  // orientation of the outward triple relative to the sorted one
  uint32_t tet;
};

int64_t eulerAndManifold(const Replay& r, std::vector<Tri>* boundary, const std::string& where) {
  std::vector<FaceKey> faces;
  std::vector<std::array<uint32_t, 2>> edges;
  std::vector<uint8_t> used(r.positions.size(), 0);
  uint64_t tets = 0;
  for (uint32_t t = 0; t < r.tets.size(); ++t) {
    if (!r.alive[t]) continue;
    ++tets;
    const Tet& v = r.tets[t];
    for (uint32_t x : v) used[x] = 1;
    for (int f = 0; f < 4; ++f) {
      const Tri o = {v[kFace[f][0]], v[kFace[f][1]], v[kFace[f][2]]};
      const Tri s = sorted(o);
      // Even permutation of the sorted triple: same orientation.
      const int i = int(std::find(o.begin(), o.end(), s[0]) - o.begin());
      faces.push_back({s, o[(i + 1) % 3] == s[1], t});
    }
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) edges.push_back({std::min(v[i], v[j]), std::max(v[i], v[j])});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const FaceKey& a, const FaceKey& b) { return a.v < b.v; });
  uint64_t unique_faces = 0;
  boundary->clear();
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].v == faces[i].v) ++j;
    EXPECT_LE(j - i, 2u) << where << ": a face in more than two tets";
    if (j - i == 2) {
      EXPECT_NE(faces[i].parity, faces[i + 1].parity) << where << ": two tets orient a face alike";
    }
    if (j - i == 1) {
      Tri o = faces[i].v;
      if (!faces[i].parity) std::swap(o[1], o[2]);
      boundary->push_back(o);
    }
    ++unique_faces;
    i = j;
  }
  std::sort(edges.begin(), edges.end());
  const uint64_t unique_edges = std::unique(edges.begin(), edges.end()) - edges.begin();
  const uint64_t vertices = std::accumulate(used.begin(), used.end(), uint64_t(0));
  return int64_t(vertices) - int64_t(unique_edges) + int64_t(unique_faces) - int64_t(tets);
}

// Vertex links: connected, every link edge in one or two link triangles,
// Euler characteristic 2 when closed and 1 with a rim.
void expectLinks(const Replay& r, const std::vector<uint32_t>& vertices, const std::string& where) {
  std::vector<std::array<uint32_t, 2>> edges;
  std::vector<uint32_t> verts, parent;
  for (uint32_t v : vertices) {
    const std::vector<uint32_t> s = r.liveStar(v);
    if (s.empty()) continue;
    edges.clear();
    verts.clear();
    for (uint32_t t : s) {
      std::array<uint32_t, 3> o;
      int n = 0;
      for (uint32_t x : r.tets[t]) {
        if (x != v) o[n++] = x;
      }
      for (int i = 0; i < 3; ++i) {
        verts.push_back(o[i]);
        edges.push_back({std::min(o[i], o[(i + 1) % 3]), std::max(o[i], o[(i + 1) % 3])});
      }
    }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    std::sort(edges.begin(), edges.end());
    auto index = [&](uint32_t x) { return uint32_t(std::lower_bound(verts.begin(), verts.end(), x) - verts.begin()); };
    parent.resize(verts.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    size_t unique_edges = 0, components = verts.size();
    int rim = 0;
    for (size_t i = 0; i < edges.size();) {
      size_t j = i + 1;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      ASSERT_LE(j - i, 2u) << where << ": vertex " << v << "'s link is not a surface";
      rim += j - i == 1;
      ++unique_edges;
      const uint32_t a = find(index(edges[i][0])), b = find(index(edges[i][1]));
      if (a != b) {
        parent[a] = b;
        --components;
      }
      i = j;
    }
    EXPECT_EQ(components, 1u) << where << ": vertex " << v << "'s link is not connected";
    const int64_t euler = int64_t(verts.size()) - int64_t(unique_edges) + int64_t(s.size());
    EXPECT_EQ(euler, rim ? 1 : 2) << where << ": vertex " << v << "'s link is neither a sphere nor a disk";
  }
}

// All pairs of boundary triangles sharing a cell of a uniform grid (each pair
// tested once, in the lowest cell both cover).
uint64_t boundaryClashes(const Replay& r, const std::vector<Tri>& boundary) {
  if (boundary.empty()) return 0;
  std::array<int64_t, 3> lo = {INT64_MAX, INT64_MAX, INT64_MAX}, hi = {0, 0, 0};
  std::vector<std::array<int64_t, 6>> box(boundary.size());
  double extent = 0.0;
  for (size_t i = 0; i < boundary.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      int64_t a = INT64_MAX, b = 0;
      for (uint32_t v : boundary[i]) {
        a = std::min<int64_t>(a, r.positions[v][k]);
        b = std::max<int64_t>(b, r.positions[v][k]);
      }
      box[i][k] = a;
      box[i][k + 3] = b;
      lo[k] = std::min(lo[k], a);
      hi[k] = std::max(hi[k], b);
      extent += double(b - a);
    }
  }
  const int64_t cell = std::max<int64_t>(1, int64_t(2.0 * extent / (3.0 * double(boundary.size()))));
  int64_t dims[3];
  for (int k = 0; k < 3; ++k) dims[k] = (hi[k] - lo[k]) / cell + 1;
  std::vector<std::array<int64_t, 6>> range(boundary.size());
  std::vector<std::pair<int64_t, uint32_t>> entries;
  for (uint32_t i = 0; i < boundary.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      range[i][k] = (box[i][k] - lo[k]) / cell;
      range[i][k + 3] = (box[i][k + 3] - lo[k]) / cell;
    }
    for (int64_t z = range[i][2]; z <= range[i][5]; ++z) {
      for (int64_t y = range[i][1]; y <= range[i][4]; ++y) {
        for (int64_t x = range[i][0]; x <= range[i][3]; ++x) entries.push_back({(z * dims[1] + y) * dims[0] + x, i});
      }
    }
  }
  std::sort(entries.begin(), entries.end());
  uint64_t clashes = 0;
  for (size_t g = 0; g < entries.size();) {
    size_t h = g + 1;
    while (h < entries.size() && entries[h].first == entries[g].first) ++h;
    const int64_t c = entries[g].first;
    for (size_t i = g; i < h; ++i) {
      for (size_t j = g; j < i; ++j) {
        const auto &a = range[entries[i].second], &b = range[entries[j].second];
        const int64_t corner =
            (std::max(a[2], b[2]) * dims[1] + std::max(a[1], b[1])) * dims[0] + std::max(a[0], b[0]);
        if (corner != c) continue;
        const auto &p = box[entries[i].second], &q = box[entries[j].second];
        if (p[0] > q[3] || q[0] > p[3] || p[1] > q[4] || q[1] > p[4] || p[2] > q[5] || q[2] > p[5]) continue;
        clashes += trianglesClash(boundary[entries[i].second], boundary[entries[j].second], r.positions.data());
      }
    }
    g = h;
  }
  return clashes;
}

// Replays `result` on `mesh` and checks everything; every full_every-th batch
// (and the last) gets the whole-mesh checks, the others check the vertices
// the batch touched.
void replayAndCheck(const QuantizedTetMesh& mesh, const TetSimplifyResult& result, const std::string& name,
                    size_t full_every) {
  Replay r(mesh);
  std::vector<Tri> boundary;
  const int64_t euler = eulerAndManifold(r, &boundary, name + " input");
  EXPECT_EQ(boundaryClashes(r, boundary), 0u) << name << ": input boundary clashes";
  std::vector<uint32_t> claimed(mesh.tets.size(), 0);  // 1 + the collapse's index in its batch
  std::vector<uint32_t> claimed_in(mesh.tets.size(), ~0u);
  uint64_t collapses = 0;
  for (size_t b = 0; b < result.batches.size(); ++b) {
    const auto& batch = result.batches[b];
    ASSERT_FALSE(batch.empty()) << name << ": empty batch " << b;
    const std::string where = name + " batch " + std::to_string(b);
    // Independence, on the mesh before the batch.
    for (uint32_t i = 0; i < batch.size(); ++i) {
      const TetCollapse& c = batch[i];
      ASSERT_NE(c.vs, c.vt);
      bool edge = false;
      for (uint32_t v : {c.vs, c.vt}) {
        for (uint32_t t : r.liveStar(v)) {
          edge |= Replay::holds(r.tets[t], c.vs) && Replay::holds(r.tets[t], c.vt);
          if (claimed_in[t] == b && claimed[t] != i + 1) {
            FAIL() << where << ": collapses " << claimed[t] - 1 << " and " << i << " share tet " << t;
          }
          claimed_in[t] = uint32_t(b);
          claimed[t] = i + 1;
        }
      }
      ASSERT_TRUE(edge) << where << ": (" << c.vs << ", " << c.vt << ") is not an edge";
    }
    std::vector<uint32_t> touched;
    for (const TetCollapse& c : batch) {
      std::vector<std::array<uint32_t, 2>> ring;
      for (uint32_t t : r.liveStar(c.vt)) {
        if (!Replay::holds(r.tets[t], c.vs)) continue;
        std::array<uint32_t, 2> e;
        int n = 0;
        for (uint32_t x : r.tets[t]) {
          if (x != c.vs && x != c.vt) e[n++] = x;
        }
        ring.push_back(e);
      }
      r.collapse(c.vs, c.vt);
      ++collapses;
      expectSplitRule(r, c.vs, ring, where + " collapse (" + std::to_string(c.vs) + ", " + std::to_string(c.vt) + ")");
      if (testing::Test::HasFatalFailure()) return;
      for (uint32_t t : r.liveStar(c.vs)) {
        for (uint32_t x : r.tets[t]) touched.push_back(x);
      }
    }
    // Orientation of every tet, every batch.
    for (uint32_t t = 0; t < r.tets.size(); ++t) {
      if (!r.alive[t]) continue;
      const Tet& v = r.tets[t];
      ASSERT_GT(orient3d(r.positions[v[0]], r.positions[v[1]], r.positions[v[2]], r.positions[v[3]]), 0)
          << where << ": tet " << t << " not positively oriented";
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    if (b % full_every == 0 || b + 1 == result.batches.size()) {
      ASSERT_EQ(eulerAndManifold(r, &boundary, where), euler) << where << ": Euler characteristic changed";
      ASSERT_EQ(boundaryClashes(r, boundary), 0u) << where << ": boundary self-intersection";
      std::vector<uint32_t> all(r.positions.size());
      std::iota(all.begin(), all.end(), 0u);
      expectLinks(r, all, where);
    } else {
      expectLinks(r, touched, where);
    }
    if (testing::Test::HasFailure()) return;
  }
  EXPECT_EQ(collapses, result.stats.collapses);
  EXPECT_EQ(r.live_tets, result.stats.final_tets);
}

TetSimplifyResult simplifyOrFail(const QuantizedTetMesh& mesh, const TetSimplifyOptions& options) {
  TetSimplifyResult result;
  const Error e = simplifyTets(mesh, options, &result);
  EXPECT_TRUE(e.ok()) << e.describe();
  return result;
}

// ------------------------------------------------------------ predicates --

TEST(TetPredicates, Orientation) {
  const IPoint a = {0, 0, 0}, b = {1 << 29, 0, 0}, c = {0, 1 << 29, 0}, d = {0, 0, (1 << 30) - 1};
  EXPECT_GT(orient3d(a, b, c, d), 0);
  EXPECT_LT(orient3d(a, c, b, d), 0);
  EXPECT_EQ(orient3d(a, b, c, {5, 7, 0}), 0);
}

TEST(TetPredicates, TriangleClashes) {
  std::vector<IPoint> p = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0},     // 0 1 2: in z = 0
                           {2, 2, -5}, {2, 2, 5}, {8, 8, 5},      // 3 4 5: pierces 0 1 2
                           {20, 20, 1}, {30, 20, 1}, {20, 30, 1},  // 6 7 8: far away
                           {5, 5, 0}, {-5, 5, 0}, {0, -5, 0},     // 9 10 11: coplanar pieces
                           {0, 0, 10}};                            // 12
  EXPECT_TRUE(trianglesClash({0, 1, 2}, {3, 4, 5}, p.data()));
  EXPECT_FALSE(trianglesClash({0, 1, 2}, {6, 7, 8}, p.data()));
  // Sharing vertex 0: apart (a wall standing on it), and folded into it.
  EXPECT_FALSE(trianglesClash({0, 1, 2}, {0, 12, 4}, p.data()));
  EXPECT_TRUE(trianglesClash({0, 1, 2}, {0, 12, 3}, p.data()));  // its far edge pierces it
  EXPECT_TRUE(trianglesClash({0, 1, 2}, {0, 9, 10}, p.data()));   // coplanar, overlapping
  EXPECT_FALSE(trianglesClash({0, 1, 2}, {0, 10, 11}, p.data())); // coplanar, beside it
  // Sharing edge 0 1: a fold (same side, coplanar) clashes, the other side does not.
  EXPECT_TRUE(trianglesClash({0, 1, 2}, {1, 0, 9}, p.data()));
  EXPECT_FALSE(trianglesClash({0, 1, 2}, {1, 0, 11}, p.data()));
  EXPECT_FALSE(trianglesClash({0, 1, 2}, {1, 0, 12}, p.data()));
}

TEST(TetSimplify, RejectsBrokenInput) {
  QuantizedTetMesh mesh;
  mesh.positions = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}, {0, 0, 100}, {100, 100, 100}};
  mesh.tets = {{0, 2, 1, 3}};  // negative
  TetSimplifyResult result;
  Error e = simplifyTets(mesh, TetSimplifyOptions{}, &result);
  EXPECT_EQ(e.status, Status::kInvalidArgument);
  EXPECT_NE(e.message.find("tet 0"), std::string::npos) << e.message;
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};  // share face 1 2 3 with the same orientation
  for (auto& t : mesh.tets) {
    if (orient3d(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]) < 0) {
      std::swap(t[0], t[1]);
    }
  }
  e = simplifyTets(mesh, TetSimplifyOptions{}, &result);
  EXPECT_TRUE(e.ok()) << e.describe();  // a valid two-tet mesh
  mesh.tets.push_back({1, 2, 3, 4});
  e = simplifyTets(mesh, TetSimplifyOptions{}, &result);
  EXPECT_EQ(e.status, Status::kInvalidArgument);
  // Two tets touching at one vertex: its link is two triangles.
  mesh.positions = {{100, 100, 100}, {200, 100, 100}, {100, 200, 100}, {100, 100, 200},
                    {0, 100, 100},   {100, 0, 100},   {100, 100, 0}};
  mesh.tets = {{0, 1, 2, 3}, {0, 4, 5, 6}};
  for (auto& t : mesh.tets) {
    if (orient3d(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]) < 0) {
      std::swap(t[1], t[2]);
    }
  }
  e = simplifyTets(mesh, TetSimplifyOptions{}, &result);
  EXPECT_EQ(e.status, Status::kInvalidArgument);
  EXPECT_NE(e.message.find("vertex 0"), std::string::npos) << e.message;
}

// ------------------------------------------------------------ real meshes --

TEST(TetSimplify, BunnyEveryBatchValid) {
  const QuantizedTetMesh mesh = loadMedit("bunny_5433v_34055tet.mesh");
  const TetSimplifyResult result = simplifyOrFail(mesh, TetSimplifyOptions{});
  EXPECT_LT(result.stats.final_tets, mesh.tets.size() / 20);
  replayAndCheck(mesh, result, "bunny", 1);
}

TEST(TetSimplify, HandEveryBatchValid) {
  const QuantizedTetMesh mesh = loadMedit("hand_7234v_29998tet.mesh");
  const TetSimplifyResult result = simplifyOrFail(mesh, TetSimplifyOptions{});
  EXPECT_LT(result.stats.final_tets, mesh.tets.size() / 20);
  replayAndCheck(mesh, result, "hand", 1);
}

TEST(TetSimplify, CtCropEveryBatchValid) {
  const QuantizedTetMesh mesh = loadCt();
  const TetSimplifyResult result = simplifyOrFail(mesh, TetSimplifyOptions{});
  EXPECT_LT(result.stats.final_tets, 1000u);
  replayAndCheck(mesh, result, "ct", 8);
}

TEST(TetSimplify, PaperCostEveryBatchValid) {
  const QuantizedTetMesh mesh = loadMedit("hand_7234v_29998tet.mesh");
  TetSimplifyOptions options;
  options.cost = TetCost::kPaper;
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  EXPECT_LT(result.stats.final_tets, mesh.tets.size() / 10);
  replayAndCheck(mesh, result, "hand paper", 4);
}

// ------------------------------------------------------------ halting --

TEST(TetSimplify, HaltsAtBaseTets) {
  const QuantizedTetMesh mesh = loadMedit("bunny_5433v_34055tet.mesh");
  TetSimplifyOptions options;
  options.min_base_tets = 5000;
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  EXPECT_GE(result.stats.final_tets, 5000u);
  EXPECT_LT(result.stats.final_tets, 5000u + 64u);  // stopped at the first collapse that would go below
  replayAndCheck(mesh, result, "bunny base tets", 1000000);
}

TEST(TetSimplify, HaltsAtBaseVertices) {
  const QuantizedTetMesh mesh = loadMedit("hand_7234v_29998tet.mesh");
  TetSimplifyOptions options;
  options.min_base_vertices = 1000;
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  EXPECT_EQ(result.stats.final_vertices, 1000u);
}

TEST(TetSimplify, HaltsAtTimeBudget) {
  const QuantizedTetMesh mesh = loadCt();
  TetSimplifyOptions options;
  options.time_budget_seconds = 0.05;
  double last = -1.0;
  bool monotone = true;
  options.progress = [&](double f) {
    monotone &= f >= last && f <= 1.0;
    last = f;
  };
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  EXPECT_TRUE(monotone);
  EXPECT_GT(result.stats.collapses, 0u);
  EXPECT_LT(result.stats.collapses, 20000u);  // the whole run makes about 32,700
  replayAndCheck(mesh, result, "ct time budget", 1000000);
}

TEST(TetSimplify, MinDihedralHonoured) {
  const QuantizedTetMesh mesh = loadCt();
  TetSimplifyOptions options;
  options.min_dihedral_degrees = 15.0;
  options.min_base_tets = 17875;  // 10 %
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  QuantizedTetMesh level;
  applyTetCollapses(mesh, result, result.stats.collapses, &level);
  const DihedralStats d = dihedralStats(level);
  EXPECT_GE(d.worst, 15.0);
  EXPECT_GT(result.stats.evaded_min_dihedral, 0u);
  EXPECT_EQ(level.tets.size(), result.stats.final_tets);
}

TEST(TetSimplify, DihedralOfRegularAndKuhnTets) {
  // Kuhn's tets (the CT crop's) have dihedral angles of 45, 60 and 90 degrees.
  EXPECT_NEAR(minDihedralDegrees({0, 0, 0}, {1024, 0, 0}, {1024, 1024, 0}, {1024, 1024, 1024}), 45.0, 1e-9);
}

}  // namespace
}  // namespace mrsv

namespace mrsv {
namespace {

// The intersection test matters: without it, the hand's boundary (fingers
// close together) crosses itself at some level; with it (HandEveryBatchValid),
// never.
TEST(TetSimplify, HandBoundaryCrossesWithoutIntersectionTest) {
  const QuantizedTetMesh mesh = loadMedit("hand_7234v_29998tet.mesh");
  TetSimplifyOptions options;
  options.boundary_intersection_test = false;
  const TetSimplifyResult result = simplifyOrFail(mesh, options);
  EXPECT_EQ(result.stats.evaded_self_intersection, 0u);
  Replay r(mesh);
  std::vector<Tri> boundary;
  uint64_t worst = 0;
  for (const auto& batch : result.batches) {
    for (const TetCollapse& c : batch) r.collapse(c.vs, c.vt);
    eulerAndManifold(r, &boundary, "hand without test");
    worst = std::max(worst, boundaryClashes(r, boundary));
  }
  EXPECT_GT(worst, 0u);
}

}  // namespace
}  // namespace mrsv
