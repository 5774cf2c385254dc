// The grid of a move of vs (spec 6.7.3 step 1, decision D33): its shift from
// the ring, and what the encoder's slides onto it keep. On a real mesh the
// full-resolution mesh must come back exactly whatever the grid (the slides
// only change coarser levels), the stream must be smaller with it, the
// coarser levels must keep their connectivity, and a vertex that slid must
// have moved by a fraction of its ring (at most a quarter of its longest
// ring edge).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "pm/pm_records.h"
#include "simplify/simplify.h"

namespace mrsv {
namespace {

TEST(MoveGrid, ShiftIsHalfTheLog2OfTheLongestSquaredEdgeLessTheDetail) {
  EXPECT_EQ(pm::moveShift(int64_t{1} << 20, 0), 0);             // no detail: every step
  EXPECT_EQ(pm::moveShift(0, 4), 0);                            // a ring collapsed to a point
  EXPECT_EQ(pm::moveShift(int64_t{1} << 20, 4), 6);             // edge 1024: units of 64
  EXPECT_EQ(pm::moveShift((int64_t{1} << 22) - 1, 4), 6);       // log2 21.99: floor 21, halved 10
  EXPECT_EQ(pm::moveShift(int64_t{1} << 22, 4), 7);             // edge 2048
  EXPECT_EQ(pm::moveShift(255, 4), 0);                          // edge below 16: no grid
  EXPECT_EQ(pm::moveShift(int64_t{3} << 60, 29), 1);            // about the largest L2 of 30-bit positions: log2 61.6
}

struct Encoded {
  std::vector<uint8_t> bytes;
  DecodedMesh decoded;
};

Encoded encodeCow(uint8_t move_detail) {
  TriangleMesh mesh;
  std::string error;
  EXPECT_TRUE(readMeshFile(std::string(MRSV_SHARED_DATA) + "/surface/cow_viewpoint_2903v_5804tri.obj", "",
                           &mesh, &error))
      << error;
  MeshRepairReport report;
  std::vector<uint32_t> origin;
  EXPECT_TRUE(repairMesh(&mesh, MeshRepairOptions{}, &report, &origin, &error)) << error;
  SimplifyOptions simplify;
  simplify.placement = Placement::kFree;
  SimplifyResult collapses;
  EXPECT_TRUE(simplifyMesh(mesh, simplify, &collapses, &error)) << error;
  PmEncodeOptions options;
  options.placement = Placement::kFree;
  options.position_bits = 12;
  options.move_detail = move_detail;
  Encoded out;
  PmEncodeReport encode_report;
  EXPECT_TRUE(encodeProgressiveMesh(mesh, collapses, options, Metadata{}, &out.bytes, &encode_report, &error))
      << error;
  const Error e = decodeProgressiveMesh(out.bytes.data(), out.bytes.size(), DecodeOptions{}, &out.decoded);
  EXPECT_TRUE(e.ok()) << e.message;
  return out;
}

TEST(MoveGrid, SlidesKeepTheFullMeshAndStayNearThePlanes) {
  Encoded exact = encodeCow(0);
  Encoded grid = encodeCow(4);
  ASSERT_EQ(exact.decoded.header.move_detail, 0);
  ASSERT_EQ(grid.decoded.header.move_detail, 4);
  EXPECT_LT(grid.bytes.size(), exact.bytes.size());
  ProgressiveMesh& a = exact.decoded.mesh;
  ProgressiveMesh& b = grid.decoded.mesh;
  ASSERT_EQ(a.splitsDecoded(), b.splitsDecoded());
  EXPECT_EQ(canonicalMeshOutput(a), canonicalMeshOutput(b)) << "the full mesh must not depend on the grid";
  // The same collapses, so every level has the same connectivity; only the
  // positions of vertices that slid differ, each by little against the
  // vertex's ring (a slide is a fraction of the longest ring edge along the
  // plane, and at most a step off it).
  const uint32_t levels[] = {0, a.splitsDecoded() / 100, a.splitsDecoded() / 10};
  int moved = 0, compared = 0;
  for (uint32_t level : levels) {
    a.setLevel(level);
    b.setLevel(level);
    const ProgressiveMesh::Impl& sa = a.state();
    const ProgressiveMesh::Impl& sb = b.state();
    ASSERT_EQ(sa.table.triangles(), sb.table.triangles()) << "level " << level;
    CornerTable::Ring ring;
    for (uint32_t v = 0; v < sa.table.vertexCount(); ++v) {
      ++compared;
      if (sa.positions[v] == sb.positions[v]) continue;
      ++moved;
      sa.table.ring(v, &ring);
      const int64_t longest = pm::longestFaceEdge2(sa.positions, ring);
      EXPECT_LE(pm::squaredDistance(sa.positions[v], sb.positions[v]) * 16, longest + 16)
          << "level " << level << ", vertex " << v << " slid more than a quarter of its longest ring edge";
    }
  }
  EXPECT_GT(moved, 0) << "no vertex slid: the grid was never used";
  EXPECT_LT(moved, compared);
}

}  // namespace
}  // namespace mrsv
