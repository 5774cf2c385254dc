// Tet mesh formats, the exact orientation test and the tetrahedralizations,
// on the real data of ../shared/data (tet/ and the Stanford CT head).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "mrsv/file_io.h"
#include "mrsv/tet_formats.h"
#include "shared_data.h"

namespace mrsv {
namespace {

const std::string kTetData = std::string(MRSV_SHARED_DATA) + "/tet/";

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

// The CT head's 32^3-sample crop of the paper's experiment 7.2 (the paper's
// "32 by 32 by 32 voxels or 178,746 tetrahedra" = 6 * 31^3).
TetMesh ctCrop(uint32_t side, const double spacing[3]) {
  test::SharedGrid grid;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst",
                                   &grid));
  GridCrop crop;
  crop.origin[0] = 112, crop.origin[1] = 112, crop.origin[2] = 40;
  crop.size[0] = crop.size[1] = crop.size[2] = side;
  TetMesh mesh;
  TetBuildReport report;
  std::string error;
  EXPECT_TRUE(tetrahedralizeGrid(grid.header, grid.samples, spacing, crop, &mesh, &report, &error)) << error;
  return mesh;
}

TetMesh plot3dMesh(const std::string& xyz, const std::string& q, TetBuildReport* report) {
  Plot3dData data;
  std::string error;
  EXPECT_TRUE(readPlot3d(kTetData + xyz, kTetData + q, &data, &error)) << error;
  TetMesh mesh;
  EXPECT_TRUE(tetrahedralizePlot3d(data, &mesh, report, &error)) << error;
  return mesh;
}

// Faces of the mesh: how many are on the boundary (one tet), how many are
// shared by two tets with the same orientation (a fold), and whether any face
// has more than two tets.
struct FaceCheck {
  uint64_t boundary = 0, interior = 0, same_orientation = 0, more_than_two = 0;
};
FaceCheck checkFaces(const TetMesh& mesh) {
  // Each face as its sorted vertices plus the parity of the sort: two tets
  // that meet properly see their common face with opposite parities.
  struct Face {
    std::array<uint32_t, 3> v;
    bool odd;
  };
  std::vector<Face> faces;
  faces.reserve(mesh.tets.size() * 4);
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // outward when positive
  for (const auto& t : mesh.tets)
    for (const auto& f : kFaces) {
      std::array<uint32_t, 3> v = {t[f[0]], t[f[1]], t[f[2]]};
      bool odd = false;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2 - i; ++j)
          if (v[j] > v[j + 1]) {
            std::swap(v[j], v[j + 1]);
            odd = !odd;
          }
      faces.push_back({v, odd});
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.v < b.v; });
  FaceCheck check;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j].v == faces[i].v) ++j;
    if (j - i == 1) ++check.boundary;
    else if (j - i == 2) {
      ++check.interior;
      if (faces[i].odd == faces[i + 1].odd) ++check.same_orientation;
    } else {
      ++check.more_than_two;
    }
    i = j;
  }
  return check;
}

uint64_t nonPositiveTets(const TetMesh& mesh) {
  uint64_t n = 0;
  for (const auto& t : mesh.tets)
    n += orient3dSign(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                      mesh.positions[t[3]]) <= 0;
  return n;
}

// Whether the tets form a 3-manifold (with boundary) of positive tets: every
// tet positive by the exact test, every face in one tet or in two that see it
// with opposite orientations, and every vertex's link (the faces opposite it
// in its tets) a sphere or a disk: connected, no link edge in more than two
// link faces, each link vertex's fan a single path or cycle (so no two fans
// meet at an edge of the mesh), and Euler characteristic 2, or 1 with a
// boundary.
struct ManifoldCheck {
  uint64_t nonpositive = 0, overshared_faces = 0, misoriented_faces = 0, bad_vertices = 0;
  int64_t first_bad_vertex = -1;
  std::string first_problem;
  bool valid() const {
    return nonpositive == 0 && overshared_faces == 0 && misoriented_faces == 0 && bad_vertices == 0;
  }
};

// Number of components among `n` items joined by `pairs` (union-find).
size_t components(size_t n, const std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  size_t count = n;
  for (auto [a, b] : pairs)
    if (root(a) != root(b)) parent[root(a)] = root(b), --count;
  return count;
}

ManifoldCheck checkManifold(const TetMesh& mesh) {
  ManifoldCheck check;
  const auto& p = mesh.positions;
  for (const auto& t : mesh.tets)
    check.nonpositive += orient3dSign(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) <= 0;
  // Faces: sorted corners and the parity of the sort.
  static const int kFaces[4][3] = {
      {1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // outward when positive
  std::vector<std::pair<std::array<uint32_t, 3>, bool>> faces;
  faces.reserve(mesh.tets.size() * 4);
  for (const auto& t : mesh.tets)
    for (const auto& f : kFaces) {
      std::array<uint32_t, 3> v = {t[f[0]], t[f[1]], t[f[2]]};
      bool odd = false;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2 - i; ++j)
          if (v[j] > v[j + 1]) std::swap(v[j], v[j + 1]), odd = !odd;
      faces.push_back({v, odd});
    }
  std::sort(faces.begin(), faces.end());
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j].first == faces[i].first) ++j;
    if (j - i > 2) ++check.overshared_faces;
    if (j - i == 2 && faces[i].second == faces[i + 1].second) ++check.misoriented_faces;
    i = j;
  }
  // Vertex links.
  std::vector<uint32_t> start(p.size() + 1, 0), incident(4 * mesh.tets.size());
  for (const auto& t : mesh.tets)
    for (uint32_t v : t) ++start[v + 1];
  for (size_t v = 0; v < p.size(); ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t t = 0; t < mesh.tets.size(); ++t)
    for (uint32_t v : mesh.tets[t]) incident[fill[v]++] = t;
  for (uint32_t v = 0; v < p.size(); ++v) {
    if (start[v] == start[v + 1]) continue;  // unused
    // The link: triangles of local vertex numbers.
    std::vector<uint32_t> verts;
    std::vector<std::array<uint32_t, 3>> tris;
    for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
      std::array<uint32_t, 3> tri;
      int n = 0;
      for (uint32_t w : mesh.tets[incident[k]])
        if (w != v) tri[n++] = w;
      tris.push_back(tri);
      verts.insert(verts.end(), tri.begin(), tri.end());
    }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    auto local = [&](uint32_t w) {
      return uint32_t(std::lower_bound(verts.begin(), verts.end(), w) - verts.begin());
    };
    std::vector<std::pair<uint32_t, uint32_t>> edges,
        joins;  // link edges; pairs of triangles' corners
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> fan(
        verts.size());  // per link vertex: opposite edges
    for (auto& tri : tris) {
      for (uint32_t& w : tri) w = local(w);
      for (int e = 0; e < 3; ++e) {
        uint32_t a = tri[e], b = tri[(e + 1) % 3], c = tri[(e + 2) % 3];
        edges.push_back({std::min(a, b), std::max(a, b)});
        joins.push_back({a, b});
        fan[c].push_back({a, b});
      }
    }
    std::sort(edges.begin(), edges.end());
    size_t edge_count = 0, boundary_edges = 0;
    bool ok = true;
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      ++edge_count;
      boundary_edges += j - i == 1;
      ok &= j - i <= 2;
      i = j;
    }
    std::string why = ok ? "" : "a link edge in three or more link faces";
    if (ok && components(verts.size(), joins) != 1)
      ok = false, why = "a link of several components";
    const int64_t euler = int64_t(verts.size()) - int64_t(edge_count) + int64_t(tris.size());
    if (ok && euler != (boundary_edges ? 1 : 2))
      ok = false, why = "a link of Euler characteristic " + std::to_string(euler) +
                        (boundary_edges ? " with a boundary" : " without a boundary");
    for (uint32_t w = 0; ok && w < verts.size(); ++w) {
      // The fan around w: its opposite edges must form one path or cycle.
      std::vector<uint32_t> ends;
      for (auto [a, b] : fan[w]) ends.push_back(a), ends.push_back(b);
      std::sort(ends.begin(), ends.end());
      ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
      std::vector<std::pair<uint32_t, uint32_t>> pairs;
      for (auto [a, b] : fan[w])
        pairs.push_back({uint32_t(std::lower_bound(ends.begin(), ends.end(), a) - ends.begin()),
                         uint32_t(std::lower_bound(ends.begin(), ends.end(), b) - ends.begin())});
      if (components(ends.size(), pairs) != 1)
        ok = false, why = "edge to vertex " + std::to_string(verts[w]) + " in several fans of tets";
    }
    if (!ok) {
      if (check.bad_vertices++ == 0) {
        check.first_bad_vertex = v;
        check.first_problem = "vertex " + std::to_string(v) + ": " + why;
      }
    }
  }
  return check;
}

void expectSameMesh(const TetMesh& a, const TetMesh& b, bool with_fields, const std::string& what) {
  ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
  ASSERT_EQ(a.tets.size(), b.tets.size()) << what;
  for (size_t v = 0; v < a.positions.size(); ++v)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(std::memcmp(&a.positions[v][k], &b.positions[v][k], 8), 0)
          << what << ": vertex " << v << " " << a.positions[v][k] << " != " << b.positions[v][k];
  for (size_t t = 0; t < a.tets.size(); ++t) ASSERT_EQ(a.tets[t], b.tets[t]) << what << ": tet " << t;
  if (!with_fields) {
    EXPECT_TRUE(b.fields.empty()) << what;
    return;
  }
  ASSERT_EQ(a.fields.size(), b.fields.size()) << what;
  for (size_t f = 0; f < a.fields.size(); ++f) {
    EXPECT_EQ(a.fields[f].name, b.fields[f].name) << what;
    ASSERT_EQ(a.fields[f].values, b.fields[f].values) << what << ": field " << a.fields[f].name;
  }
}

// Writes `mesh` as `path`'s format to memory and reads it back.
TetMesh roundTrip(const TetMesh& mesh, const std::string& path, bool ascii) {
  std::vector<TetFileBytes> files;
  TetWriteOptions options;
  options.ascii = ascii;
  std::string error;
  EXPECT_TRUE(encodeTetFile(path, mesh, options, &files, nullptr, &error)) << error;
  TetMesh back;
  TetReadReport report;
  if (tetFormatOf(path) == TetFormat::kTetgen) {
    EXPECT_EQ(files.size(), 2u);
    EXPECT_TRUE(readTetgenBytes(files[0].path, files[0].bytes.data(), files[0].bytes.size(), files[1].path,
                                files[1].bytes.data(), files[1].bytes.size(), &back, &report, &error))
        << error;
  } else {
    EXPECT_EQ(files.size(), 1u);
    EXPECT_TRUE(readTetBytes(path, tetFormatOf(path), files[0].bytes.data(), files[0].bytes.size(), &back,
                             &report, &error))
        << error;
  }
  EXPECT_EQ(report.flipped, 0u) << path;
  return back;
}

// ---- the exact orientation test

// Coordinates m * 2^-20 with |m| < 2^26, shifted by up to 2^20: the exact
// determinant is an integer multiple of 2^-60 that fits in 128 bits.
TEST(TetOrient, MatchesExactIntegerDeterminantOnNearlyCoplanarPoints) {
  std::mt19937_64 rng(21);
  std::uniform_int_distribution<int64_t> coordinate(-(int64_t{1} << 25), int64_t{1} << 25);
  std::uniform_int_distribution<int64_t> noise(-2, 2);
  uint64_t zero = 0, positive = 0, negative = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    int64_t p[4][3];
    for (int k = 0; k < 3; ++k) {
      p[0][k] = coordinate(rng);
      p[1][k] = p[0][k] + 4 * (coordinate(rng) / 8);
      p[2][k] = p[0][k] + 4 * (coordinate(rng) / 8);
    }
    // d on the plane of a, b, c (a + (b - a) / 2 + (c - a) / 4, exact), and in
    // two of three trials moved off it by a unit or two.
    for (int k = 0; k < 3; ++k)
      p[3][k] = p[0][k] + (p[1][k] - p[0][k]) / 2 + (p[2][k] - p[0][k]) / 4 + (trial % 3 ? noise(rng) : 0);
    const int64_t shift = (trial % 2) ? (int64_t{1} << 40) : 0;  // 2^20 in coordinate units
    std::array<double, 3> q[4];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) q[i][k] = std::ldexp(static_cast<double>(p[i][k] + shift), -20);
    __int128 u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = p[1][k] - p[0][k];
      v[k] = p[2][k] - p[0][k];
      w[k] = p[3][k] - p[0][k];
    }
    __int128 det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                   u[2] * (v[0] * w[1] - v[1] * w[0]);
    int expected = det > 0 ? 1 : det < 0 ? -1 : 0;
    ASSERT_EQ(orient3dSign(q[0], q[1], q[2], q[3]), expected) << "trial " << trial;
    zero += expected == 0;
    positive += expected > 0;
    negative += expected < 0;
  }
  // The cases must include all three signs, coplanar ones among them.
  EXPECT_GT(zero, 1000u);
  EXPECT_GT(positive, 1000u);
  EXPECT_GT(negative, 1000u);
}

TEST(TetOrient, SignConvention) {
  std::array<double, 3> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(orient3dSign(a, b, c, d), 1);
  EXPECT_EQ(orient3dSign(a, c, b, d), -1);
  EXPECT_EQ(orient3dSign(a, b, c, {0.25, 0.25, 0}), 0);
  // Tiny and huge coordinates at the ends of the supported range.
  EXPECT_EQ(orient3dSign({0, 0, 0}, {1e-50, 0, 0}, {0, 1e-50, 0}, {0, 0, 1e-50}), 1);
  EXPECT_EQ(orient3dSign({1e50, 1e50, 1e50}, {-1e50, 1e50, 1e50}, {1e50, -1e50, 1e50}, {1e50, 1e50, -1e50}), -1);
}

// ---- real tet meshes

TEST(TetFormats, ReadsTheRealMeditMeshes) {
  const struct {
    const char* file;
    size_t vertices, tets;
  } kFiles[] = {{"bunny_5433v_34055tet.mesh", 5433, 34055}, {"hand_7234v_29998tet.mesh", 7234, 29998}};
  for (const auto& f : kFiles) {
    TetMesh mesh;
    TetReadReport report;
    std::string error;
    ASSERT_TRUE(readTetFile(kTetData + f.file, &mesh, &report, &error)) << error;
    EXPECT_EQ(mesh.positions.size(), f.vertices) << f.file;
    EXPECT_EQ(mesh.tets.size(), f.tets) << f.file;
    EXPECT_EQ(report.flipped, 0u) << f.file << ": the README says every tet is positive";
    EXPECT_EQ(nonPositiveTets(mesh), 0u);
    FaceCheck faces = checkFaces(mesh);
    EXPECT_EQ(faces.more_than_two, 0u) << f.file;
    EXPECT_EQ(faces.same_orientation, 0u) << f.file;
    // Every format carries the mesh exactly.
    for (const char* out : {"x.mesh", "x.node", "x.vtu", "x.vtk"})
      for (bool ascii : {false, true}) expectSameMesh(mesh, roundTrip(mesh, out, ascii), false, std::string(f.file) + " -> " + out);
  }
}

TEST(TetFormats, RoundTripsEveryFormatExactly) {
  // Spacings with long decimal expansions make every coordinate a test of the
  // shortest round-trip text and of the binary encodings.
  const double spacing[3] = {0.1, 1.0 / 3.0, 3.14159265358979};
  TetMesh mesh = ctCrop(12, spacing);
  ASSERT_EQ(mesh.tets.size(), 6u * 11 * 11 * 11);
  ScalarField wobble{"wobble", {}};
  for (size_t v = 0; v < mesh.positions.size(); ++v) wobble.values.push_back(std::sin(0.37 * v) * 1e-7);
  mesh.fields.push_back(wobble);
  for (const char* out : {"x.node", "x.ele", "x.vtu", "x.vtk"})
    for (bool ascii : {false, true}) expectSameMesh(mesh, roundTrip(mesh, out, ascii), true, std::string(out) + (ascii ? " ascii" : ""));
  TetWriteReport report;
  std::vector<TetFileBytes> files;
  std::string error;
  ASSERT_TRUE(encodeTetFile("x.mesh", mesh, {}, &files, &report, &error));
  EXPECT_EQ(report.fields_dropped, 2u);
  expectSameMesh(mesh, roundTrip(mesh, "x.mesh", true), false, "x.mesh");
}

TEST(TetFormats, WritersRefuseWhatTheFormatsCannotCarry) {
  TetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.tets = {{0, 1, 2, 3}};
  mesh.fields = {{"two words", {1, 2, 3, 4}}};
  std::vector<TetFileBytes> files;
  std::string error;
  EXPECT_FALSE(encodeTetFile("x.vtk", mesh, {}, &files, nullptr, &error));
  EXPECT_NE(error.find("white space"), std::string::npos) << error;
  mesh.fields[0] = {"short", {1, 2}};
  EXPECT_FALSE(encodeTetFile("x.vtu", mesh, {}, &files, nullptr, &error));
  EXPECT_NE(error.find("2 values for 4 vertices"), std::string::npos) << error;
  mesh.fields.clear();
  mesh.tets[0][3] = 4;
  EXPECT_FALSE(encodeTetFile("x.mesh", mesh, {}, &files, nullptr, &error));
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
  EXPECT_FALSE(encodeTetFile("x.obj", mesh, {}, &files, nullptr, &error));
  EXPECT_NE(error.find("unknown tet mesh format"), std::string::npos) << error;
}

// ---- tet meshes from data

TEST(TetsFromData, CtCropGivesThePapersTetCountConforming) {
  const double unit[3] = {1, 1, 1};
  TetMesh mesh = ctCrop(32, unit);
  EXPECT_EQ(mesh.positions.size(), 32u * 32 * 32);
  EXPECT_EQ(mesh.tets.size(), 178746u);
  ASSERT_EQ(mesh.fields.size(), 1u);
  EXPECT_EQ(mesh.fields[0].name, "value");
  EXPECT_EQ(nonPositiveTets(mesh), 0u);
  FaceCheck faces = checkFaces(mesh);
  EXPECT_EQ(faces.more_than_two, 0u);
  EXPECT_EQ(faces.same_orientation, 0u);
  EXPECT_EQ(faces.boundary, 6u * 31 * 31 * 2);  // the cube's six sides, two triangles per square
  EXPECT_EQ(faces.boundary + 2 * faces.interior, 4 * mesh.tets.size());
  // A mirrored spacing gives the same conforming mesh with every tet re-ordered.
  const double mirrored[3] = {1, -1, 2};
  TetMesh flipped = ctCrop(8, mirrored);
  EXPECT_EQ(nonPositiveTets(flipped), 0u);
  EXPECT_EQ(checkFaces(flipped).same_orientation, 0u);
}

TEST(TetsFromData, Plot3dGivesTheClassicTetCounts) {
  TetBuildReport report;
  // Blunt fin: 5 * 39 * 31 * 31 = 187,395 cut; its grid collapses the edge
  // from j = 0 to j = 1 at k = 0 for i = 1..39, so 39 points weld and the 77
  // tets holding such an edge have no volume and are dropped.
  TetMesh fin = plot3dMesh("bluntfin_plot3d_40x32x32_f32be.xyz", "bluntfin_plot3d_40x32x32_f32be.q", &report);
  EXPECT_EQ(report.cells, 39u * 31 * 31);
  EXPECT_EQ(report.welded, 39u);
  EXPECT_EQ(report.collapsed, 77u);
  EXPECT_EQ(fin.tets.size(), 187395u - 77u);
  EXPECT_EQ(fin.positions.size(), 40u * 32 * 32 - 39u);
  EXPECT_EQ(report.flipped, 0u);
  ASSERT_EQ(fin.fields.size(), 5u);
  EXPECT_EQ(fin.fields[0].name, "density");
  auto [lo, hi] = std::minmax_element(fin.fields[0].values.begin(), fin.fields[0].values.end());
  EXPECT_NEAR(*lo, 0.193, 0.001);  // the data README's range
  EXPECT_NEAR(*hi, 4.98, 0.01);
  FaceCheck faces = checkFaces(fin);
  EXPECT_EQ(faces.more_than_two, 0u);
  EXPECT_EQ(faces.same_orientation, 0u);
  EXPECT_EQ(nonPositiveTets(fin), 0u);

  // Combustion chamber: 5 * 56 * 32 * 24 = 215,040 for a 5-tet cut. Two
  // hexahedra, (39, 0, 0) and (39, 31, 0), are too distorted for it (a corner
  // tet comes out negative); each is cut into 6 tets from its corner 5 or 7,
  // the one corner whose cut is positive (D45): 215,042.
  TetMesh chamber = plot3dMesh("combustion_chamber_plot3d_57x33x25_f32be.xyz",
                               "combustion_chamber_plot3d_57x33x25_f32be.q", &report);
  EXPECT_EQ(chamber.tets.size(), 215040u + 2);
  EXPECT_EQ(chamber.positions.size(), 57u * 33 * 25);
  EXPECT_EQ(report.welded, 0u);
  EXPECT_EQ(report.flipped, 0u);
  EXPECT_EQ(report.cut_from_corner, 2u);
  EXPECT_EQ(report.cut_around_centroid, 0u);
  faces = checkFaces(chamber);
  EXPECT_EQ(faces.more_than_two, 0u);
  EXPECT_EQ(faces.same_orientation, 0u);
  EXPECT_EQ(nonPositiveTets(chamber), 0u);

  // LOX post: 5 * 37 * 75 * 37 = 513,375 for a 5-tet cut. Its IBLANK holds 1
  // and -1 but no 0, so no cell is left out; its O-grid seam (j = 0 and
  // j = 75) welds. A ring has 75 hexahedra, an odd count, so the seam faces'
  // diagonals differ from the two sides; the 37 x 37 hexahedra at j = 74 take
  // those of j = 0 and are cut into 6 tets from a corner: 513,375 + 1,369.
  TetMesh lox = plot3dMesh("lox_post_plot3d_38x76x38_f32be_iblank.xyz", "lox_post_plot3d_38x76x38_f32be.q",
                           &report);
  EXPECT_EQ(lox.tets.size(), 513375u + 37 * 37);
  EXPECT_EQ(report.cells_left_out, 0u);
  EXPECT_EQ(report.welded, 1444u);
  EXPECT_EQ(report.cut_from_corner, 37u * 37);
  EXPECT_EQ(report.cut_around_centroid, 0u);
  EXPECT_EQ(lox.positions.size(), 38u * 76 * 38 - 1444u);
  EXPECT_EQ(report.flipped, 0u);
  faces = checkFaces(lox);
  EXPECT_EQ(faces.more_than_two, 0u);
  EXPECT_EQ(faces.same_orientation, 0u);
  EXPECT_EQ(nonPositiveTets(lox), 0u);
}

// Every real PLOT3D grid gives a 3-manifold of positive tets, which the
// progressive encoder needs (before D45 the chamber had 4 folded faces and
// each of the LOX post's 1,444 seam vertices an annulus for a link).
TEST(TetsFromData, Plot3dMeshesAreManifoldsOfPositiveTets) {
  const char* const kGrids[][2] = {
      {"bluntfin_plot3d_40x32x32_f32be.xyz", "bluntfin_plot3d_40x32x32_f32be.q"},
      {"combustion_chamber_plot3d_57x33x25_f32be.xyz", "combustion_chamber_plot3d_57x33x25_f32be.q"},
      {"lox_post_plot3d_38x76x38_f32be_iblank.xyz", "lox_post_plot3d_38x76x38_f32be.q"}};
  for (const auto& grid : kGrids) {
    SCOPED_TRACE(grid[0]);
    TetBuildReport report;
    ManifoldCheck check = checkManifold(plot3dMesh(grid[0], grid[1], &report));
    EXPECT_EQ(check.nonpositive, 0u);
    EXPECT_EQ(check.overshared_faces, 0u);
    EXPECT_EQ(check.misoriented_faces, 0u);
    EXPECT_EQ(check.bad_vertices, 0u) << check.first_problem;
  }
  // The check finds what it looks for: two tets folded onto one side of
  // their common face, and two tets meeting at a vertex only.
  TetMesh folded;
  folded.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2, 0.2, 2}};
  folded.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}};
  EXPECT_EQ(checkManifold(folded).misoriented_faces, 1u);
  TetMesh pinched;
  pinched.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  pinched.tets = {{0, 1, 2, 3}, {0, 4, 6, 5}};
  ManifoldCheck check = checkManifold(pinched);
  EXPECT_EQ(check.nonpositive, 0u);
  EXPECT_EQ(check.bad_vertices, 1u);
  EXPECT_EQ(check.first_bad_vertex, 0);
}

// One hexahedron (integer corners, found by a random search) that neither
// its 5-tet cut nor any of the four 6-tet cuts from a corner fits: 12 tets
// around an added vertex at the mean of its corners, and the field's mean
// there. A flat hexahedron fits no cut: a one-line error naming it.
TEST(TetsFromData, Plot3dHexahedraThe5TetCutDoesNotFit) {
  Plot3dData data;
  data.dims[0] = data.dims[1] = data.dims[2] = 2;
  data.xyz = {{1, 2, -1}, {6, 2, 0}, {2, 4, 2}, {4, 6, 2}, {0, 1, 4}, {5, -1, 6}, {-1, 2, 4}, {3, 2, 4}};
  data.q.resize(1);
  data.q[0].name = "density";
  data.q[0].values = {0, 1, 2, 3, 4, 5, 6, 7};
  TetMesh mesh;
  TetBuildReport report;
  std::string error;
  ASSERT_TRUE(tetrahedralizePlot3d(data, &mesh, &report, &error)) << error;
  EXPECT_EQ(report.cut_from_corner, 0u);
  EXPECT_EQ(report.cut_around_centroid, 1u);
  EXPECT_EQ(report.flipped, 0u);
  ASSERT_EQ(mesh.positions.size(), 9u);
  EXPECT_EQ(mesh.tets.size(), 12u);
  EXPECT_EQ(mesh.positions[8], (std::array<double, 3>{2.5, 2.25, 2.625}));
  EXPECT_EQ(mesh.fields[0].values[8], 3.5);
  ManifoldCheck check = checkManifold(mesh);
  EXPECT_TRUE(check.valid()) << check.first_problem;
  EXPECT_EQ(checkFaces(mesh).boundary, 12u);  // the 6 faces, two triangles each

  for (auto& p : data.xyz) p[2] = p[0] * 0.5 + p[1] * 0.25;  // all eight in one plane
  EXPECT_FALSE(tetrahedralizePlot3d(data, &mesh, &report, &error));
  EXPECT_NE(error.find("hexahedron (i, j, k) = (0, 0, 0) cannot be cut"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

TEST(TetsFromData, IblankZeroLeavesCellsOut) {
  Plot3dData data;
  data.dims[0] = 3, data.dims[1] = 2, data.dims[2] = 2;
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t j = 0; j < 2; ++j)
      for (uint32_t i = 0; i < 3; ++i) data.xyz.push_back({double(i), double(j), double(k)});
  data.iblank.assign(12, 1);
  data.iblank[2] = 0;  // a corner of the second hexahedron only
  TetMesh mesh;
  TetBuildReport report;
  std::string error;
  ASSERT_TRUE(tetrahedralizePlot3d(data, &mesh, &report, &error)) << error;
  EXPECT_EQ(report.cells, 2u);
  EXPECT_EQ(report.cells_left_out, 1u);
  EXPECT_EQ(mesh.tets.size(), 5u);
  EXPECT_EQ(mesh.positions.size(), 8u);  // the second hexahedron's other points dropped
}

// ---- malformed input: one line naming the file, the place and the rule

struct Bad {
  TetFormat format;
  std::string text;
  std::string expected;  // a part of the message
};

TEST(TetFormats, MalformedInputGivesOneLineErrors) {
  const std::string tet_mesh = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
  const std::string vtk_head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                               "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  const std::string vtu_head =
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1"
      "</DataArray></Points><Cells>";
  const std::vector<Bad> cases = {
      {TetFormat::kMedit, "MeshVersionFormatted 2\nDimension 2\n", "t:2: Dimension '2'"},
      {TetFormat::kMedit, tet_mesh + "Tetrahedra\n1\n1 2 3 5 0\n", "t:11: tet 1: vertex index 5 is out of range"},
      {TetFormat::kMedit, tet_mesh + "Tetrahedra\n1\n1 2 3 4 0\n", ""},  // valid
      {TetFormat::kMedit, tet_mesh + "Tetrahedra\n1\n1 2 3 2 0\n", "tet 0 (vertices 0 1 2 1) is degenerate"},
      {TetFormat::kMedit, tet_mesh + "Tetrahedra\n99999\n1 2 3 4 0\n", "99999 entries cannot fit"},
      {TetFormat::kMedit, tet_mesh + "Hexahedra\n1\n1 2 3 4 1 2 3 4 0\n", "Hexahedra: 1 cells that are not tetrahedra"},
      {TetFormat::kMedit, tet_mesh + "Foo\n1\n", "unknown section 'Foo'"},
      {TetFormat::kMedit, "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 nan 0 0\n", "is not finite"},
      {TetFormat::kMedit, "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 1e60 0 0\n", "outside the supported range"},
      {TetFormat::kVtkLegacy, vtk_head + "CELLS 1 5\n4 0 1 2 9\nCELL_TYPES 1\n10\n", "cell 0 has vertex index 9 out of range"},
      {TetFormat::kVtkLegacy, vtk_head + "CELLS 1 9\n8 0 1 2 3 0 1 2 3\nCELL_TYPES 1\n12\n", "cell 0 is a hexahedron"},
      {TetFormat::kVtkLegacy, vtk_head + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS s float\n1 2 3\n",
       "the file ends after 3 of 4 values"},
      {TetFormat::kVtkLegacy, vtk_head + "CELLS 1 5000000\n4 0 1 2 3\n", "values cannot fit"},
      {TetFormat::kVtkLegacy, "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n", "only UNSTRUCTURED_GRID"},
      {TetFormat::kVtu, vtu_head + "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>"
                        "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>"
                        "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">13</DataArray></Cells></Piece>"
                        "</UnstructuredGrid></VTKFile>",
       "cell 0 is a wedge"},
      {TetFormat::kVtu, vtu_head + "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">AAAA</DataArray>",
       "Cells needs the DataArrays"},
      {TetFormat::kVtu, "<VTKFile type=\"UnstructuredGrid\" compressor=\"vtkZLibDataCompressor\">", "compressed data"},
      {TetFormat::kVtu, "<VTKFile type=\"PolyData\">", "only UnstructuredGrid"},
      {TetFormat::kVtu, vtu_head + "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">AAAAAAAAAA$A"
                        "</DataArray><DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>"
                        "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray></Cells></Piece>"
                        "</UnstructuredGrid></VTKFile>",
       "is not base64"},
  };
  for (const Bad& bad : cases) {
    std::vector<uint8_t> bytes = bytesOf(bad.text);
    TetMesh mesh;
    std::string error;
    bool ok = readTetBytes("t", bad.format, bytes.data(), bytes.size(), &mesh, nullptr, &error);
    if (bad.expected.empty()) {
      EXPECT_TRUE(ok) << error;
      continue;
    }
    EXPECT_FALSE(ok) << bad.text;
    EXPECT_NE(error.find(bad.expected), std::string::npos) << "got: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(error.rfind("t", 0), 0u) << error;
    EXPECT_TRUE(mesh.positions.empty() && mesh.tets.empty());
  }
}

TEST(TetFormats, RepairsNegativeTetsAndSkipsLowerDimensionalCells) {
  // A MEDIT tet in the other orientation convention is flipped and counted.
  std::vector<uint8_t> bytes = bytesOf(
      "MeshVersionFormatted 1\nDimension\n3\n# comment\nVertices\n4\n0 0 0 7\n1 0 0 7\n0 1 0 7\n0 0 1 7\n"
      "Triangles\n1\n1 2 3 5\nTetrahedra\n1\n1 3 2 4 9\nEnd\n");
  TetMesh mesh;
  TetReadReport report;
  std::string error;
  ASSERT_TRUE(readTetBytes("t.mesh", TetFormat::kMedit, bytes.data(), bytes.size(), &mesh, &report, &error)) << error;
  EXPECT_EQ(report.flipped, 1u);
  EXPECT_EQ(mesh.tets[0], (std::array<uint32_t, 4>{0, 2, 3, 1}));
  // A legacy VTK file with a triangle beside its tet: the triangle is skipped.
  bytes = bytesOf("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                  "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 2 9\n3 0 1 2\n4 0 1 2 3\nCELL_TYPES 2\n5 10\n");
  ASSERT_TRUE(readTetBytes("t.vtk", TetFormat::kVtkLegacy, bytes.data(), bytes.size(), &mesh, &report, &error)) << error;
  EXPECT_EQ(report.skipped_cells, 1u);
  EXPECT_EQ(mesh.tets.size(), 1u);
  // TetGen files numbered from 1, with an attribute and boundary markers.
  std::vector<uint8_t> node = bytesOf("4 3 1 1\n1 0 0 0 5 1\n2 1 0 0 6 1\n3 0 1 0 7 1\n4 0 0 1 8 0\n");
  std::vector<uint8_t> ele = bytesOf("# tets\n1 4 1\n1 1 2 3 4 -1\n");
  ASSERT_TRUE(readTetgenBytes("t.node", node.data(), node.size(), "t.ele", ele.data(), ele.size(), &mesh, &report, &error))
      << error;
  ASSERT_EQ(mesh.fields.size(), 1u);
  EXPECT_EQ(mesh.fields[0].name, "attribute1");
  EXPECT_EQ(mesh.fields[0].values, (std::vector<double>{5, 6, 7, 8}));
  ele = bytesOf("1 4 0\n1 0 2 3 4\n");
  EXPECT_FALSE(readTetgenBytes("t.node", node.data(), node.size(), "t.ele", ele.data(), ele.size(), &mesh, &report, &error));
  EXPECT_EQ(error, "t.ele:2: tet 1: vertex index 0 is out of range (4 points numbered from 1 in the .node file)");
}

}  // namespace
}  // namespace mrsv
