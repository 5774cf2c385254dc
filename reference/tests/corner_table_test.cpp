// Vertex splits and edge collapses on the corner table (spec 6.6): random
// valid splits keep an oriented manifold, and collapses undo them exactly.
#include <gtest/gtest.h>

#include <random>

#include "mesh/corner_table.h"

namespace mrsv {
namespace {

// A closed octahedron and an open square fan (boundary everywhere but the centre).
std::vector<std::array<uint32_t, 3>> octahedron() {
  return {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {5, 2, 1}, {5, 3, 2}, {5, 4, 3}, {5, 1, 4}};
}
std::vector<std::array<uint32_t, 3>> squareFan() {
  return {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
}

void randomSplits(uint32_t vertices, const std::vector<std::array<uint32_t, 3>>& tris, uint32_t seed) {
  CornerTable table;
  ASSERT_EQ(table.build(vertices, tris), "");
  std::mt19937 rng(seed);
  struct Done {
    uint32_t vs;
    uint32_t a, b;
    CornerTable::SplitShape shape;
    std::vector<std::array<uint32_t, 3>> before, after;
  };
  std::vector<Done> done;
  CornerTable::Ring ring;
  for (int step = 0; step < 400; ++step) {
    uint32_t vs = rng() % table.vertexCount();
    table.ring(vs, &ring);
    uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
    uint32_t a = rng() % d, b = rng() % d;
    CornerTable::SplitShape shape{true, true};
    if (ring.boundary) {
      int kind = rng() % 3;
      shape = {kind != 1, kind != 2};
    }
    if (!splitPositionsValid(ring.boundary, d, a, b, shape)) continue;
    Done record{vs, a, b, shape, table.triangles(), {}};
    const uint32_t t0 = table.triangleCount();
    table.split(vs, ring, a, b, shape);
    ASSERT_EQ(table.validate(), "") << "after split " << step;
    ASSERT_EQ(table.triangleCount(), t0 + record.shape.has_g1 + record.shape.has_g2);
    record.after = table.triangles();
    done.push_back(record);
  }
  ASSERT_GT(done.size(), 100u);
  for (size_t i = done.size(); i-- > 0;) {
    table.collapseLast(done[i].vs, done[i].shape);
    ASSERT_EQ(table.validate(), "");
    ASSERT_EQ(table.triangles(), done[i].before);
  }
  EXPECT_EQ(table.triangles(), tris);
  // Splitting again after the undo (as a level switch does) finds the same
  // rings, so the same positions give the same mesh at every step.
  for (const Done& record : done) {
    table.ring(record.vs, &ring);
    table.split(record.vs, ring, record.a, record.b, record.shape);
    ASSERT_EQ(table.validate(), "");
    ASSERT_EQ(table.triangles(), record.after);
  }
}

TEST(CornerTable, RandomSplitsOnClosedMeshUndoExactly) {
  for (uint32_t seed = 1; seed <= 20; ++seed) randomSplits(6, octahedron(), seed);
}
TEST(CornerTable, RandomSplitsWithBoundaryUndoExactly) {
  for (uint32_t seed = 1; seed <= 20; ++seed) randomSplits(5, squareFan(), seed);
}

TEST(CornerTable, RingsAreCanonical) {
  CornerTable table;
  ASSERT_EQ(table.build(6, octahedron()), "");
  CornerTable::Ring ring;
  table.ring(0, &ring);
  EXPECT_FALSE(ring.boundary);
  EXPECT_EQ(ring.neighbours, (std::vector<uint32_t>{1, 2, 3, 4}));
  ASSERT_EQ(table.build(5, squareFan()), "");
  table.ring(1, &ring);  // boundary: faces (1, 2, 0) and (1, 0, 4)... fan 2, 0, 4
  EXPECT_TRUE(ring.boundary);
  EXPECT_EQ(ring.neighbours, (std::vector<uint32_t>{2, 0, 4}));
}

TEST(CornerTable, RejectsBrokenConnectivity) {
  CornerTable table;
  EXPECT_NE(table.build(4, {{0, 1, 2}, {0, 1, 3}}), "");                       // same direction
  EXPECT_NE(table.build(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), "");            // 3 faces on an edge
  EXPECT_NE(table.build(7, {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}}), "");            // bow-tie vertex
  EXPECT_NE(table.build(4, {{0, 1, 2}}), "");                                  // unused vertex
  EXPECT_NE(table.build(3, {{0, 0, 2}}), "");                                  // degenerate
}

}  // namespace
}  // namespace mrsv
