// spec 8.3 to 8.7: the 2-D Delaunay core against CGAL, and greedy insertion
// on real terrains: valid triangulations, the error bound on every sample,
// the border rule across two tiles, stages that only add vertices.
#include "mrsv/terrain_insertion.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "grid_mesh_checks.h"
#include "mrsv/quadtree_mesh.h"
#include "reconstruct/candidate_queue.h"
#include "reconstruct/delaunay2.h"
#include "reconstruct/quadtree_error.h"
#include "reconstruct/quadtree_removal.h"

namespace mrsv {
namespace {

using reconstruct::Delaunay2;
using reconstruct::Point2;
using Tri = std::array<int32_t, 6>;  // three (x, y) corners, smallest first, counter-clockwise

Tri canonicalTri(Point2 a, Point2 b, Point2 c) {
  Point2 p[3] = {a, b, c};
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (reconstruct::lexLess(p[i], p[m])) m = i;
  return {p[m].x, p[m].y, p[(m + 1) % 3].x, p[(m + 1) % 3].y, p[(m + 2) % 3].x, p[(m + 2) % 3].y};
}

// `rank` gives each point's rank (spec 8.3) from its coordinates.
template <class Rank>
std::vector<Tri> ourTriangles(const std::vector<Point2>& pts, int32_t mx, int32_t my, Rank&& rank) {
  const uint64_t corners[4] = {rank(Point2{0, 0}), rank(Point2{mx, 0}), rank(Point2{mx, my}), rank(Point2{0, my})};
  Delaunay2 dt(mx, my, corners);
  std::vector<uint32_t> touched;
  uint32_t hint = 0;
  for (Point2 p : pts) {
    const bool corner = (p.x == 0 || p.x == mx) && (p.y == 0 || p.y == my);
    if (corner) continue;
    hint = dt.locate(p, hint);
    touched.clear();
    dt.insert(p, rank(p), hint, &touched);
    hint = touched.front();
  }
  std::vector<Tri> out;
  for (uint32_t t = 0; t < dt.triangleCount(); ++t) {
    const auto& v = dt.triangle(t);
    out.push_back(canonicalTri(dt.point(v[0]), dt.point(v[1]), dt.point(v[2])));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Tri> cgalTriangles(const std::vector<Point2>& pts) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Delaunay_triangulation_2<K> dt;
  for (Point2 p : pts) dt.insert(K::Point_2(p.x, p.y));
  std::vector<Tri> out;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    Point2 c[3];
    for (int i = 0; i < 3; ++i) c[i] = {int32_t(f->vertex(i)->point().x()), int32_t(f->vertex(i)->point().y())};
    out.push_back(canonicalTri(c[0], c[1], c[2]));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Grid points are as cocircular as points get: the perturbation decides. With
// ranks in lexicographic order it must decide as CGAL's
// Delaunay_triangulation_2 does (the same Devillers-Teillaud rule), whatever
// the insertion order.
TEST(Delaunay2, SameTrianglesAsCgalOnDegenerateGridSubsets) {
  std::mt19937 rng(2211);
  for (int trial = 0; trial < 40; ++trial) {
    const int32_t mx = 8 + trial % 25, my = 6 + (trial * 7) % 27;
    std::vector<Point2> pts = {{0, 0}, {mx, 0}, {mx, my}, {0, my}};
    const double keep = (trial % 4 + 1) / 4.0;
    std::uniform_real_distribution<double> u(0, 1);
    for (int32_t y = 0; y <= my; ++y)
      for (int32_t x = 0; x <= mx; ++x)
        if (!((x == 0 || x == mx) && (y == 0 || y == my)) && u(rng) < keep) pts.push_back({x, y});
    std::vector<Point2> shuffled(pts.begin() + 4, pts.end());
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    const auto lex = [&](Point2 p) { return uint64_t(p.x) * 1000 + uint64_t(p.y); };
    const auto ours = ourTriangles(shuffled, mx, my, lex);
    const auto theirs = cgalTriangles(pts);
    ASSERT_EQ(ours, theirs) << "trial " << trial << ": " << mx << " x " << my << ", " << pts.size() << " points";
  }
}

// Any ranks make the triangulation unique: the same for every insertion order.
TEST(Delaunay2, InsertionOrderDoesNotMatterForGivenRanks) {
  std::mt19937 rng(7);
  std::vector<Point2> pts;
  for (int32_t y = 0; y <= 20; ++y)
    for (int32_t x = 0; x <= 30; ++x)
      if ((x * 7 + y * 3) % 5 != 0 || x == 0 || y == 0) pts.push_back({x, y});
  std::vector<uint64_t> ranks(31 * 21);
  for (size_t i = 0; i < ranks.size(); ++i) ranks[i] = i;
  std::shuffle(ranks.begin(), ranks.end(), rng);
  const auto rank = [&](Point2 p) { return ranks[size_t(p.y) * 31 + size_t(p.x)]; };
  const auto first = ourTriangles(pts, 30, 20, rank);
  for (int k = 0; k < 5; ++k) {
    std::shuffle(pts.begin(), pts.end(), rng);
    EXPECT_EQ(ourTriangles(pts, 30, 20, rank), first);
  }
  // Other ranks may give another of the (many) Delaunay triangulations.
  const auto lex = [&](Point2 p) { return uint64_t(p.x) * 1000 + uint64_t(p.y); };
  EXPECT_NE(ourTriangles(pts, 30, 20, lex), first);
}

GridMesh insertionMesh(const SampleField& f, const char* error, bool border = true, uint64_t cells = 0) {
  TerrainInserter ins(f.size[0], f.size[1]);
  InsertionLimits limits;
  if (error) {
    EXPECT_TRUE(parseErrorBound(error, &limits.max_error));
  }
  limits.max_cells = cells;
  limits.border_rule = border;
  std::string problem;
  EXPECT_TRUE(ins.refine(f, 0, limits, &problem)) << problem;
  GridMesh m;
  ins.mesh(&m);
  return m;
}

TEST(TerrainInsertion, ErrorBoundHoldsOnEverySampleOfRealTerrains) {
  const SampleField helens = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 317, 460);
  const SampleField fuji = test::terrainCrop("srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", 441, 304, 460, 378);
  for (const SampleField* f : {&helens, &fuji}) {
    size_t previous = SIZE_MAX;
    for (const char* e : {"1", "5", "20", "50"}) {
      for (bool border : {true, false}) {
        const GridMesh m = insertionMesh(*f, e, border);
        EXPECT_EQ(test::triangulationProblem(m), "") << e;
        ErrorBound b;
        parseErrorBound(e, &b);
        double worst = 0;
        EXPECT_TRUE(test::withinBoundEverywhere(*f, m, b, &worst)) << e << " m: " << worst;
        EXPECT_LE(worst, double(b.num) / b.den);
        if (border) {
          EXPECT_LT(m.cells.size(), previous) << e;
          previous = m.cells.size();
        }
      }
    }
  }
}

// spec 8.8: the removal pass after insertion keeps the bound on every sample
// and the border's vertices (so tiles still meet), and leaves far fewer
// triangles (measured 0.54 to 0.70 x on the bench's crops, D84).
TEST(TerrainInsertion, RemovalPassKeepsTheBoundAndTheBorder) {
  const SampleField helens = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 317, 460);
  const SampleField fuji = test::terrainCrop("srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", 441, 304, 460, 378);
  for (const SampleField* f : {&helens, &fuji})
    for (const char* e : {"1", "5", "20", "50"})
      for (bool rule : {true, false}) {
        SCOPED_TRACE(std::string(e) + (rule ? " m, border rule" : " m"));
        const GridMesh inserted = insertionMesh(*f, e, rule);
        GridMesh m = inserted;
        ErrorBound b;
        parseErrorBound(e, &b);
        uint64_t removed = 0;
        std::string problem;
        ASSERT_TRUE(removeInnerVertices(*f, b, &m, &removed, &problem)) << problem;
        EXPECT_EQ(test::triangulationProblem(m), "");
        double worst = 0;
        EXPECT_TRUE(test::withinBoundEverywhere(*f, m, b, &worst)) << worst;
        EXPECT_EQ(test::borderPoints(m), test::borderPoints(inserted));
        EXPECT_EQ(m.points.size() + removed, inserted.points.size());
        EXPECT_LT(m.cells.size(), inserted.cells.size() * 4 / 5);
      }
}

// spec 8.8's border cleanup: the bound on every sample, the sides' vertices
// kept, fewer triangles; and run on the sub-mesh around the border zone it
// gives the mesh the same pass run on the whole mesh gives.
TEST(TerrainInsertion, BorderCleanupKeepsTheBoundAndTheBorder) {
  const SampleField helens = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 317, 460);
  const SampleField fuji = test::terrainCrop("srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", 441, 304, 460, 378);
  uint64_t removed_total = 0;
  for (const SampleField* f : {&helens, &fuji})
    for (const char* e : {"1", "5", "20", "50"}) {
      SCOPED_TRACE(std::string(e) + " m");
      const GridMesh inserted = insertionMesh(*f, e, true);
      ErrorBound b;
      parseErrorBound(e, &b);
      GridMesh m = inserted;
      uint64_t removed = 0;
      std::string problem;
      ASSERT_TRUE(cleanBorderZone(*f, b, &m, &removed, &problem)) << problem;
      EXPECT_EQ(test::triangulationProblem(m), "");
      double worst = 0;
      EXPECT_TRUE(test::withinBoundEverywhere(*f, m, b, &worst)) << worst;
      EXPECT_EQ(test::borderPoints(m), test::borderPoints(inserted));
      EXPECT_EQ(m.points.size() + removed, inserted.points.size());
      EXPECT_EQ(m.cells.size() + 2 * removed, inserted.cells.size());
      GridMesh whole = inserted;
      quadtree::RemovalReport report;
      quadtree::removeVertices(quadtree::ErrorTest(*f, b), &whole, quadtree::kBorderCleanup, &report);
      EXPECT_EQ(report.removed, removed);
      EXPECT_TRUE(canonicalGridMeshOutput(whole) == canonicalGridMeshOutput(m));
      removed_total += removed;
    }
  EXPECT_GT(removed_total, 100u);
}

TEST(TerrainInsertion, TriangleCountLimit) {
  const SampleField f = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 257, 257);
  const GridMesh m = insertionMesh(f, nullptr, false, 5000);
  EXPECT_EQ(test::triangulationProblem(m), "");
  EXPECT_GE(m.cells.size(), 5000u);
  EXPECT_LE(m.cells.size(), 5002u);
}

// spec 8.6: two windows sharing a column, meshed apart, have the same
// vertices on it, so their meshes meet without cracks.
TEST(TerrainInsertion, BorderRuleMakesAdjacentTilesMeet) {
  const char* file = "big_tujunga_1197x643_int16le.raw.zst";
  const SampleField left = test::terrainCrop(file, 300, 100, 257, 257);
  const SampleField right = test::terrainCrop(file, 556, 100, 257, 257);
  const SampleField below = test::terrainCrop(file, 300, 356, 257, 257);
  for (const char* e : {"1", "5", "20", "50"}) {
    const GridMesh a = insertionMesh(left, e), b = insertionMesh(right, e), c = insertionMesh(below, e);
    std::set<uint32_t> a_right, b_left, a_bottom, c_top;
    for (const auto& p : a.points) {
      if (p[0] == 256) a_right.insert(p[1]);
      if (p[1] == 256) a_bottom.insert(p[0]);
    }
    for (const auto& p : b.points)
      if (p[0] == 0) b_left.insert(p[1]);
    for (const auto& p : c.points)
      if (p[1] == 0) c_top.insert(p[0]);
    EXPECT_EQ(a_right, b_left) << e;
    EXPECT_EQ(a_bottom, c_top) << e;
    EXPECT_GT(a_right.size(), 2u) << e;
  }
}

// spec 8.7: stages on coarser lattices first only add vertices, and end
// within the bound with few more triangles than one stage.
TEST(TerrainInsertion, StagesOnlyAddVertices) {
  const SampleField f = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 317, 460);
  for (const char* e : {"5", "20"}) {
    InsertionLimits limits;
    parseErrorBound(e, &limits.max_error);
    TerrainInserter ins(f.size[0], f.size[1]);
    std::set<std::array<uint32_t, 3>> previous;
    std::string problem;
    for (int shift = 4; shift >= 0; --shift) {
      ASSERT_TRUE(ins.refine(f, shift, limits, &problem)) << problem;
      GridMesh m;
      ins.mesh(&m);
      std::set<std::array<uint32_t, 3>> now(m.points.begin(), m.points.end());
      EXPECT_TRUE(std::includes(now.begin(), now.end(), previous.begin(), previous.end()));
      for (const auto& p : m.points) {
        const bool lattice = (p[0] % (1u << shift) == 0 || p[0] == f.size[0] - 1) &&
                             (p[1] % (1u << shift) == 0 || p[1] == f.size[1] - 1);
        EXPECT_TRUE(lattice) << shift;
      }
      previous = std::move(now);
    }
    GridMesh last;
    ins.mesh(&last);
    double worst = 0;
    EXPECT_TRUE(test::withinBoundEverywhere(f, last, limits.max_error, &worst));
    const GridMesh single = insertionMesh(f, e);
    EXPECT_LE(last.cells.size(), single.cells.size() * 11 / 10) << e;
  }
}

// maxError() scans the triangles again: without the border rule (whose side
// samples the scans leave out) it is the largest error of every sample,
// whether the bound or a triangle count stopped the insertion.
TEST(TerrainInsertion, MaxErrorIsTheLargestSampleError) {
  const SampleField f = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 257, 257);
  for (const char* e : {"5", static_cast<const char*>(nullptr)}) {
    TerrainInserter ins(f.size[0], f.size[1]);
    InsertionLimits limits;
    if (e) parseErrorBound(e, &limits.max_error);
    else limits.max_cells = 3000;
    limits.border_rule = false;
    std::string problem;
    ASSERT_TRUE(ins.refine(f, 0, limits, &problem)) << problem;
    GridMesh m;
    ins.mesh(&m);
    double worst = 0;
    test::withinBoundEverywhere(f, m, ErrorBound{1000000, 1}, &worst);
    EXPECT_GT(worst, 1.0);
    EXPECT_NEAR(ins.maxError(), worst, 1e-9 * worst) << (e ? e : "3000 triangles");
  }
}

// Samples that fit 16 bits are scanned from a 16-bit copy (with AVX2 where
// the CPU has it), others from the field: the same terrain times 1000, with
// the bound times 1000, has every error times 1000 and so the same mesh.
TEST(TerrainInsertion, WideSamplesGiveTheSameMesh) {
  const SampleField f = test::terrainCrop("srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", 441, 304, 460, 378);
  SampleField wide = f;
  for (int32_t& v : wide.values) v *= 1000;
  for (const auto& [e, wide_e] : {std::pair{"1", "1000"}, {"20", "20000"}}) {
    GridMesh narrow_mesh = insertionMesh(f, e), wide_mesh = insertionMesh(wide, wide_e);
    EXPECT_EQ(narrow_mesh.points, wide_mesh.points) << e;
    EXPECT_EQ(narrow_mesh.cells, wide_mesh.cells) << e;
  }
}

// An exact heap entry's error back from its key alone, in lowest terms:
// random errors and the extremes.
TEST(CandidateQueue, ExactErrorFromItsKey) {
  std::mt19937_64 rng(8);
  std::vector<std::pair<int64_t, int64_t>> errors = {
      {1, 1}, {1, (1 << 20) - 1}, {(1 << 30) - 1, 1}, {(1 << 30) - 1, (1 << 20) - 1}, {(1 << 30) - 2, (1 << 20) - 2}};
  for (int i = 0; i < 100000; ++i) errors.push_back({int64_t(rng() % ((1 << 30) - 1)) + 1, int64_t(rng() % ((1 << 20) - 1)) + 1});
  for (const auto& [num, den] : errors) {
    const double key = double(num) / double(den);
    uint64_t bits;
    std::memcpy(&bits, &key, sizeof bits);
    int64_t n = 0, d = 0;
    reconstruct::CandidateQueue::exactError(bits, &n, &d);
    const int64_t g = std::gcd(num, den);
    ASSERT_EQ(n, num / g) << num << " / " << den;
    ASSERT_EQ(d, den / g) << num << " / " << den;
  }
}

// The queue's order (spec 8.5: larger error, then smaller sample) with exact
// entries, which keep only their key, sample and den, against inexact ones
// of the same errors (num and den times 2^21): every tie between the two
// kinds goes to the exact comparison. Cells are set, set again and removed
// at random; the top is always the worst of those left.
TEST(CandidateQueue, OrderOfExactAndInexactEntries) {
  std::mt19937_64 rng(22);
  reconstruct::CandidateQueue queue;
  queue.clear();
  std::map<uint32_t, reconstruct::Candidate> live;
  const auto random = [&] {
    reconstruct::Candidate c;
    c.den = int64_t(rng() % 64) + 1;
    c.num = __int128(rng() % (64 * c.den)) + 1;
    c.sample = rng() % 50;
    if (rng() % 3 == 0) c.num <<= 21, c.den <<= 21;
    return c;
  };
  for (int step = 0; step < 20000; ++step) {
    const uint32_t cell = uint32_t(rng() % 300);
    if (rng() % 4 == 0) {
      queue.remove(cell);
      live.erase(cell);
    } else {
      const reconstruct::Candidate c = random();
      queue.set(cell, c);
      live[cell] = c;
    }
    if (step % 7 == 0 && !live.empty()) {
      auto worst = live.begin();
      for (auto it = live.begin(); it != live.end(); ++it)
        if (reconstruct::worse(it->second, worst->second) ||
            (!reconstruct::worse(worst->second, it->second) && it->first > worst->first))
          worst = it;
      ASSERT_FALSE(queue.empty());
      EXPECT_EQ(queue.topSample(), worst->second.sample) << step;
      const reconstruct::Candidate& top = live.at(queue.top());
      EXPECT_FALSE(reconstruct::worse(worst->second, top)) << step;
    }
  }
}

TEST(TerrainInsertion, CanonicalOutputIsRepeatable) {
  const SampleField f = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 30, 40, 129, 200);
  EXPECT_EQ(canonicalGridMeshOutput(insertionMesh(f, "3.5")), canonicalGridMeshOutput(insertionMesh(f, "3.5")));
}

TEST(TerrainInsertion, RefusesAFieldOfAnotherSize) {
  const SampleField f = test::terrainCrop("mt_st_helens_317x460_int16le.raw.zst", 0, 0, 65, 65);
  TerrainInserter ins(64, 65);
  InsertionLimits limits;
  parseErrorBound("1", &limits.max_error);
  std::string error;
  EXPECT_FALSE(ins.refine(f, 0, limits, &error));
  EXPECT_NE(error, "");
  TerrainInserter ok(65, 65);
  EXPECT_FALSE(ok.refine(f, 0, InsertionLimits{}, &error));
}

}  // namespace
}  // namespace mrsv
