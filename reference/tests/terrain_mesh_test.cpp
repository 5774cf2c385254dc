// Terrain to mesh on real terrain crops (one with voids) and on tiny grids
// that pin down the diagonal rule and the orientation.
#include "mrsv/terrain_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mrsv/grid_formats.h"
#include "mrsv/mesh_repair.h"
#include "test_support.h"

namespace mrsv {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

GridInput readCrop(const char* name, bool voids) {
  RawLayout layout;
  layout.has_layout = true;
  layout.header.num_dims = 2;
  layout.header.size_x = layout.header.size_y = 128;
  layout.header.sample_type = SampleType::kInt16;
  if (voids) {
    layout.header.grid_flags = kGridFlagHasNodata;
    layout.header.nodata_bits = 0x8000;  // -32768
  }
  GridInput in;
  std::string error;
  EXPECT_TRUE(readGridInput(test::sourcePath(std::string("demo/data/") + name), layout, &in, &error))
      << error;
  return in;
}

// The z component of the triangle's normal (twice its signed area in x-y).
double normalZ(const TriangleMesh& mesh, const std::array<uint32_t, 3>& t) {
  const auto& a = mesh.positions[t[0]];
  const auto& b = mesh.positions[t[1]];
  const auto& c = mesh.positions[t[2]];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

TEST(TerrainMesh, MountStHelensCropIsAClosedDiskFacingUp) {
  GridInput in = readCrop("mt_st_helens_128x128_int16le.raw", false);
  TerrainMeshOptions options;
  options.spacing_x = options.spacing_y = 30.0;
  TriangleMesh mesh;
  std::string error;
  ASSERT_TRUE(terrainToMesh(in.header, in.samples, options, &mesh, &error)) << error;
  EXPECT_EQ(mesh.positions.size(), 128u * 128u);
  EXPECT_EQ(mesh.triangles.size(), 2u * 127u * 127u);
  for (const auto& t : mesh.triangles) ASSERT_GT(normalZ(mesh, t), 0.0);
  // Vertex (i, j) = sample j*128 + i, unscaled height.
  int16_t sample;
  std::memcpy(&sample, in.samples.data() + 2 * (5 * 128 + 7), 2);
  EXPECT_EQ(mesh.positions[5 * 128 + 7], (std::array<double, 3>{7 * 30.0, 5 * 30.0, static_cast<double>(sample)}));
  std::string message;
  EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
  TriangleMesh copy = mesh;
  MeshRepairReport report;
  ASSERT_TRUE(repairMesh(&copy, {}, &report, nullptr, &error)) << error;
  EXPECT_EQ(report.boundary_edges, 4u * 127u);
  EXPECT_EQ(report.components, 1u);
  EXPECT_EQ(copy.triangles, mesh.triangles);
}

TEST(TerrainMesh, VoidsOfTheFujiSummitCropAreSkipped) {
  GridInput in = readCrop("mt_fuji_summit_128x128_int16le.raw", true);
  std::vector<bool> valid(128 * 128);
  int voids = 0;
  for (size_t s = 0; s < valid.size(); ++s) {
    int16_t v;
    std::memcpy(&v, in.samples.data() + 2 * s, 2);
    valid[s] = v != -32768;
    voids += !valid[s];
  }
  ASSERT_EQ(voids, 50);  // as the crop's SOURCES.md says
  size_t cells = 0;
  std::vector<bool> used(valid.size());
  for (size_t j = 0; j + 1 < 128; ++j)
    for (size_t i = 0; i + 1 < 128; ++i) {
      size_t s = j * 128 + i;
      if (valid[s] && valid[s + 1] && valid[s + 128] && valid[s + 129]) {
        ++cells;
        used[s] = used[s + 1] = used[s + 128] = used[s + 129] = true;
      }
    }
  TriangleMesh mesh;
  std::string error;
  TerrainMeshOptions options;
  options.spacing_y = -1.0;  // north up
  options.z_scale = 0.001;   // kilometres
  ASSERT_TRUE(terrainToMesh(in.header, in.samples, options, &mesh, &error)) << error;
  EXPECT_LT(cells, 127u * 127u);
  EXPECT_EQ(mesh.triangles.size(), 2 * cells);
  EXPECT_EQ(mesh.positions.size(), static_cast<size_t>(std::count(used.begin(), used.end(), true)));
  for (const auto& p : mesh.positions) {
    ASSERT_GT(p[2], 0.0);  // no void height, scaled or not
    ASSERT_LT(p[2], 3.8);  // Fuji is 3,776 m
  }
  for (const auto& t : mesh.triangles) ASSERT_GT(normalZ(mesh, t), 0.0);
  MeshRepairReport report;
  ASSERT_TRUE(repairMesh(&mesh, {}, &report, nullptr, &error)) << error;
  EXPECT_EQ(report.unused_vertices, 0u);
  std::printf("[ terrain  ] fuji summit crop: %s\n", describe(report).c_str());
}

GridHeader smallHeader(uint32_t w, uint32_t h, SampleType type) {
  GridHeader header;
  header.num_dims = 2;
  header.size_x = w;
  header.size_y = h;
  header.sample_type = type;
  return header;
}

std::vector<uint8_t> floatSamples(const std::vector<float>& values) {
  std::vector<uint8_t> bytes(values.size() * 4);
  std::memcpy(bytes.data(), values.data(), bytes.size());  // the test machines are little-endian
  return bytes;
}

TEST(TerrainMesh, DiagonalJoinsTheCloserHeightsTiesTakeTheMainDiagonal) {
  // Corners 00, 10 / 01, 11 of one cell.
  struct Case {
    std::vector<float> values;
    Triangles expected;
  } cases[] = {
      {{0, 5, 7, 1}, {{0, 1, 3}, {0, 3, 2}}},  // |00-11| = 1 < |10-01| = 2
      {{0, 5, 6, 9}, {{0, 1, 2}, {1, 3, 2}}},  // |00-11| = 9 > |10-01| = 1
      {{0, 5, 5, 1}, {{0, 1, 2}, {1, 3, 2}}},  // |00-11| = 1 > |10-01| = 0
      {{0, 2, 4, 2}, {{0, 1, 3}, {0, 3, 2}}},  // tie, 2 and 2: the main diagonal
  };
  for (const Case& c : cases) {
    TriangleMesh mesh;
    std::string error;
    ASSERT_TRUE(terrainToMesh(smallHeader(2, 2, SampleType::kFloat32), floatSamples(c.values), {},
                              &mesh, &error))
        << error;
    EXPECT_EQ(mesh.triangles, c.expected) << c.values[0] << " " << c.values[1] << " " << c.values[2]
                                          << " " << c.values[3];
    for (const auto& t : mesh.triangles) EXPECT_GT(normalZ(mesh, t), 0.0);
  }
}

TEST(TerrainMesh, EveryMirroringStillFacesUp) {
  for (double sx : {1.0, -2.0})
    for (double sy : {0.5, -1.0}) {
      TerrainMeshOptions options;
      options.spacing_x = sx;
      options.spacing_y = sy;
      options.z_scale = -3.0;
      TriangleMesh mesh;
      std::string error;
      ASSERT_TRUE(terrainToMesh(smallHeader(3, 3, SampleType::kFloat32),
                                floatSamples({0, 1, 4, 2, 8, 3, 1, 1, 0}), options, &mesh, &error))
          << error;
      ASSERT_EQ(mesh.triangles.size(), 8u);
      for (const auto& t : mesh.triangles) EXPECT_GT(normalZ(mesh, t), 0.0) << sx << " " << sy;
      EXPECT_EQ(mesh.positions[5], (std::array<double, 3>{2 * sx, 1 * sy, -9.0}));
      std::string message;
      EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
    }
}

TEST(TerrainMesh, NodataAndNonFiniteSamplesDropTheirCells) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // 3x3 grid: the centre is NaN, so no cell survives and no vertex is emitted.
  TriangleMesh mesh;
  std::string error;
  ASSERT_TRUE(terrainToMesh(smallHeader(3, 3, SampleType::kFloat32),
                            floatSamples({0, 1, 2, 3, nan, 5, 6, 7, 8}), {}, &mesh, &error))
      << error;
  EXPECT_TRUE(mesh.positions.empty());
  EXPECT_TRUE(mesh.triangles.empty());
  // uint8 with nodata 255 in a corner: 3 of 4 cells stay, the corner vertex goes.
  GridHeader header = smallHeader(3, 3, SampleType::kUint8);
  header.grid_flags = kGridFlagHasNodata;
  header.nodata_bits = 255;
  ASSERT_TRUE(terrainToMesh(header, {255, 1, 2, 3, 4, 5, 6, 7, 8}, {}, &mesh, &error)) << error;
  EXPECT_EQ(mesh.triangles.size(), 6u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  EXPECT_EQ(mesh.positions[0], (std::array<double, 3>{1, 0, 1}));
}

TEST(TerrainMesh, RejectsWhatIsNotATerrain) {
  TriangleMesh mesh;
  std::string error;
  GridHeader volume = smallHeader(2, 2, SampleType::kUint8);
  volume.num_dims = 3;
  volume.size_z = 2;
  EXPECT_FALSE(terrainToMesh(volume, std::vector<uint8_t>(8), {}, &mesh, &error));
  EXPECT_NE(error.find("needs a 2-D grid"), std::string::npos) << error;
  EXPECT_FALSE(terrainToMesh(smallHeader(2, 2, SampleType::kInt16), std::vector<uint8_t>(7), {},
                             &mesh, &error));
  EXPECT_NE(error.find("7 bytes of samples, but 2x2 int16 needs 8"), std::string::npos) << error;
  TerrainMeshOptions flat;
  flat.spacing_x = 0;
  EXPECT_FALSE(terrainToMesh(smallHeader(2, 2, SampleType::kUint8), std::vector<uint8_t>(4), flat,
                             &mesh, &error));
  EXPECT_NE(error.find("spacings must be finite and not zero"), std::string::npos) << error;
}

}  // namespace
}  // namespace mrsv
