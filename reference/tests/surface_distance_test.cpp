// Surface distances against cases with known answers: parallel planes, a
// sphere and its inscribed icosahedron, identical meshes, and a real mesh with
// one vertex moved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "metrics/surface_distance.h"
#include "mrsv/mesh_formats.h"

namespace mrsv {
namespace {

Point3 add(const Point3& a, const Point3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 scale(const Point3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
Point3 unit(const Point3& a) { return scale(a, 1.0 / norm(a)); }

// The square origin + x*u + y*v, 0 <= x, y <= 1, cut into n*n cells of two triangles.
TriangleMesh square(const Point3& origin, const Point3& u, const Point3& v, int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.push_back(add(origin, add(scale(u, double(i) / n), scale(v, double(j) / n))));
  auto at = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// The regular icosahedron with its vertices on the sphere of radius r.
TriangleMesh icosahedron(double r) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  for (double s : {-1.0, 1.0})
    for (double t : {-1.0, 1.0}) {
      m.positions.push_back({0.0, s, t * phi});
      m.positions.push_back({s, t * phi, 0.0});
      m.positions.push_back({t * phi, 0.0, s});
    }
  // Faces are the triples at pairwise distance 2 (the edge length before scaling).
  const size_t n = m.positions.size();
  auto edge = [&](size_t a, size_t b) {
    return std::fabs(norm(sub(m.positions[a], m.positions[b])) - 2.0) < 1e-9;
  };
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b)
      for (size_t c = b + 1; c < n; ++c)
        if (edge(a, b) && edge(b, c) && edge(a, c)) {
          std::array<uint32_t, 3> t{uint32_t(a), uint32_t(b), uint32_t(c)};
          const Point3 &pa = m.positions[a], &pb = m.positions[b], &pc = m.positions[c];
          if (dot(cross(sub(pb, pa), sub(pc, pa)), pa) < 0) std::swap(t[1], t[2]);
          m.triangles.push_back(t);
        }
  for (Point3& p : m.positions) p = scale(unit(p), r);
  return m;
}

// A geodesic sphere: every icosahedron face cut into f*f similar triangles,
// the grid points pushed out onto the sphere of radius r.
TriangleMesh geodesicSphere(double r, int f) {
  TriangleMesh ico = icosahedron(1.0), m;
  for (const auto& t : ico.triangles) {
    const Point3 &a = ico.positions[t[0]], &b = ico.positions[t[1]], &c = ico.positions[t[2]];
    std::vector<std::vector<uint32_t>> id(f + 1);
    for (int j = 0; j <= f; ++j)
      for (int i = 0; i + j <= f; ++i) {
        id[j].push_back(static_cast<uint32_t>(m.positions.size()));
        Point3 p = add(a, add(scale(sub(b, a), double(i) / f), scale(sub(c, a), double(j) / f)));
        m.positions.push_back(scale(unit(p), r));
      }
    for (int j = 0; j < f; ++j)
      for (int i = 0; i + j < f; ++i) {
        m.triangles.push_back({id[j][i], id[j][i + 1], id[j + 1][i]});
        if (i + j + 1 < f) m.triangles.push_back({id[j][i + 1], id[j + 1][i + 1], id[j + 1][i]});
      }
  }
  return m;
}

// Smallest distance from the origin to the plane of a triangle of `m`.
double minPlaneDistance(const TriangleMesh& m) {
  double best = INFINITY;
  for (const auto& t : m.triangles) {
    const Point3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    best = std::min(best, std::fabs(dot(unit(cross(sub(b, a), sub(c, a))), a)));
  }
  return best;
}

SurfaceDistanceOptions withSamples(uint64_t n) {
  SurfaceDistanceOptions o;
  o.sampling.sample_count = n;
  return o;
}

SurfaceDistanceReport measure(const TriangleMesh& a, const TriangleMesh& b,
                              const SurfaceDistanceOptions& options) {
  SurfaceDistanceReport r;
  std::string error;
  EXPECT_TRUE(measureSurfaceDistance(a, b, options, &r, &error)) << error;
  return r;
}

// ---------------------------------------------------------------- sampling

TEST(SurfaceSampling, ExactCountEveryVertexAndDeterministic) {
  TriangleMesh m = geodesicSphere(1.0, 6);  // 720 triangles
  SurfaceSamplingOptions o;
  o.sample_count = 50000;
  SurfaceSamples s, again, other;
  sampleSurface(m, o, &s);
  EXPECT_EQ(s.points.size(), 50000u);
  EXPECT_EQ(s.is_face_sample.size(), s.points.size());
  EXPECT_EQ(s.vertex_samples + s.edge_samples + s.face_samples, s.points.size());
  EXPECT_GT(s.edge_samples, 0u);
  EXPECT_GT(s.face_samples, s.edge_samples);
  // The vertices are duplicated along the icosahedron's edges (each face has
  // its own grid), and every copy is a sample.
  EXPECT_EQ(s.vertex_samples, m.positions.size());
  std::set<Point3> points(s.points.begin(), s.points.end());
  for (const Point3& p : m.positions) EXPECT_TRUE(points.count(p));

  sampleSurface(m, o, &again);
  EXPECT_EQ(again.points, s.points);
  o.seed = 2;
  sampleSurface(m, o, &other);
  EXPECT_EQ(other.points.size(), s.points.size());
  EXPECT_NE(other.points, s.points);
}

TEST(SurfaceSampling, FaceSamplesAreAreaProportionalAndInside) {
  // Two separate triangles, the second with 9 times the area of the first.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {8, 0, 0}, {5, 3, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  SurfaceSamplingOptions o;
  o.sample_count = 100000;
  SurfaceSamples s;
  sampleSurface(m, o, &s);
  EXPECT_EQ(s.points.size(), 100000u);
  uint64_t small = 0, large = 0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const Point3& p = s.points[i];
    EXPECT_EQ(p[2], 0.0);
    bool in_small = p[0] >= 0 && p[1] >= 0 && p[0] + p[1] <= 1 + 1e-12;
    bool in_large = p[0] >= 5 && p[1] >= 0 && (p[0] - 5) + p[1] <= 3 + 1e-12;
    EXPECT_TRUE(in_small || in_large) << p[0] << " " << p[1];
    if (s.is_face_sample[i]) ++(in_small ? small : large);
  }
  EXPECT_EQ(small + large, s.face_samples);
  EXPECT_NEAR(double(large) / double(small), 9.0, 9.0 * 2.0 / double(small));

  // Stratified: each of the 64 similar sub-triangles of the large triangle
  // (side 3/8) gets its share within 2 %. Uniform random points would miss
  // that often: the standard deviation of a cell's count would be 2.8 %.
  std::map<std::pair<int, int>, int> per_cell;  // (row, position in row)
  for (size_t i = 0; i < s.points.size(); ++i) {
    if (!s.is_face_sample[i] || s.points[i][0] < 5) continue;
    double x = (s.points[i][0] - 5) / 3 * 8, y = s.points[i][1] / 3 * 8;
    int ix = std::min(7, int(x)), iy = std::min(7, int(y));
    bool downward = (x - ix) + (y - iy) > 1;
    ++per_cell[{iy, 2 * ix + (downward ? 1 : 0)}];
  }
  ASSERT_EQ(per_cell.size(), 64u);
  const double expected = double(large) / 64.0;
  for (const auto& [cell, count] : per_cell)
    EXPECT_NEAR(count, expected, 0.02 * expected) << cell.first << " " << cell.second;
}

TEST(SurfaceSampling, DegenerateTrianglesAreSkipped) {
  TriangleMesh m = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2);
  const auto n = static_cast<uint32_t>(m.positions.size());
  // A zero-area triangle on three collinear new vertices, a needle, and one
  // repeating a vertex: none may enter the sampling or the tree.
  m.positions.push_back({0, 0, 5});
  m.positions.push_back({1, 0, 5});
  m.positions.push_back({2, 0, 5});
  m.positions.push_back({0, 1e-14, 5});
  m.triangles.push_back({n, n + 1, n + 2});
  m.triangles.push_back({n, n + 2, n + 3});
  m.triangles.push_back({0, 0, 4});
  std::string error;
  ASSERT_TRUE(checkSurfaceMesh(m, &error)) << error;
  SurfaceSamplingOptions o;
  o.sample_count = 1000;
  SurfaceSamples s;
  sampleSurface(m, o, &s);
  EXPECT_EQ(s.vertex_samples, 9u);
  for (const Point3& p : s.points) EXPECT_EQ(p[2], 0.0);
  SurfaceDistanceTree tree(m);
  EXPECT_EQ(tree.triangleCount(), 8u);
  EXPECT_NEAR(tree.distance({0.5, 0.5, 5.0}), 5.0, 1e-12);
  EXPECT_NEAR(surfaceBoxDiagonal(m), std::sqrt(2.0), 1e-15);
}

TEST(SurfaceSampling, CheckRejectsUnusableMeshes) {
  std::string error;
  TriangleMesh m = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  EXPECT_TRUE(checkSurfaceMesh(m, &error));
  TriangleMesh bad = m;
  bad.triangles[1][2] = 4;
  EXPECT_FALSE(checkSurfaceMesh(bad, &error));
  EXPECT_NE(error.find("vertex 4 of 4"), std::string::npos) << error;
  bad = m;
  bad.positions[2][1] = NAN;
  EXPECT_FALSE(checkSurfaceMesh(bad, &error));
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
  bad = m;
  bad.triangles.clear();
  EXPECT_FALSE(checkSurfaceMesh(bad, &error));
  bad.triangles = {{0, 1, 1}};
  EXPECT_FALSE(checkSurfaceMesh(bad, &error));
  EXPECT_EQ(error, "every triangle has zero area");
  SurfaceDistanceReport r;
  EXPECT_FALSE(measureSurfaceDistance(m, bad, {}, &r, &error));
  EXPECT_EQ(error.rfind("B: ", 0), 0u) << error;
}

// ------------------------------------------------------- known distances

// (a) A square against a parallel copy at distance d: every point of either
// is exactly d from the other, so max, mean and RMS are all d. The frame is
// tilted and the two triangulations differ, so closest points fall inside
// triangles, on edges and on the boundary.
TEST(SurfaceDistance, ParallelPlanesAreDApart) {
  const Point3 u = unit({1.0, 0.2, -0.3});
  const Point3 v = unit(cross(u, unit({0.1, 1.0, 0.4})));
  const Point3 w = cross(u, v);  // unit normal
  const Point3 o{0.3, -0.2, 0.7};
  const double d = 0.0625;
  TriangleMesh a = square(o, u, w, 40);
  TriangleMesh b = square(add(o, scale(v, d)), u, w, 13);
  SurfaceDistanceReport r = measure(a, b, withSamples(100000));
  for (const OneSidedDistance* s : {&r.a_to_b, &r.b_to_a}) {
    EXPECT_NEAR(s->max, d, 1e-12 * d);
    EXPECT_NEAR(s->mean, d, 1e-12 * d);
    EXPECT_NEAR(s->rms, d, 1e-12 * d);
    EXPECT_EQ(s->samples, 100000u);
    // 3,200 small triangles: many samples go to their edges (spacing h).
    EXPECT_GT(s->area_samples, 50000u);
  }
  EXPECT_NEAR(r.hausdorff, d, 1e-12 * d);
  EXPECT_NEAR(r.mean, d, 1e-12 * d);
  EXPECT_NEAR(r.rms, d, 1e-12 * d);
  // The axis-aligned box of the tilted square: o plus the extent of u and w.
  double diag2 = 0;
  for (int k = 0; k < 3; ++k) diag2 += (std::fabs(u[k]) + std::fabs(w[k])) * (std::fabs(u[k]) + std::fabs(w[k]));
  EXPECT_NEAR(r.bbox_diagonal, std::sqrt(diag2), 1e-12);
  EXPECT_NEAR(r.relative(r.hausdorff), d / std::sqrt(diag2), 1e-12 * d);
}

// (b) The sphere S of radius r and its inscribed icosahedron P (vertices on
// S, inradius rho). Both one-sided Hausdorff distances are H = r - rho:
//   P -> S: a point x of P is r - |x| from S, largest at the face centres.
//   S -> P: P contains the ball of radius rho, so x on S is within r - rho of
//   it; above a face centre it is exactly r - rho away.
// "The sphere" is a geodesic sphere G (frequency f, vertices on S), which is
// delta = r - (its smallest face-plane distance) away from S. Then:
//   G -> P: the same two arguments give at most H, and G has a vertex on S
//   exactly above each face centre of P (f is a multiple of 3), so the
//   measured value is H up to rounding.
//   P -> G: G contains the ball of radius r - delta and lies in the ball of
//   radius r, so a point x of P is between r - delta - |x| and r - |x| from
//   G. A sample at distance t from a face centre has |x| = sqrt(rho^2 + t^2)
//   <= rho + t^2 / (2 rho), so the measured maximum lies in
//   [H - delta - t^2 / (2 rho), H] with t the nearest sample to a face centre.
TEST(SurfaceDistance, SphereAgainstInscribedIcosahedron) {
  const double r = 2.5;
  TriangleMesh ico = icosahedron(r);
  TriangleMesh sphere = geodesicSphere(r, 42);  // 35,280 triangles
  ASSERT_EQ(ico.triangles.size(), 20u);
  const double rho = minPlaneDistance(ico);
  // The closed form of the inradius / circumradius of the icosahedron.
  EXPECT_NEAR(rho / r, std::sqrt((5.0 + 2.0 * std::sqrt(5.0)) / 15.0), 1e-14);
  const double h = r - rho;
  const double delta = r - minPlaneDistance(sphere);
  EXPECT_LT(delta, 2e-3 * h);  // the tolerance below is meaningful

  SurfaceDistanceOptions o = withSamples(200000);
  SurfaceDistanceReport rep = measure(sphere, ico, o);

  SurfaceSamples ico_samples;
  sampleSurface(ico, o.sampling, &ico_samples);
  double t = INFINITY;
  for (const auto& f : ico.triangles) {
    Point3 c = scale(add(ico.positions[f[0]], add(ico.positions[f[1]], ico.positions[f[2]])), 1.0 / 3);
    for (const Point3& p : ico_samples.points) t = std::min(t, norm(sub(p, c)));
  }
  const double sampling_slack = t * t / (2 * rho);
  EXPECT_LT(sampling_slack, delta);  // the samples are dense enough to matter little

  EXPECT_NEAR(rep.a_to_b.max, h, 1e-12 * h);  // G -> P
  EXPECT_LE(rep.b_to_a.max, h * (1 + 1e-12));  // P -> G
  EXPECT_GE(rep.b_to_a.max, h - delta - sampling_slack - 1e-12 * h);
  EXPECT_NEAR(rep.hausdorff, h, 1e-12 * h);
  // The point of G farthest from P is one of those above a face centre.
  EXPECT_NEAR(norm(rep.a_to_b.max_at), r, 1e-12 * r);
  // Mean and RMS have no closed form here, but they are between 0 and the max
  // and the RMS is at least the mean.
  for (const OneSidedDistance* s : {&rep.a_to_b, &rep.b_to_a}) {
    EXPECT_GT(s->mean, 0.1 * h);
    EXPECT_LT(s->mean, s->max);
    EXPECT_GE(s->rms, s->mean);
    EXPECT_LE(s->rms, s->max);
  }
}

// (c) A mesh against itself: every sample lies on the other surface.
TEST(SurfaceDistance, IdenticalMeshesAreZeroApart) {
  for (const TriangleMesh& m : {geodesicSphere(1.0, 9), icosahedron(3.0),
                                square({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 7)}) {
    SurfaceDistanceReport r = measure(m, m, withSamples(50000));
    EXPECT_LE(r.hausdorff, 1e-14 * r.bbox_diagonal);
    EXPECT_LE(r.mean, 1e-14 * r.bbox_diagonal);
    EXPECT_LE(r.rms, 1e-14 * r.bbox_diagonal);
  }
}

// (d) The Stanford bunny against a copy with one vertex moved by m. Take the vertex v
// that is extreme in a direction e and move it by m along e: all of A lies in
// the half-space e.x <= e.v, so the moved vertex is exactly m from A (its
// distance to the half-space is m, and to v it is m). No point is farther: a
// point of a moved triangle, (1-s)p + s v', is s*m from the point (1-s)p + s v
// of A, and likewise the other way. So the Hausdorff distance is exactly m and
// the moved vertex, a sample, attains it from B's side.
TEST(SurfaceDistance, RealMeshWithOneVertexMoved) {
  TriangleMesh a;
  std::string error;
  ASSERT_TRUE(readMeshFile(std::string(MRSV_SHARED_DATA) +
                               "/surface/bunny_stanford_zipper_35947v_69451tri.ply",
                           "", &a, &error))
      << error;
  ASSERT_EQ(a.triangles.size(), 69451u);
  ASSERT_TRUE(checkSurfaceMesh(a, &error)) << error;
  const Point3 e = unit({0.3, 1.0, -0.2});
  std::vector<bool> used(a.positions.size(), false);
  for (const auto& t : a.triangles)
    for (uint32_t v : t) used[v] = true;
  size_t best = 0;
  for (size_t v = 0; v < a.positions.size(); ++v)
    if (used[v] && dot(a.positions[v], e) > dot(a.positions[best], e)) best = v;
  const double diag = surfaceBoxDiagonal(a);
  const double moved = 0.01 * diag;
  TriangleMesh b = a;
  b.positions[best] = add(a.positions[best], scale(e, moved));

  // The answer comes from a vertex sample, so the count only needs to be
  // enough for the other checks.
  SurfaceDistanceReport r = measure(a, b, withSamples(100000));
  EXPECT_NEAR(r.b_to_a.max, moved, 1e-12 * moved);
  EXPECT_NEAR(norm(sub(r.b_to_a.max_at, b.positions[best])), 0.0, 1e-15);
  EXPECT_LE(r.a_to_b.max, moved * (1 + 1e-12));
  EXPECT_GT(r.a_to_b.max, 0.0);
  EXPECT_NEAR(r.hausdorff, moved, 1e-12 * moved);
  EXPECT_NEAR(r.relative(r.hausdorff), 0.01, 1e-12);
  // Only the triangles around one vertex moved: the mean is a tiny fraction.
  EXPECT_LT(r.mean, 0.01 * moved);
  EXPECT_GT(r.mean, 0.0);
}

// The figures do not depend on the number of threads.
TEST(SurfaceDistance, ThreadCountDoesNotChangeResults) {
  TriangleMesh a = geodesicSphere(1.0, 12), b = icosahedron(1.0);
  SurfaceDistanceOptions o = withSamples(100000);
  o.threads = 1;
  SurfaceDistanceReport one = measure(a, b, o);
  o.threads = 3;
  double last_progress = 0;
  int calls = 0;
  o.progress = [&](double f) {
    EXPECT_GE(f, last_progress);
    last_progress = f;
    ++calls;
  };
  SurfaceDistanceReport three = measure(a, b, o);
  EXPECT_GT(calls, 2);
  EXPECT_DOUBLE_EQ(last_progress, 1.0);
  for (auto [x, y] : {std::pair{&one.a_to_b, &three.a_to_b}, std::pair{&one.b_to_a, &three.b_to_a}}) {
    EXPECT_EQ(x->max, y->max);
    EXPECT_EQ(x->mean, y->mean);
    EXPECT_EQ(x->rms, y->rms);
    EXPECT_EQ(x->max_at, y->max_at);
  }
  SurfaceDistanceTree tree(b);
  SurfaceSamples s;
  sampleSurface(a, o.sampling, &s);
  std::vector<double> d1 = tree.distances(s.points, 1), d2 = tree.distances(s.points, 2);
  EXPECT_EQ(d1, d2);
  EXPECT_EQ(*std::max_element(d1.begin(), d1.end()), one.a_to_b.max);
}

}  // namespace
}  // namespace mrsv
