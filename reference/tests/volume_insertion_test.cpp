// spec 10: the 3-D Delaunay core (same tets as CGAL's Delaunay_triangulation_3
// on degenerate grid subsets, every face locally Delaunay under the
// perturbation, every tet positive) and the volume inserter (max error
// honoured on every sample of a CT crop, stages only add, determinism).
#include "mrsv/volume_insertion.h"

#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/delaunay3.h"
#include "shared_data.h"

namespace mrsv {
namespace {

using reconstruct::Delaunay3;
using reconstruct::GridPoint;
using reconstruct::orient3dValue;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalDelaunay = CGAL::Delaunay_triangulation_3<Kernel>;
using TetKey = std::array<uint64_t, 4>;  // a tet's corners as sorted sample indices

struct Box {
  int32_t x, y, z;
  uint64_t index(const GridPoint& p) const { return (uint64_t(p[2]) * y + p[1]) * x + p[0]; }
};

std::vector<GridPoint> corners(const Box& b) {
  std::vector<GridPoint> c;
  for (int32_t z : {0, b.z - 1})
    for (int32_t y : {0, b.y - 1})
      for (int32_t x : {0, b.x - 1}) c.push_back({x, y, z});
  return c;
}

bool isCorner(const Box& b, const GridPoint& p) {
  return (p[0] == 0 || p[0] == b.x - 1) && (p[1] == 0 || p[1] == b.y - 1) && (p[2] == 0 || p[2] == b.z - 1);
}

// Builds ours from the non-corner points (in the order given).
bool build(const Box& b, const std::vector<GridPoint>& points, Delaunay3* dt) {
  std::string error;
  if (!dt->init(uint32_t(b.x), uint32_t(b.y), uint32_t(b.z), &error)) return false;
  for (const GridPoint& p : points)
    if (!isCorner(b, p)) dt->insert(p);
  return true;
}

std::vector<TetKey> tetsOf(const Box& b, const Delaunay3& dt) {
  std::vector<TetKey> tets;
  for (uint32_t c = 0; c < dt.cellSlots(); ++c) {
    if (!dt.isLive(c) || !dt.isFinite(c)) continue;
    TetKey k;
    for (int i = 0; i < 4; ++i) k[i] = b.index(dt.point(dt.cell(c).v[i]));
    std::sort(k.begin(), k.end());
    tets.push_back(k);
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

std::vector<TetKey> cgalTets(const Box& b, const std::vector<GridPoint>& points) {
  std::vector<Kernel::Point_3> pts;
  for (const GridPoint& p : corners(b)) pts.emplace_back(p[0], p[1], p[2]);
  for (const GridPoint& p : points)
    if (!isCorner(b, p)) pts.emplace_back(p[0], p[1], p[2]);
  CgalDelaunay cgal(pts.begin(), pts.end());
  std::vector<TetKey> tets;
  for (auto c = cgal.finite_cells_begin(); c != cgal.finite_cells_end(); ++c) {
    TetKey k;
    for (int i = 0; i < 4; ++i) {
      const auto& q = c->vertex(i)->point();
      k[i] = b.index(GridPoint{int32_t(q.x()), int32_t(q.y()), int32_t(q.z())});
    }
    std::sort(k.begin(), k.end());
    tets.push_back(k);
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

// Every finite tet positive; across every face, the other cell's far corner
// is not in conflict with the cell (the perturbed empty-sphere and, on the
// hull, empty-circle tests of spec 10.2 and 10.3), checked from both sides.
void expectLocallyDelaunay(const Delaunay3& dt) {
  uint64_t finite = 0;
  for (uint32_t c = 0; c < dt.cellSlots(); ++c) {
    if (!dt.isLive(c)) continue;
    const Delaunay3::Cell& t = dt.cell(c);
    int inf = -1;
    for (int k = 0; k < 4; ++k)
      if (t.v[k] == Delaunay3::kInfinite) inf = k;
    if (inf < 0) {
      ++finite;
      ASSERT_GT(orient3dValue(dt.point(t.v[0]), dt.point(t.v[1]), dt.point(t.v[2]), dt.point(t.v[3])), 0);
    }
    for (int i = 0; i < 4; ++i) {
      const Delaunay3::Cell& o = dt.cell(t.n[i]);
      uint32_t far = Delaunay3::kNone;
      int back = 0;
      for (int k = 0; k < 4; ++k) {
        if (o.n[k] == c) back++, far = o.v[k];
      }
      ASSERT_EQ(back, 1) << "neighbour links are not mutual";
      if (far == Delaunay3::kInfinite) continue;
      const GridPoint& p = dt.point(far);
      if (inf < 0) {
        const GridPoint* q[4] = {&dt.point(t.v[0]), &dt.point(t.v[1]), &dt.point(t.v[2]), &dt.point(t.v[3])};
        EXPECT_FALSE(reconstruct::insphereConflict<__int128>(q, p)) << "cell " << c << " face " << i;
      } else {
        const GridPoint* q[4];
        const GridPoint* f[3];
        int m = 0;
        for (int k = 0; k < 4; ++k) {
          q[k] = k == inf ? &p : &dt.point(t.v[k]);
          if (k != inf) f[m++] = q[k];
        }
        const int64_t side = orient3dValue(*q[0], *q[1], *q[2], *q[3]);
        EXPECT_LE(side, 0) << "a vertex beyond the hull";
        if (side == 0) {
          const int axis = reconstruct::sharedAxis(*f[0], *f[1], *f[2]);
          ASSERT_GE(axis, 0);
          EXPECT_FALSE(reconstruct::coplanarCircleConflict(axis, f, p)) << "hull cell " << c;
        }
      }
    }
  }
  EXPECT_EQ(finite, dt.finiteCellCount());
}

std::vector<GridPoint> randomSubset(const Box& b, double fraction, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<GridPoint> pts = corners(b);
  for (int32_t z = 0; z < b.z; ++z)
    for (int32_t y = 0; y < b.y; ++y)
      for (int32_t x = 0; x < b.x; ++x)
        if (!isCorner(b, {x, y, z}) && u(rng) < fraction) pts.push_back({x, y, z});
  std::shuffle(pts.begin(), pts.end(), rng);
  return pts;
}

TEST(Delaunay3, EqualsCgalOnEveryPointOfSmallGrids) {
  for (Box b : {Box{2, 2, 2}, Box{3, 3, 3}, Box{5, 5, 5}, Box{7, 4, 9}, Box{2, 6, 3}}) {
    std::vector<GridPoint> pts = randomSubset(b, 1.0, 7);
    Delaunay3 dt;
    ASSERT_TRUE(build(b, pts, &dt));
    EXPECT_EQ(tetsOf(b, dt), cgalTets(b, pts)) << b.x << "x" << b.y << "x" << b.z;
    expectLocallyDelaunay(dt);
    // Every point of a grid: the tets fill the box, 6 x volume in all.
    EXPECT_EQ(dt.finiteCellCount(), 6ull * (b.x - 1) * (b.y - 1) * (b.z - 1));
  }
}

TEST(Delaunay3, EqualsCgalOnRandomSubsetsInAnyOrder) {
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const Box b = seed <= 4 ? Box{17, 17, 17} : Box{23, 11, 30};
    std::vector<GridPoint> pts = randomSubset(b, 0.05 * seed, seed);
    Delaunay3 dt;
    ASSERT_TRUE(build(b, pts, &dt));
    const std::vector<TetKey> ours = tetsOf(b, dt);
    EXPECT_EQ(ours, cgalTets(b, pts)) << "seed " << seed;
    expectLocallyDelaunay(dt);
    // Another insertion order, the same tetrahedralization.
    std::reverse(pts.begin(), pts.end());
    Delaunay3 again;
    ASSERT_TRUE(build(b, pts, &again));
    EXPECT_EQ(tetsOf(b, again), ours);
  }
}

TEST(Delaunay3, WideCoordinatesTakeThe128BitPath) {
  // Sides above 2048: the 128-bit insphere; a sparse random set with the
  // eight corners of a large box.
  const Box b{3000, 40, 2500};
  std::mt19937 rng(11);
  std::vector<GridPoint> pts = corners(b);
  for (int i = 0; i < 3000; ++i)
    pts.push_back({int32_t(rng() % b.x), int32_t(rng() % b.y), int32_t(rng() % b.z)});
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  Delaunay3 dt;
  ASSERT_TRUE(build(b, pts, &dt));
  EXPECT_EQ(tetsOf(b, dt), cgalTets(b, pts));
}

TEST(Delaunay3, RefusesSidesOutOfRange) {
  Delaunay3 dt;
  std::string error;
  EXPECT_FALSE(dt.init(1, 5, 5, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(dt.init(5, 5, Delaunay3::kMaxSide + 1, &error));
  EXPECT_TRUE(dt.init(2, 2, Delaunay3::kMaxSide, &error));
}

// The 32^3 crop of the Stanford CT head at (112, 112, 40): skull and soft
// tissue, the crop the PT tests use.
SampleField ctCrop(uint32_t side, const uint32_t origin[3]) {
  SampleField f;
  test::SharedGrid grid;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst",
                                   &grid));
  if (grid.samples.empty()) return f;
  const uint32_t gx = grid.header.size_x, gy = grid.header.size_y;
  for (int a = 0; a < 3; ++a) f.size[a] = side;
  for (uint32_t z = 0; z < side; ++z)
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x)
        f.values.push_back(
            grid.samples[(uint64_t(origin[2] + z) * gy + origin[1] + y) * gx + origin[0] + x]);
  return f;
}

SampleField ctCrop32() {
  const uint32_t origin[3] = {112, 112, 40};
  return ctCrop(32, origin);
}

ErrorBound bound(const char* text) {
  ErrorBound b;
  EXPECT_TRUE(parseErrorBound(text, &b));
  return b;
}

// Every sample of the grid against the mesh, independently of the inserter:
// each tet's bounding box scanned point by point with four orientations;
// the tets tile the box (their 6 x volumes add up to the box's).
void expectWithin(const GridMesh& mesh, const SampleField& field, const ErrorBound& e) {
  std::vector<uint8_t> seen(field.values.size(), 0);
  __int128 total = 0;
  for (const auto& c : mesh.cells) {
    GridPoint P[4];
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) P[k][a] = int32_t(mesh.points[c[k]][a]);
    const int64_t D = orient3dValue(P[0], P[1], P[2], P[3]);
    ASSERT_GT(D, 0);
    total += D;
    int32_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min({P[0][a], P[1][a], P[2][a], P[3][a]});
      hi[a] = std::max({P[0][a], P[1][a], P[2][a], P[3][a]});
    }
    for (int32_t z = lo[2]; z <= hi[2]; ++z)
      for (int32_t y = lo[1]; y <= hi[1]; ++y)
        for (int32_t x = lo[0]; x <= hi[0]; ++x) {
          const GridPoint p{x, y, z};
          int64_t lambda[4];
          bool inside = true;
          for (int k = 0; k < 4 && inside; ++k) {
            GridPoint q[4] = {P[0], P[1], P[2], P[3]};
            q[k] = p;
            lambda[k] = orient3dValue(q[0], q[1], q[2], q[3]);
            inside = lambda[k] >= 0;
          }
          if (!inside) continue;
          __int128 interp = 0;
          for (int k = 0; k < 4; ++k) interp += __int128{lambda[k]} * mesh.values[c[k]];
          const uint64_t s = field.index(uint32_t(x), uint32_t(y), uint32_t(z));
          __int128 err = __int128{field.values[s]} * D - interp;
          if (err < 0) err = -err;
          ASSERT_LE(err * e.den, __int128{e.num} * D) << "sample " << x << "," << y << "," << z;
          seen[s] = 1;
        }
  }
  EXPECT_EQ(total, __int128{6} * (field.size[0] - 1) * (field.size[1] - 1) * (field.size[2] - 1));
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), 0);
}

TEST(VolumeInserter, MaxErrorHonouredOnEverySampleOfACtCrop) {
  const SampleField field = ctCrop32();
  ASSERT_EQ(field.values.size(), 32u * 32 * 32);
  uint64_t previous = 0;
  for (const char* e : {"40", "10", "2.5", "0"}) {
    VolumeInserter ins(32, 32, 32);
    InsertionLimits limits;
    limits.max_error = bound(e);
    std::string error;
    ASSERT_TRUE(ins.refine(field, 0, limits, &error)) << error;
    GridMesh mesh;
    ins.mesh(&mesh);
    EXPECT_EQ(mesh.cells.size(), ins.cellCount());
    EXPECT_EQ(mesh.points.size(), ins.vertexCount());
    expectWithin(mesh, field, limits.max_error);
    int64_t num = -1, den = 0;
    ins.maxError(&num, &den);
    EXPECT_LE(__int128{num} * limits.max_error.den, __int128{limits.max_error.num} * den) << e;
    EXPECT_GT(ins.cellCount(), previous) << e;  // a smaller error takes more tets
    previous = ins.cellCount();
    // The inserter's mesh is the Delaunay tetrahedralization of its vertices.
    const Box b{32, 32, 32};
    std::vector<GridPoint> pts;
    for (const auto& p : mesh.points) pts.push_back({int32_t(p[0]), int32_t(p[1]), int32_t(p[2])});
    Delaunay3 dt;
    ASSERT_TRUE(build(b, pts, &dt));
    std::vector<TetKey> ours;
    for (const auto& c : mesh.cells) {
      TetKey k;
      for (int i = 0; i < 4; ++i) k[i] = b.index(pts[c[i]]);
      std::sort(k.begin(), k.end());
      ours.push_back(k);
    }
    std::sort(ours.begin(), ours.end());
    EXPECT_EQ(ours, cgalTets(b, pts)) << e;
    if (std::string(e) == "10") expectLocallyDelaunay(dt);
  }
}

TEST(VolumeInserter, StagesOnlyAddVertices) {
  const SampleField field = ctCrop32();
  ASSERT_FALSE(field.values.empty());
  VolumeInserter ins(32, 32, 32);
  InsertionLimits limits;
  limits.max_error = bound("8");
  GridMesh before;
  ins.mesh(&before);
  EXPECT_EQ(before.points.size(), 8u);
  EXPECT_EQ(before.cells.size(), ins.cellCount());
  for (unsigned shift : {4u, 3u, 2u, 1u, 0u}) {
    std::string error;
    ASSERT_TRUE(ins.refine(field, shift, limits, &error)) << error;
    GridMesh after;
    ins.mesh(&after);
    ASSERT_GE(after.points.size(), before.points.size());
    // Points are listed in insertion order: the earlier set is a prefix.
    EXPECT_TRUE(std::equal(before.points.begin(), before.points.end(), after.points.begin())) << shift;
    for (const auto& p : after.points) {
      const uint32_t step = 1u << shift;
      for (int a = 0; a < 3; ++a)
        EXPECT_TRUE(p[a] % step == 0 || p[a] == 31 || std::find(before.points.begin(), before.points.end(), p) !=
                                                            before.points.end());
    }
    before = after;
  }
  expectWithin(before, field, limits.max_error);
  // Band by band ends within 10 % of one shot at the same error.
  VolumeInserter once(32, 32, 32);
  std::string error;
  ASSERT_TRUE(once.refine(field, 0, limits, &error));
  EXPECT_LE(ins.cellCount(), once.cellCount() * 11 / 10);
}

TEST(VolumeInserter, CanonicalOutputIsDeterministic) {
  const SampleField field = ctCrop32();
  ASSERT_FALSE(field.values.empty());
  std::vector<uint8_t> first;
  for (int run = 0; run < 2; ++run) {
    VolumeInserter ins(32, 32, 32);
    InsertionLimits limits;
    limits.max_error = bound("6");
    std::string error;
    ASSERT_TRUE(ins.refine(field, 1, limits, &error)) << error;
    ASSERT_TRUE(ins.refine(field, 0, limits, &error)) << error;
    GridMesh mesh;
    ins.mesh(&mesh);
    const std::vector<uint8_t> out = canonicalGridMeshOutput(mesh);
    if (run == 0) first = out;
    else EXPECT_EQ(out, first);
  }
}

TEST(VolumeInserter, TetLimitStopsTheStage) {
  const SampleField field = ctCrop32();
  ASSERT_FALSE(field.values.empty());
  VolumeInserter ins(32, 32, 32);
  InsertionLimits limits;
  limits.max_cells = 5000;
  std::string error;
  ASSERT_TRUE(ins.refine(field, 0, limits, &error)) << error;
  EXPECT_GE(ins.cellCount(), 5000u);
  EXPECT_LT(ins.cellCount(), 5200u);  // one insertion adds a few dozen at most
  int64_t num = 0, den = 0;
  ins.maxError(&num, &den);
  EXPECT_GT(num, 0);
  // The progress callback can stop it too, leaving a valid mesh.
  VolumeInserter stopped(32, 32, 32);
  limits.max_cells = 0;
  limits.max_error = bound("0");
  int calls = 0;
  ASSERT_TRUE(stopped.refine(field, 0, limits, &error, [&](uint64_t) { return ++calls < 2; }));
  EXPECT_EQ(calls, 2);
  GridMesh mesh;
  stopped.mesh(&mesh);
  EXPECT_EQ(mesh.points.size(), 8u + 2048u);
}

TEST(VolumeInserter, TrilinearDistanceHonoursTheErrorToo) {
  const SampleField field = ctCrop32();
  ASSERT_FALSE(field.values.empty());
  VolumeInserter ins(32, 32, 32);
  ins.setDistance(VolumeDistance::kTrilinear);
  InsertionLimits limits;
  limits.max_error = bound("10");
  std::string error;
  for (unsigned shift : {3u, 2u, 1u, 0u}) ASSERT_TRUE(ins.refine(field, shift, limits, &error)) << error;
  GridMesh mesh;
  ins.mesh(&mesh);
  expectWithin(mesh, field, limits.max_error);
}

TEST(VolumeInserter, RefusesWhatDoesNotFit) {
  SampleField field;
  field.size[0] = field.size[1] = field.size[2] = 4;
  field.values.assign(64, 1);
  InsertionLimits limits;
  std::string error;
  VolumeInserter ins(4, 4, 4);
  EXPECT_FALSE(ins.refine(field, 0, limits, &error));  // no limit
  EXPECT_NE(error.find("maximum error"), std::string::npos);
  limits.max_error = bound("1");
  EXPECT_TRUE(ins.refine(field, 0, limits, &error));
  EXPECT_EQ(ins.vertexCount(), 8u);  // a constant field needs only the corners
  EXPECT_EQ(ins.cellCount(), 6u);
  VolumeInserter other(4, 4, 5);
  EXPECT_FALSE(other.refine(field, 0, limits, &error));
  VolumeInserter flat(4, 4, 1);
  EXPECT_FALSE(flat.refine(field, 0, limits, &error));
  EXPECT_FALSE(error.empty());
}

TEST(VolumeInserter, WideValuesTakeThe128BitInterpolants) {
  // int32 samples of full range: max|v| x side^3 above 2^57.
  SampleField field;
  field.size[0] = field.size[1] = 5;
  field.size[2] = 600;
  std::mt19937 rng(5);
  for (int i = 0; i < 5 * 5 * 600; ++i) field.values.push_back(int32_t(rng()));
  VolumeInserter ins(5, 5, 600);
  InsertionLimits limits;
  limits.max_error = bound("100000000");
  std::string error;
  ASSERT_TRUE(ins.refine(field, 0, limits, &error)) << error;
  GridMesh mesh;
  ins.mesh(&mesh);
  expectWithin(mesh, field, limits.max_error);
}

}  // namespace
}  // namespace mrsv
