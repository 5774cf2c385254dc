// The split flags' contexts (spec 6.7.1): the decoder keeps each vertex's
// neighbour count from the split parameters alone, without walking rings.
// After every split of a stream those counts must be what the mesh's rings
// say, for splits of every shape (the terrain vector has boundary splits of
// all three kinds).
#include <gtest/gtest.h>

#include <string>

#include "pm/pm_state.h"
#include "test_support.h"

namespace mrsv {
namespace {

void expectContextsMatchRings(const std::string& vector) {
  const std::vector<uint8_t> bytes =
      test::readFileOrFail(std::string(MRSV_SOURCE_DIR) + "/conformance/vectors/coded_valid/" + vector);
  DecodedMesh decoded;
  const Error e = decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &decoded);
  ASSERT_TRUE(e.ok()) << vector << ": " << e.message;
  ProgressiveMesh::Impl& s = decoded.mesh.state();
  ASSERT_GT(s.splits.size(), 0u) << vector;
  ASSERT_EQ(s.flag_context.size(), s.table.vertexCount()) << vector;
  CornerTable::Ring ring;
  for (uint32_t v = 0; v < s.table.vertexCount(); ++v) {
    s.table.ring(v, &ring);
    ASSERT_EQ(s.flag_context[v], ProgressiveMesh::Impl::flagContext(ring.neighbours.size()))
        << vector << ": vertex " << v << (ring.boundary ? " (boundary)" : "");
  }
}

TEST(SplitFlags, ContextsAreTheNeighbourCountsAfterEverySplit) {
  for (const char* vector : {"mesh_cow.mrsv", "mesh_cow_free.mrsv", "mesh_terrain.mrsv", "mesh_cow_paper.mrsv"})
    expectContextsMatchRings(vector);
}

}  // namespace
}  // namespace mrsv
