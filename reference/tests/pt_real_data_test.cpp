// The PT pipeline on the real tet meshes: read (or built from the CT head and
// a PLOT3D grid), simplified, written, decoded. Every batch's level is a
// 3-manifold of positive tets; the finest level is the input; levels are
// reached again after moving away.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/tet_formats.h"
#include "pt/pt_encode.h"
#include "pt/pt_state.h"
#include "shared_data.h"
#include "tetsimplify/tet_simplify.h"

namespace mrsv {
namespace {

const std::string kTetData = std::string(MRSV_SHARED_DATA) + "/tet/";

TetMesh ctCrop() {
  test::SharedGrid grid;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst",
                                   &grid));
  GridCrop crop;
  const uint32_t origin[3] = {112, 112, 40};
  for (int a = 0; a < 3; ++a) {
    crop.origin[a] = origin[a];
    crop.size[a] = 32;
  }
  const double spacing[3] = {1, 1, 1};
  TetMesh mesh;
  TetBuildReport report;
  std::string error;
  EXPECT_TRUE(tetrahedralizeGrid(grid.header, grid.samples, spacing, crop, &mesh, &report, &error)) << error;
  return mesh;
}

TetMesh readTets(const std::string& name) {
  TetMesh mesh;
  std::string error;
  EXPECT_TRUE(readTetFile(kTetData + name, &mesh, nullptr, &error)) << error;
  return mesh;
}

// A single-grid PLOT3D pair as 5 tets per hexahedron, the density as the field.
TetMesh plot3dDensity(const std::string& name) {
  Plot3dData data;
  std::string error;
  EXPECT_TRUE(readPlot3d(kTetData + name + ".xyz", kTetData + name + ".q", &data, &error))
      << error;
  TetMesh mesh;
  TetBuildReport report;
  EXPECT_TRUE(tetrahedralizePlot3d(data, &mesh, &report, &error)) << error;
  mesh.fields.resize(1);  // density only: the test is about topology
  return mesh;
}

// Quantises (with the fewest bits from 16 that keep every tet positive),
// simplifies and writes `mesh`; decodes the stream.
void encodeAndDecode(const TetMesh& mesh, QuantizedTets* q, std::vector<uint8_t>* bytes, DecodedTetMesh* d) {
  Error e;
  for (int bits = 16; bits <= 24; bits += 2)
    if ((e = quantizeTetMesh(mesh, bits, 16, q)).ok()) break;
  ASSERT_TRUE(e.ok()) << e.message;
  QuantizedTetMesh input;
  input.positions = q->positions;
  input.tets = q->tets;
  for (const ScalarField& f : mesh.fields) input.fields.push_back(f.values);
  TetSimplifyResult result;
  e = simplifyTets(input, TetSimplifyOptions{}, &result);
  ASSERT_TRUE(e.ok()) << e.message;
  std::vector<std::vector<PtCollapse>> batches(result.batches.size());
  for (size_t b = 0; b < batches.size(); ++b)
    for (const TetCollapse& c : result.batches[b]) batches[b].push_back({c.vs, c.vt});
  e = writePtStream(*q, batches, bytes);
  ASSERT_TRUE(e.ok()) << e.message;
  e = decodeProgressiveTetMesh(bytes->data(), bytes->size(), DecodeOptions{}, d);
  ASSERT_TRUE(e.ok()) << e.describe();
}

void checkEveryBatchLevel(const std::string& name, const TetMesh& mesh) {
  SCOPED_TRACE(name);
  QuantizedTets q;
  std::vector<uint8_t> bytes;
  DecodedTetMesh d;
  encodeAndDecode(mesh, &q, &bytes, &d);
  if (::testing::Test::HasFatalFailure()) return;
  ProgressiveTetMesh& pt = d.mesh;
  EXPECT_EQ(pt.vertexCount(), mesh.positions.size());
  EXPECT_EQ(pt.tetCount(), mesh.tets.size());
  EXPECT_LT(pt.header().base_tet_count, mesh.tets.size() / 20) << "simplified too little";
  // The finest level holds the input's tets (as sets of positions).
  std::multiset<std::array<int32_t, 12>> in, out;
  auto key = [](const auto& p, Tet t) {
    std::sort(t.begin(), t.end(), [&](uint32_t a, uint32_t b) { return p[a] < p[b]; });
    std::array<int32_t, 12> k;
    for (int i = 0; i < 4; ++i)
      for (int a = 0; a < 3; ++a) k[3 * i + a] = p[t[i]][a];
    return k;
  };
  for (const Tet& t : q.tets) in.insert(key(q.positions, t));
  const auto& s = pt.state().mesh;
  for (const Tet& t : s.tets) out.insert(key(s.positions, t));
  EXPECT_EQ(in, out);
  // The level after each batch (the levels a prefix decodes to), reached by
  // moving down from the finest; a few of them also decoded as prefixes.
  std::vector<uint64_t> chunk_ends;
  for (const ChunkView& chunk : d.container.chunks)
    if (chunk.chunk_type == kChunkTetSplits || chunk.chunk_type == kChunkTetBase) chunk_ends.push_back(chunk.endOffset());
  ASSERT_EQ(chunk_ends.size(), pt.header().batch_count + 1u);
  std::vector<uint32_t> batch_levels{0};
  {
    uint32_t level = 0;
    for (uint32_t b = 0; b < pt.header().batch_count; ++b) {
      const ChunkView* chunk = nullptr;
      for (const ChunkView& c : d.container.chunks)
        if (c.endOffset() == chunk_ends[b + 1]) chunk = &c;
      level += chunk->payload[0] | chunk->payload[1] << 8 | chunk->payload[2] << 16 | chunk->payload[3] << 24;
      batch_levels.push_back(level);
    }
  }
  DecodeOptions partial;
  partial.container.allow_partial_tail = true;
  // The decoder checks every split; here the complex itself is checked at up
  // to 24 batch levels spread over the stream (and always the base).
  const size_t stride = batch_levels.size() / 24 + 1;
  for (size_t k = batch_levels.size(); k-- > 0;) {
    if (k % stride != 0 && k + 1 != batch_levels.size()) continue;
    pt.setLevel(batch_levels[k]);
    TetComplex c = pt.state().mesh;
    c.positions.resize(pt.vertexCount());
    c.buildIncidence();
    ASSERT_EQ(c.checkManifold(), "") << "level " << batch_levels[k];
    if (k % (4 * stride) == 0) {
      DecodedTetMesh prefix;
      ASSERT_TRUE(decodeProgressiveTetMesh(bytes.data(), chunk_ends[k], partial, &prefix).ok());
      ASSERT_EQ(prefix.mesh.level(), batch_levels[k]);
      ASSERT_EQ(canonicalTetMeshOutput(prefix.mesh), canonicalTetMeshOutput(pt)) << "prefix of batch " << k;
    }
  }
}

TEST(PtRealData, CtHeadCrop) { checkEveryBatchLevel("CT head 32^3", ctCrop()); }
TEST(PtRealData, Bunny) { checkEveryBatchLevel("bunny", readTets("bunny_5433v_34055tet.mesh")); }
TEST(PtRealData, Hand) { checkEveryBatchLevel("hand", readTets("hand_7234v_29998tet.mesh")); }
TEST(PtRealData, BluntFin) { checkEveryBatchLevel("blunt fin", plot3dDensity("bluntfin_plot3d_40x32x32_f32be")); }
TEST(PtRealData, CombustionChamber) {
  checkEveryBatchLevel("combustion chamber", plot3dDensity("combustion_chamber_plot3d_57x33x25_f32be"));
}

}  // namespace
}  // namespace mrsv
