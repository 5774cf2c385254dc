// spec 8.1 to 8.3: the sample field, the error bound and the canonical output
// that every reconstructor shares.
#include "mrsv/grid_mesh.h"

#include <gtest/gtest.h>

#include <string>

namespace mrsv {
namespace {

TEST(ErrorBound, ParsesDecimalsExactly) {
  ErrorBound b;
  ASSERT_TRUE(parseErrorBound("20", &b));
  EXPECT_EQ(b.num, 20);
  EXPECT_EQ(b.den, 1);
  ASSERT_TRUE(parseErrorBound("2.50", &b));
  EXPECT_EQ(b.num, 25);  // 2.50 -> 250/100, reduced by tens only
  EXPECT_EQ(b.den, 10);
}

TEST(ErrorBound, RefusesWhatIsNotADecimal) {
  ErrorBound b;
  for (const char* bad : {"", ".", "-1", "1e3", "1.2.3", "0.1234567891", "2147483649", "nan"})
    EXPECT_FALSE(parseErrorBound(bad, &b)) << bad;
  EXPECT_TRUE(parseErrorBound("0", &b));
  EXPECT_EQ(b.num, 0);
  EXPECT_TRUE(parseErrorBound(".5", &b));
}

GridMesh twoTriangles() {
  GridMesh m;
  m.dims = 2;
  m.size[0] = 3, m.size[1] = 2, m.size[2] = 1;
  m.points = {{2, 1, 0}, {0, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  m.values = {40, 10, 20, 30};
  m.cells = {{1, 2, 0, 0}, {0, 3, 1, 0}};
  return m;
}

TEST(CanonicalGridMesh, IndependentOfStoredOrder) {
  GridMesh a = twoTriangles();
  GridMesh b = a;
  // Same mesh, points and cells listed differently and triangles rotated.
  b.points = {{0, 0, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  b.values = {10, 30, 20, 40};
  b.cells = {{1, 0, 3, 0}, {3, 0, 2, 0}};
  EXPECT_EQ(canonicalGridMeshOutput(a), canonicalGridMeshOutput(b));
  const auto out = canonicalGridMeshOutput(a);
  const std::string line = "mrsv-canonical-grid-mesh 1 2 4 2\n";
  ASSERT_GE(out.size(), line.size());
  EXPECT_EQ(std::string(out.begin(), out.begin() + line.size()), line);
  EXPECT_EQ(out.size(), line.size() + 4 * 16 + 2 * 12);
  // First vertex: (0, 0, 0) value 10; first cell: 0 1 3 (vertices in index order 0:(0,0) 1:(2,0) 2:(0,1) 3:(2,1)).
  const size_t cells = line.size() + 4 * 16;
  EXPECT_EQ(out[cells], 0);
  EXPECT_EQ(out[cells + 4], 1);
  EXPECT_EQ(out[cells + 8], 3);
}

TEST(CanonicalGridMesh, TetsKeepTheirOrientation) {
  GridMesh m;
  m.dims = 3;
  m.size[0] = m.size[1] = m.size[2] = 2;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.values = {1, 2, 3, 4};
  m.cells = {{1, 0, 2, 3}};  // odd permutation of 0 1 2 3
  const auto out = canonicalGridMeshOutput(m);
  const size_t cells = out.size() - 16;
  EXPECT_EQ(out[cells + 0], 0);
  EXPECT_EQ(out[cells + 4], 1);
  EXPECT_EQ(out[cells + 8], 3);
  EXPECT_EQ(out[cells + 12], 2);
}

TEST(GridMeshGeometry, ReadsSpacingAndOrigin) {
  Metadata meta;
  meta.set("spacing", "30,-30");
  meta.set("origin", "557970,5121870");
  GridMeshGeometry g;
  std::string error;
  ASSERT_TRUE(gridMeshGeometryFromMetadata(meta, 2, &g, &error)) << error;
  EXPECT_EQ(g.spacing[1], -30);
  EXPECT_EQ(g.origin[0], 557970);
  meta.set("spacing", "30;30");
  EXPECT_FALSE(gridMeshGeometryFromMetadata(meta, 2, &g, &error));
  EXPECT_NE(error.find("spacing"), std::string::npos);
  // A mirrored map keeps its triangles facing up.
  GridMesh m = twoTriangles();
  g.spacing[0] = 30, g.spacing[1] = -30;
  TriangleMesh t = gridMeshToTriangles(m, g);
  const auto& p = t.positions;
  const auto& f = t.triangles[0];
  const double nz = (p[f[1]][0] - p[f[0]][0]) * (p[f[2]][1] - p[f[0]][1]) -
                    (p[f[1]][1] - p[f[0]][1]) * (p[f[2]][0] - p[f[0]][0]);
  EXPECT_GT(nz, 0);
}

}  // namespace
}  // namespace mrsv
