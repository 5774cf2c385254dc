// Tet-mesh metrics against cases with known answers: point location in
// convex meshes (random points, points on shared faces and vertices), exact
// interpolation of a linear field across two unrelated meshes of one domain,
// volumes and boundaries of boxes, inverted, flat, non-manifold and
// self-intersecting complexes, and the real bunny tet mesh.
#include "mrsv/tet_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "metrics/tet_predicates.h"
#include "tet_metric_meshes.h"

namespace mrsv {
namespace {

using test::gridTetMesh;

double linear(const Point3& p) { return 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2] + 1.0; }

// The unit cube cut into n^3 cubes of 6 tets, interior vertices moved by up
// to `jitter` of a cube per axis, the linear field at the vertices. With
// jitter 0.1 a vertex moves at most 0.17 of a cube, under a quarter of the
// smallest height of a Kuhn tet (0.71): every tet stays positive.
TetMesh unitCube(int n, double jitter, uint64_t seed) {
  const double h = 1.0 / n;
  TetMesh m = gridTetMesh(n + 1, n + 1, n + 1, {0, 0, 0}, {h, h, h});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  for (auto& p : m.positions)
    for (double& x : p)
      if (x > 1e-9 && x < 1.0 - 1e-9) x += u(rng);
  m.fields.push_back({"value", {}});
  for (const auto& p : m.positions) m.fields[0].values.push_back(linear(p));
  return m;
}

// Whether p is in closed tet t, exactly (the brute-force reference).
bool inTet(const TetMesh& m, size_t t, const Point3& p) {
  const auto& tet = m.tets[t];
  for (int i = 0; i < 4; ++i) {
    Point3 q[4] = {m.positions[tet[0]], m.positions[tet[1]], m.positions[tet[2]],
                   m.positions[tet[3]]};
    q[i] = p;
    if (exactOrientation(q[0], q[1], q[2], q[3]) < 0) return false;
  }
  return true;
}

TEST(TetMetrics, OrientationConvention) {
  EXPECT_EQ(exactOrientation({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
  EXPECT_EQ(exactOrientation({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}), -1);
  EXPECT_EQ(exactOrientation({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0);
  const TetMesh m = gridTetMesh(3, 4, 5, {0, 0, 0}, {1, 1, 1});
  ASSERT_EQ(m.tets.size(), 2u * 3u * 4u * 6u);
  for (const auto& t : m.tets)
    EXPECT_EQ(exactOrientation(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]],
                               m.positions[t[3]]),
              1);
  EXPECT_EQ(gridTetMesh(32, 32, 32, {0, 0, 0}, {1, 1, 2}).tets.size(), 178746u);
}

TEST(TetMetrics, LocatesEveryPointOfAConvexMesh) {
  const TetMesh m = unitCube(6, 0.1, 7);
  std::string error;
  ASSERT_TRUE(checkTetMesh(m, &error)) << error;
  const TetLocator locator(m);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 100000; ++i) {
    const Point3 p{u(rng), u(rng), u(rng)};
    std::array<double, 4> b;
    const int64_t t = locator.locate(p, &b);
    ASSERT_GE(t, 0) << "point " << i;
    ASSERT_TRUE(inTet(m, static_cast<size_t>(t), p));
    Point3 q{0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) q[d] += b[k] * m.positions[m.tets[t][k]][d];
    for (int d = 0; d < 3; ++d) ASSERT_NEAR(q[d], p[d], 1e-12);
  }
  // Outside: beyond the box, and just beyond a face.
  EXPECT_EQ(locator.locate({1.5, 0.5, 0.5}), -1);
  EXPECT_EQ(locator.locate({0.5, 0.5, -1e-300}), -1);
  EXPECT_EQ(locator.locate({0.5, std::nextafter(1.0, 2.0), 0.5}), -1);
}

TEST(TetMetrics, PointsOnSharedFacesGoToTheLowestTet) {
  // Vertices, edge midpoints and face centroids of every tet lie on shared
  // faces; each must be found, in the lowest-indexed tet that holds it.
  const TetMesh m = unitCube(3, 0.1, 5);
  const TetLocator locator(m);
  std::vector<Point3> points;
  for (const auto& t : m.tets) {
    for (uint32_t v : t) points.push_back(m.positions[v]);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        Point3 mid;
        for (int d = 0; d < 3; ++d) mid[d] = 0.5 * (m.positions[t[i]][d] + m.positions[t[j]][d]);
        points.push_back(mid);
      }
    for (int f = 0; f < 4; ++f) {
      Point3 c{0, 0, 0};
      for (int k = 0; k < 4; ++k)
        if (k != f)
          for (int d = 0; d < 3; ++d) c[d] += m.positions[t[k]][d] / 3.0;
      points.push_back(c);
    }
  }
  for (const Point3& p : points) {
    int64_t lowest = -1;
    for (size_t t = 0; t < m.tets.size() && lowest < 0; ++t)
      if (inTet(m, t, p)) lowest = static_cast<int64_t>(t);
    ASSERT_GE(lowest, 0);  // midpoints and centroids of rounded coordinates stay in the cube
    EXPECT_EQ(locator.locate(p), lowest) << p[0] << " " << p[1] << " " << p[2];
  }
}

TEST(TetMetrics, SelfComparisonHasNoError) {
  const TetMesh m = gridTetMesh(9, 7, 6, {1, 2, 3}, {0.5, 0.5, 1.0}, [](int i, int j, int k) {
    return std::sin(0.7 * i) * std::cos(0.4 * j) + 0.1 * k * k;
  });
  TetFieldErrorOptions o;
  o.sample_count = 200000;
  TetFieldError e;
  std::string error;
  ASSERT_TRUE(measureTetFieldError(m, m, o, &e, &error)) << error;
  EXPECT_EQ(e.samples, 200000u);
  EXPECT_EQ(e.outside_b, 0u);
  EXPECT_LT(e.max_abs, 1e-13);
  EXPECT_GT(e.psnr_db, 250.0);  // rounding of the two interpolations only
  EXPECT_GT(e.range, 0.0);

  TetCompareOptions c;
  c.field.sample_count = 100000;
  c.threads = 1;
  const TetCompareReport r = compareTetMeshes(m, m, c);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.boundary.hausdorff, 0.0);
  EXPECT_EQ(r.volume_difference, 0.0);
  EXPECT_TRUE(r.quality_a.valid());
  const std::string json = tetCompareJson(r);
  EXPECT_NE(json.find("\"psnr_db\": "), std::string::npos);
  EXPECT_NE(json.find("\"manifold\": true"), std::string::npos);
  EXPECT_EQ(json.find("inf"), std::string::npos);
  EXPECT_EQ(json.find("nan"), std::string::npos);
}

TEST(TetMetrics, IdenticalFieldsGiveInfinitePsnr) {
  // Vertices of one grid: both meshes interpolate in the same tets.
  TetMesh a = gridTetMesh(5, 5, 5, {0, 0, 0}, {1, 1, 1}, [](int i, int, int) { return i * i; });
  TetFieldErrorOptions o;
  o.sample_count = 10000;
  TetFieldError e;
  std::string error;
  ASSERT_TRUE(measureTetFieldError(a, a, o, &e, &error)) << error;
  EXPECT_EQ(e.rms, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr_db));
  TetCompareReport r;
  r.has_field = true;
  r.field = e;
  EXPECT_NE(tetCompareJson(r).find("\"psnr_db\": null"), std::string::npos);
}

TEST(TetMetrics, LinearFieldInterpolatesExactlyAcrossResolutions) {
  // Two unrelated tetrahedralisations of the unit cube (different
  // resolutions, jittered interiors): a linear field is the same function
  // on both, so the sampled error is rounding only, and no sample of A is
  // outside B (the domains are the same closed cube).
  const TetMesh a = unitCube(4, 0.1, 1);
  const TetMesh b = unitCube(7, 0.1, 2);
  TetFieldErrorOptions o;
  o.sample_count = 200000;
  o.seed = 3;
  TetFieldError e;
  std::string error;
  ASSERT_TRUE(measureTetFieldError(a, b, o, &e, &error)) << error;
  EXPECT_EQ(e.outside_b, 0u);
  EXPECT_LT(e.max_abs, 1e-12);
  EXPECT_NEAR(e.range, 2.0 + 3.0 + 0.5, 1e-12);
  // A non-linear field is not interpolated exactly: the test can fail.
  TetMesh a2 = a, b2 = b;
  for (TetMesh* m : {&a2, &b2})
    for (size_t v = 0; v < m->positions.size(); ++v)
      m->fields[0].values[v] = std::sin(4.0 * m->positions[v][0]);
  ASSERT_TRUE(measureTetFieldError(a2, b2, o, &e, &error)) << error;
  EXPECT_GT(e.max_abs, 1e-3);
  EXPECT_LT(e.psnr_db, 60.0);
}

TEST(TetMetrics, SamplesOutsideBAreCounted) {
  // B is the half x <= 0.5 of A's cube: about half of the samples fall
  // outside it and take the value of its nearest boundary point.
  const TetMesh a = gridTetMesh(9, 9, 9, {0, 0, 0}, {0.125, 0.125, 0.125},
                                [](int i, int, int) { return 0.125 * i; });
  const TetMesh b = gridTetMesh(5, 9, 9, {0, 0, 0}, {0.125, 0.125, 0.125},
                                [](int i, int, int) { return 0.125 * i; });
  TetFieldErrorOptions o;
  o.sample_count = 100000;
  TetFieldError e;
  std::string error;
  ASSERT_TRUE(measureTetFieldError(a, b, o, &e, &error)) << error;
  EXPECT_NEAR(static_cast<double>(e.outside_b) / 1e5, 0.5, 0.01);  // binomial sd 0.0016
  // Outside, B's value is 0.5 (its face x = 0.5) and the error x - 0.5.
  EXPECT_NEAR(e.max_abs, 0.5, 1e-3);
  EXPECT_NEAR(e.outside_b_max_distance, 0.5, 1e-3);
  EXPECT_NEAR(e.mean_abs, 0.5 * 0.25, 0.005);
  EXPECT_NEAR(tetMeshVolume(b), 0.5, 1e-14);
}

TEST(TetMetrics, VolumeOfABox) {
  const TetMesh m = gridTetMesh(5, 7, 11, {-1, 2, 3}, {0.5, 0.5, 0.5});  // 2 x 3 x 5
  EXPECT_NEAR(tetMeshVolume(m), 30.0, 1e-12);
  TetMesh inverted = m;
  std::swap(inverted.tets[0][0], inverted.tets[0][1]);
  EXPECT_NEAR(tetMeshVolume(inverted), 30.0 - 2.0 * 0.125 / 6.0, 1e-12);
}

TEST(TetMetrics, BoundaryOfACubeIsClosedAndOutward) {
  const int n = 5;
  const TetMesh m = gridTetMesh(n + 1, n + 1, n + 1, {0, 0, 0}, {1, 1, 1});
  std::vector<uint32_t> original;
  const TriangleMesh s = tetBoundary(m, &original);
  EXPECT_EQ(s.triangles.size(), static_cast<size_t>(6 * n * n * 2));
  EXPECT_EQ(s.positions.size(),
            static_cast<size_t>((n + 1) * (n + 1) * (n + 1) - (n - 1) * (n - 1) * (n - 1)));
  ASSERT_EQ(original.size(), s.positions.size());
  for (size_t v = 0; v < original.size(); ++v) EXPECT_EQ(s.positions[v], m.positions[original[v]]);
  // Closed and consistently oriented: every directed edge once, its reverse once.
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const auto& t : s.triangles)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  // Outward: the divergence theorem gives the volume with a plus sign.
  double volume = 0.0;
  for (const auto& t : s.triangles) {
    const Point3 &a = s.positions[t[0]], &b = s.positions[t[1]], &c = s.positions[t[2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0])) /
              6.0;
  }
  EXPECT_NEAR(volume, n * n * n, 1e-9);
}

TEST(TetMetrics, ValidMeshPassesEveryCheck) {
  const TetMesh m = unitCube(4, 0.1, 9);
  const TetQuality q = measureTetQuality(m);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_EQ(q.degenerate, 0u);
  EXPECT_TRUE(q.manifold.manifold());
  EXPECT_EQ(q.manifold.unused_vertices, 0u);
  EXPECT_EQ(q.boundary_self_intersections, 0);
  EXPECT_TRUE(q.valid());
  EXPECT_GT(q.min_dihedral_worst, 0.0);
  // Kuhn tets of a cube: dihedral angles 45, 60 and 90 degrees.
  const TetQuality k = measureTetQuality(gridTetMesh(3, 3, 3, {0, 0, 0}, {1, 1, 1}));
  EXPECT_NEAR(k.min_dihedral_worst, 45.0, 1e-9);
  EXPECT_NEAR(k.min_dihedral_mean, 45.0, 1e-9);
  EXPECT_NEAR(k.max_dihedral_worst, 90.0, 1e-9);
}

TEST(TetMetrics, InvertedAndFlatTetsAreDetected) {
  TetMesh m = unitCube(3, 0.1, 4);
  std::swap(m.tets[17][2], m.tets[17][3]);
  TetQuality q = measureTetQuality(m);
  EXPECT_EQ(q.inverted, 1u);
  EXPECT_EQ(q.degenerate, 0u);
  // Its four faces now run the same way as its neighbours' (or, on the
  // boundary, inward): some shared face is misoriented.
  EXPECT_GT(q.manifold.misoriented_faces, 0u);
  EXPECT_GE(q.manifold.first_bad_face_tet, 0);
  EXPECT_LE(q.manifold.first_bad_face_tet, 17);
  EXPECT_FALSE(q.valid());

  // A flat tet beside a good one.
  TetMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  flat.tets = {{0, 1, 2, 3}, {0, 1, 4, 2}};
  q = measureTetQuality(flat);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_EQ(q.degenerate, 1u);
  EXPECT_EQ(q.min_dihedral_worst, 0.0);
  EXPECT_FALSE(q.valid());
}

TEST(TetMetrics, NonManifoldComplexesAreDetected) {
  const std::vector<Point3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Two tets: a copy of a unit tet translated by `shift`, with `shared` of
  // its vertices identified with the first tet's.
  auto pair = [&](const Point3& shift, int shared) {
    TetMesh m;
    for (const auto& p : corners) m.positions.push_back(p);
    std::array<uint32_t, 4> second;
    for (int i = 0; i < 4; ++i) {
      if (i < shared) {
        second[i] = static_cast<uint32_t>(i);
      } else {
        second[i] = static_cast<uint32_t>(m.positions.size());
        m.positions.push_back(
            {corners[i][0] + shift[0], corners[i][1] + shift[1], corners[i][2] + shift[2]});
      }
    }
    m.tets = {{0, 1, 2, 3}, second};
    return m;
  };
  // Sharing one vertex: the vertex's link is two triangles.
  TetManifoldReport r = checkTetManifold(pair({0, 0, -2}, 1));
  EXPECT_EQ(r.nonmanifold_vertices, 1u);
  EXPECT_EQ(r.first_bad_vertex, 0);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_FALSE(r.manifold());
  // Sharing an edge (0, 1), the second tet reflected below z = 0... its
  // vertices 2, 3 moved to (0.3, -1, -1) and (0.3, 0, -1) keep it positive.
  TetMesh edge;
  edge.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, -1, -1}, {0.3, 0, -1}};
  edge.tets = {{0, 1, 2, 3}, {0, 1, 4, 5}};
  ASSERT_EQ(measureTetQuality(edge).inverted, 0u);
  r = checkTetManifold(edge);
  // The links of 0 and 1 are two triangles pinched at one vertex (connected,
  // Euler characteristic 1): only the edge test sees this.
  EXPECT_EQ(r.nonmanifold_edges, 1u);
  EXPECT_EQ(r.first_bad_edge, 0);
  EXPECT_FALSE(r.manifold());
  // Three tets on one face.
  TetMesh fan;
  fan.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 1}, {0.3, 0.3, 2}, {0.2, 0.2, -1}};
  fan.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 2, 1, 5}};
  r = checkTetManifold(fan);
  EXPECT_EQ(r.overshared_faces, 1u);
  EXPECT_FALSE(r.manifold());
  // Two tets sharing a face properly: a manifold.
  TetMesh good = fan;
  good.tets = {{0, 1, 2, 3}, {0, 2, 1, 5}};
  r = checkTetManifold(good);
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.unused_vertices, 1u);  // vertex 4
}

TEST(TetMetrics, BoundarySelfIntersectionsAreCounted) {
  // Two disjoint tets that pass through each other: each is a manifold, the
  // boundary is not embedded.
  TetMesh m;
  m.positions = {{0, 0, 0},       {1, 0, 0},       {0, 1, 0},       {0, 0, 1},
                 {0.2, 0.2, 0.2}, {1.2, 0.2, 0.2}, {0.2, 1.2, 0.2}, {0.2, 0.2, 1.2}};
  m.tets = {{0, 1, 2, 3}, {4, 5, 6, 7}};
  const TetQuality q = measureTetQuality(m);
  EXPECT_TRUE(q.manifold.manifold());
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_GT(q.boundary_self_intersections, 0);
  EXPECT_FALSE(q.valid());
  // Moved apart: none.
  for (int v = 4; v < 8; ++v) m.positions[v][0] += 2.0;
  EXPECT_EQ(measureTetQuality(m).boundary_self_intersections, 0);
}

// The real tet meshes of ../shared/data/tet are valid, and every random
// point of their volume is found again by the locator.
void expectValidRealMesh(const std::string& name, size_t tets, size_t boundary_faces) {
  TetMesh m;
  std::string error;
  ASSERT_TRUE(test::readMeditTetMesh(std::string(MRSV_SHARED_DATA "/tet/") + name, &m, &error))
      << error;
  ASSERT_TRUE(checkTetMesh(m, &error)) << error;
  ASSERT_EQ(m.tets.size(), tets);
  const TetQuality q = measureTetQuality(m);
  EXPECT_EQ(q.inverted, 0u);  // the data's README: all positively oriented
  EXPECT_EQ(q.degenerate, 0u);
  EXPECT_TRUE(q.manifold.manifold());
  EXPECT_EQ(q.boundary_faces, boundary_faces);
  EXPECT_EQ(q.boundary_self_intersections, 0);
  EXPECT_GT(q.volume, 0.0);
  m.fields.push_back({"y", {}});
  for (const auto& p : m.positions) m.fields[0].values.push_back(p[1]);
  TetFieldErrorOptions o;
  o.sample_count = 100000;
  TetFieldError e;
  ASSERT_TRUE(measureTetFieldError(m, m, o, &e, &error)) << error;
  EXPECT_EQ(e.outside_b, 0u);
  EXPECT_EQ(e.max_abs, 0.0);
}

TEST(TetMetrics, HandTetMeshIsValid) {
  // Its boundary is the file's Triangles section (9,556 triangles).
  expectValidRealMesh("hand_7234v_29998tet.mesh", 29998, 9556);
}

TEST(TetMetrics, BunnyTetMeshIsValid) {
  // The tets fill the bunny's convex hull: the boundary is 670 hull faces,
  // and the file's 6,966 Triangles (the bunny's surface) are inside, 6,781
  // of them between two tets.
  expectValidRealMesh("bunny_5433v_34055tet.mesh", 34055, 670);
}

TEST(TetMetrics, Plot3dGridsAreValid) {
  // The combustion chamber: 56 x 32 x 24 hexes of 5 tets, every one kept.
  // The blunt fin's grid has 39 points twice (a collapsed line at k = 0):
  // merged, its 77 collapsed tets are gone and the rest is a manifold with
  // an embedded boundary (before merging: 77 flat tets, not a manifold, 352
  // boundary self-intersections).
  const struct {
    const char* name;
    size_t tets;
  } grids[] = {{"combustion_chamber_plot3d_57x33x25_f32be", 215040},
               {"bluntfin_plot3d_40x32x32_f32be", 187395 - 77}};
  for (const auto& g : grids) {
    SCOPED_TRACE(g.name);
    TetMesh m;
    std::string error;
    const std::string prefix = std::string(MRSV_SHARED_DATA "/tet/") + g.name;
    ASSERT_TRUE(test::readPlot3dTetMesh(prefix + ".xyz", prefix + ".q", &m, &error)) << error;
    ASSERT_TRUE(checkTetMesh(m, &error)) << error;
    EXPECT_EQ(m.tets.size(), g.tets);
    const TetQuality q = measureTetQuality(m);
    EXPECT_EQ(q.inverted, 0u);
    EXPECT_EQ(q.degenerate, 0u);
    EXPECT_TRUE(q.manifold.manifold());
    EXPECT_EQ(q.boundary_self_intersections, 0);
  }
}

}  // namespace
}  // namespace mrsv
