// The grid points the PM encoder gives the input's vertices (decision D34):
// the point of the 27 around the nearest one that leaves the surface least.
// On a real mesh with a boundary (the bunny's holes), at 14 bits, the full
// mesh must come back nearer the input than plainly rounded positions are:
// a much smaller RMS distance, and a largest distance no larger.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "metrics/surface_distance.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "simplify/simplify.h"

namespace mrsv {
namespace {

SurfaceDistanceReport distanceFrom(const TriangleMesh& input, const TriangleMesh& output) {
  SurfaceDistanceOptions options;
  options.sampling.sample_count = 200000;
  options.sampling.seed = 1;
  options.threads = 1;
  SurfaceDistanceReport report;
  std::string error;
  EXPECT_TRUE(measureSurfaceDistance(input, output, options, &report, &error)) << error;
  return report;
}

TEST(GridPoints, TheFullMeshIsNearerTheSurfaceThanRoundedPositions) {
  TriangleMesh input;
  std::string error;
  ASSERT_TRUE(readMeshFile(std::string(MRSV_SHARED_DATA) + "/surface/bunny_stanford_zipper_35947v_69451tri.ply",
                           "", &input, &error))
      << error;
  MeshRepairReport repair;
  std::vector<uint32_t> origin;
  ASSERT_TRUE(repairMesh(&input, MeshRepairOptions{}, &repair, &origin, &error)) << error;
  SimplifyResult collapses;
  ASSERT_TRUE(simplifyMesh(input, SimplifyOptions{}, &collapses, &error)) << error;
  PmEncodeOptions options;
  options.position_bits = 14;
  std::vector<uint8_t> bytes;
  PmEncodeReport encode_report;
  ASSERT_TRUE(encodeProgressiveMesh(input, collapses, options, Metadata{}, &bytes, &encode_report, &error)) << error;
  DecodedMesh decoded;
  const Error e = decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &decoded);
  ASSERT_TRUE(e.ok()) << e.message;
  const TriangleMesh coded = decoded.mesh.mesh();
  ASSERT_EQ(coded.triangles.size(), input.triangles.size());

  // The same grid, each vertex at its nearest point.
  TriangleMesh rounded = input;
  const PmHeader& h = decoded.header;
  for (auto& p : rounded.positions)
    for (int k = 0; k < 3; ++k) p[k] = h.origin[k] + std::nearbyint((p[k] - h.origin[k]) / h.position_step) * h.position_step;

  const SurfaceDistanceReport ours = distanceFrom(input, coded);
  const SurfaceDistanceReport plain = distanceFrom(input, rounded);
  // Measured: RMS 0.62 of plain rounding's, the largest distance 0.97 of it.
  EXPECT_LT(ours.rms, 0.75 * plain.rms);
  EXPECT_LE(ours.hausdorff, plain.hausdorff);
}

}  // namespace
}  // namespace mrsv
