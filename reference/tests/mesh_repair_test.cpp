// Mesh repair and validation: each rule on a tiny constructed mesh, random
// triangle soups against the validator, and what repair does to the real meshes.
#include "mrsv/mesh_repair.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "mrsv/mesh_formats.h"

namespace mrsv {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

TriangleMesh meshOf(size_t vertices, Triangles triangles) {
  TriangleMesh mesh;
  for (size_t v = 0; v < vertices; ++v)
    mesh.positions.push_back({static_cast<double>(v), static_cast<double>(v * v % 7), 0.5 * v});
  mesh.triangles = std::move(triangles);
  return mesh;
}

// A closed, consistently oriented tetrahedron.
const Triangles kTetrahedron = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};

bool repair(TriangleMesh* mesh, MeshRepairReport* report, std::string* error,
            MeshRepairOptions options = {}, std::vector<uint32_t>* origin = nullptr) {
  return repairMesh(mesh, options, report, origin, error);
}

TEST(MeshRepair, CleanMeshIsUnchanged) {
  TriangleMesh mesh = meshOf(4, kTetrahedron);
  const TriangleMesh before = mesh;
  MeshRepairReport report;
  std::string error;
  std::vector<uint32_t> origin;
  ASSERT_TRUE(repair(&mesh, &report, &error, {}, &origin)) << error;
  EXPECT_EQ(mesh.triangles, before.triangles);
  EXPECT_EQ(mesh.positions, before.positions);
  EXPECT_EQ(origin, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(report.components, 1u);
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(report.flipped_triangles + report.unused_vertices + report.vertices_added_by_split, 0u);
  EXPECT_EQ(describe(report), "4 -> 4 vertices, 4 -> 4 triangles; 0 boundary edges, 1 component");
  std::string message = "stale";
  EXPECT_TRUE(isOrientedManifold(mesh, &message));
  EXPECT_TRUE(message.empty());
}

TEST(MeshRepair, FlippedTriangleInAnOrientableComponentIsFixed) {
  for (size_t flipped = 0; flipped < 4; ++flipped) {
    TriangleMesh mesh = meshOf(4, kTetrahedron);
    std::swap(mesh.triangles[flipped][0], mesh.triangles[flipped][1]);
    std::string message;
    EXPECT_FALSE(isOrientedManifold(mesh, &message));
    EXPECT_NE(message.find("same direction (inconsistent orientation)"), std::string::npos) << message;
    MeshRepairReport report;
    std::string error;
    ASSERT_TRUE(repair(&mesh, &report, &error)) << error;
    EXPECT_EQ(report.inconsistent_edges, 3u);
    EXPECT_EQ(report.flipped_triangles, 1u);
    EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
    // The majority kept its orientation, so the flipped triangle was turned back.
    for (size_t t = 0; t < 4; ++t) {
      if (t == flipped) {
        // (b, a, c) flipped as (b, c, a): the same cyclic order as (a, b, c).
        const auto& got = mesh.triangles[t];
        const auto& want = kTetrahedron[t];
        bool same_cycle = false;
        for (int r = 0; r < 3; ++r)
          same_cycle |= got[0] == want[r] && got[1] == want[(r + 1) % 3] && got[2] == want[(r + 2) % 3];
        EXPECT_TRUE(same_cycle) << "triangle " << t;
      } else {
        EXPECT_EQ(mesh.triangles[t], kTetrahedron[t]);
      }
    }
  }
}

TEST(MeshRepair, InsideOutClosedComponentsAreCountedAndTurnedOnRequest) {
  TriangleMesh mesh;
  // The unit corner tetrahedron, far from the origin; kTetrahedron faces outwards on it.
  mesh.positions = {{1e6, 1e6, 1e6}, {1e6 + 1, 1e6, 1e6}, {1e6, 1e6 + 1, 1e6}, {1e6, 1e6, 1e6 + 1}};
  mesh.triangles = kTetrahedron;
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  // A second, open component facing either way is not counted.
  mesh.positions.push_back({0, 0, 0});
  mesh.positions.push_back({0, 1, 0});
  mesh.positions.push_back({1, 0, 0});
  mesh.triangles.push_back({4, 5, 6});
  const TriangleMesh inside_out = mesh;
  MeshRepairReport report;
  std::string error;
  ASSERT_TRUE(repair(&mesh, &report, &error)) << error;
  EXPECT_EQ(report.inward_closed_components, 1u);
  EXPECT_FALSE(report.inward_closed_turned);
  EXPECT_EQ(report.flipped_triangles, 0u);
  EXPECT_EQ(mesh.triangles, inside_out.triangles);
  EXPECT_NE(describe(report).find("1 inside-out closed components (left as they are)"),
            std::string::npos);
  MeshRepairOptions outward;
  outward.orient_closed_outward = true;
  ASSERT_TRUE(repair(&mesh, &report, &error, outward)) << error;
  EXPECT_TRUE(report.inward_closed_turned);
  EXPECT_EQ(report.flipped_triangles, 4u);
  EXPECT_EQ(Triangles(mesh.triangles.begin(), mesh.triangles.begin() + 4), kTetrahedron);
  EXPECT_EQ(mesh.triangles.back(), (std::array<uint32_t, 3>{4, 5, 6}));
  ASSERT_TRUE(repair(&mesh, &report, &error, outward)) << error;
  EXPECT_EQ(report.inward_closed_components, 0u);
  EXPECT_EQ(report.flipped_triangles, 0u);
}

TEST(MeshRepair, OrientationTieKeepsTheFirstTriangle) {
  // Two triangles sharing edge (1, 2), traversed the same way by both.
  TriangleMesh mesh = meshOf(4, {{0, 1, 2}, {3, 1, 2}});
  MeshRepairReport report;
  std::string error;
  ASSERT_TRUE(repair(&mesh, &report, &error)) << error;
  EXPECT_EQ(mesh.triangles, (Triangles{{0, 1, 2}, {3, 2, 1}}));
  EXPECT_EQ(report.flipped_triangles, 1u);
  EXPECT_EQ(report.boundary_edges, 4u);
}

// Two open cones (fans of 5 triangles) whose apexes are the same vertex 0.
Triangles twoConesAtVertex0() {
  Triangles t;
  for (uint32_t cone = 0; cone < 2; ++cone) {
    uint32_t base = 1 + 5 * cone;
    for (uint32_t k = 0; k < 5; ++k) t.push_back({0, base + k, base + (k + 1) % 5});
  }
  return t;
}

TEST(MeshRepair, TwoConesTouchingAtTheApexGetTheApexSplit) {
  TriangleMesh mesh = meshOf(11, twoConesAtVertex0());
  mesh.scalars.resize(11);
  for (size_t v = 0; v < 11; ++v) mesh.scalars[v] = 100.0 + v;
  std::string message;
  EXPECT_FALSE(isOrientedManifold(mesh, &message));
  EXPECT_NE(message.find("vertex 0 is non-manifold"), std::string::npos) << message;
  MeshRepairReport report;
  std::string error;
  std::vector<uint32_t> origin;
  ASSERT_TRUE(repair(&mesh, &report, &error, {}, &origin)) << error;
  EXPECT_EQ(report.nonmanifold_vertices, 1u);
  EXPECT_EQ(report.vertices_added_by_split, 1u);
  EXPECT_EQ(report.components, 2u);
  ASSERT_EQ(mesh.positions.size(), 12u);
  EXPECT_EQ(origin[11], 0u);
  EXPECT_EQ(mesh.positions[11], mesh.positions[0]);
  EXPECT_EQ(mesh.scalars[11], 100.0);
  EXPECT_EQ(mesh.scalars[10], 110.0);
  // The first cone keeps vertex 0, the second uses the copy.
  for (size_t t = 0; t < 10; ++t) EXPECT_EQ(mesh.triangles[t][0], t < 5 ? 0u : 11u);
  EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
}

TEST(MeshRepair, BowtieAndDoubleFanVertex) {
  // Two closed tetrahedra sharing vertex 0 only: vertex 0 has two disk fans.
  Triangles t = kTetrahedron;
  for (auto tri : kTetrahedron) {
    for (uint32_t& v : tri)
      if (v) v += 3;
    t.push_back(tri);
  }
  TriangleMesh mesh = meshOf(7, t);
  MeshRepairReport report;
  std::string error;
  ASSERT_TRUE(repair(&mesh, &report, &error)) << error;
  EXPECT_EQ(report.vertices_added_by_split, 1u);
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  std::string message;
  EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
}

TEST(MeshRepair, ThreeTrianglesOnOneEdgeAreAnErrorUnlessDetached) {
  const Triangles fin = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  TriangleMesh mesh = meshOf(5, fin);
  const TriangleMesh before = mesh;
  std::string message;
  EXPECT_FALSE(isOrientedManifold(mesh, &message));
  EXPECT_NE(message.find("edge (0, 1) is used by 3 triangles"), std::string::npos) << message;
  MeshRepairReport report;
  std::string error;
  EXPECT_FALSE(repair(&mesh, &report, &error));
  EXPECT_NE(error.find("edge (0, 1) is used by 3 triangles (0, 1, 2)"), std::string::npos) << error;
  EXPECT_EQ(mesh.triangles, before.triangles);
  EXPECT_EQ(mesh.positions, before.positions);

  MeshRepairOptions detach;
  detach.detach_overfull_edges = true;
  std::vector<uint32_t> origin;
  ASSERT_TRUE(repair(&mesh, &report, &error, detach, &origin)) << error;
  EXPECT_EQ(report.overfull_edges, 1u);
  EXPECT_EQ(report.detached_triangles, 1u);
  EXPECT_EQ(report.unused_vertices, 1u);  // vertex 4 was only in the detached triangle
  EXPECT_EQ(report.components, 2u);
  EXPECT_EQ(mesh.triangles, (Triangles{{0, 1, 2}, {1, 0, 3}, {4, 5, 6}}));
  EXPECT_EQ(origin, (std::vector<uint32_t>{0, 1, 2, 3, 0, 1, 4}));
  for (size_t v = 0; v < origin.size(); ++v) EXPECT_EQ(mesh.positions[v], before.positions[origin[v]]);
  EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
}

TEST(MeshRepair, DegenerateDuplicateAndUnusedAreDropped) {
  // A tetrahedron on vertices 0, 1, 2, 5 with a degenerate triangle, a copy
  // of a face in the other orientation, an exact copy, and unused vertices 3, 4, 6.
  Triangles t = {{0, 2, 1}, {3, 3, 5}, {0, 1, 3}, {1, 2, 3}, {3, 1, 0}, {2, 0, 3}, {1, 2, 3}};
  for (auto& tri : t)
    for (uint32_t& v : tri)
      if (v == 3) v = 5;
  TriangleMesh mesh = meshOf(7, t);
  MeshRepairReport report;
  std::string error;
  std::vector<uint32_t> origin;
  ASSERT_TRUE(repair(&mesh, &report, &error, {}, &origin)) << error;
  EXPECT_EQ(report.degenerate_triangles, 1u);
  EXPECT_EQ(report.duplicate_triangles, 2u);
  EXPECT_EQ(report.unused_vertices, 3u);
  EXPECT_EQ(origin, (std::vector<uint32_t>{0, 1, 2, 5}));
  EXPECT_EQ(mesh.triangles, kTetrahedron);
  EXPECT_NE(describe(report).find("3 unused vertices dropped; 1 degenerate triangles dropped; "
                                  "2 duplicate triangles dropped"),
            std::string::npos)
      << describe(report);
}

TEST(MeshRepair, MoebiusBandIsNotOrientable) {
  // A strip of 6 quads (12 triangles) whose ends are glued with a half twist.
  const uint32_t n = 6;
  Triangles t;
  for (uint32_t k = 0; k < n; ++k) {
    uint32_t a = k, b = k + n, c = (k + 1) % n, d = (k + 1) % n + n;
    if (k == n - 1) std::swap(c, d);  // the twist
    t.push_back({a, c, b});
    t.push_back({c, d, b});
  }
  TriangleMesh mesh = meshOf(2 * n, t);
  MeshRepairReport report;
  std::string error;
  EXPECT_FALSE(repair(&mesh, &report, &error));
  EXPECT_NE(error.find("cannot be oriented consistently"), std::string::npos) << error;
  MeshRepairOptions allow;
  allow.allow_non_orientable = true;
  ASSERT_TRUE(repair(&mesh, &report, &error, allow)) << error;
  EXPECT_EQ(report.non_orientable_components, 1u);
  EXPECT_EQ(report.flipped_triangles, 0u);
  std::string message;
  EXPECT_FALSE(isOrientedManifold(mesh, &message));
}

TEST(MeshRepair, InputErrorsAndValidatorMessages) {
  TriangleMesh mesh = meshOf(3, {{0, 1, 3}});
  MeshRepairReport report;
  std::string error;
  EXPECT_FALSE(repair(&mesh, &report, &error));
  EXPECT_NE(error.find("triangle 0: vertex index 3 is out of range"), std::string::npos) << error;
  std::string message;
  EXPECT_FALSE(isOrientedManifold(mesh, &message));
  EXPECT_NE(message.find("vertex index 3 is out of range"), std::string::npos) << message;
  mesh = meshOf(3, {{0, 1, 1}});
  EXPECT_FALSE(isOrientedManifold(mesh, &message));
  EXPECT_NE(message.find("triangle 0 is degenerate"), std::string::npos) << message;
  mesh = meshOf(3, {{0, 1, 2}});
  mesh.scalars = {1.0};
  EXPECT_FALSE(repair(&mesh, &report, &error));
  EXPECT_NE(error.find("1 scalars for 3 vertices"), std::string::npos) << error;
  EXPECT_TRUE(isOrientedManifold(meshOf(5, {}), nullptr));
}

// Random triangle soups on a few vertices hit every rule at once; whenever
// repair succeeds, the result must pass the validator and copy the right vertices.
TEST(MeshRepair, RandomSoupsComeOutOrientedManifold) {
  uint32_t seed = 2024;
  auto random = [&seed](uint32_t n) {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) % n;
  };
  int repaired = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const uint32_t vertices = 4 + random(12);
    Triangles t(1 + random(30));
    for (auto& tri : t)
      for (uint32_t& v : tri) v = random(vertices);
    TriangleMesh mesh = meshOf(vertices, t);
    mesh.scalars.resize(vertices);
    for (uint32_t v = 0; v < vertices; ++v) mesh.scalars[v] = v;
    const TriangleMesh before = mesh;
    MeshRepairOptions options;
    options.detach_overfull_edges = trial % 2 == 0;
    MeshRepairReport report;
    std::string error;
    std::vector<uint32_t> origin;
    if (!repairMesh(&mesh, options, &report, &origin, &error)) {
      EXPECT_FALSE(error.empty());
      EXPECT_EQ(mesh.triangles, before.triangles);
      continue;
    }
    ++repaired;
    std::string message;
    ASSERT_TRUE(isOrientedManifold(mesh, &message)) << "trial " << trial << ": " << message;
    ASSERT_EQ(origin.size(), mesh.positions.size());
    for (size_t v = 0; v < origin.size(); ++v) {
      ASSERT_EQ(mesh.positions[v], before.positions[origin[v]]);
      ASSERT_EQ(mesh.scalars[v], static_cast<double>(origin[v]));
    }
    EXPECT_EQ(report.output_triangles, mesh.triangles.size());
    EXPECT_EQ(report.input_triangles - report.degenerate_triangles - report.duplicate_triangles,
              mesh.triangles.size());
    // A second repair finds nothing to do.
    MeshRepairReport again;
    TriangleMesh copy = mesh;
    ASSERT_TRUE(repairMesh(&copy, options, &again, nullptr, &error)) << error;
    EXPECT_EQ(copy.triangles, mesh.triangles);
    EXPECT_EQ(again.flipped_triangles + again.vertices_added_by_split + again.detached_triangles +
                  again.unused_vertices,
              0u);
  }
  EXPECT_GT(repaired, 500);
}

// --- the shared real meshes ---------------------------------------------------

TEST(MeshRepairSharedData, BunnyWithoutItsUnusedVertices) {
  TriangleMesh mesh;
  std::string error;
  ASSERT_TRUE(readMeshFile(std::string(MRSV_SHARED_DATA) +
                               "/surface/bunny_stanford_zipper_35947v_69451tri.ply",
                           "confidence", &mesh, &error))
      << error;
  const std::vector<double> scalars = mesh.scalars;
  std::vector<uint32_t> origin;
  EXPECT_EQ(dropUnusedVertices(&mesh, &origin), 1113u);
  EXPECT_EQ(mesh.positions.size(), 34834u);
  EXPECT_EQ(mesh.triangles.size(), 69451u);
  ASSERT_EQ(mesh.scalars.size(), 34834u);
  for (size_t v = 0; v < origin.size(); ++v) ASSERT_EQ(mesh.scalars[v], scalars[origin[v]]);
}

TEST(MeshRepairSharedData, WhatRepairDoesToEachMesh) {
  const char* files[] = {"cow_viewpoint_2903v_5804tri.obj",
                         "fandisk_6475v_12946tri.obj",
                         "armadillo_stanford_decimated_43243v_86482tri.obj",
                         "bunny_stanford_zipper_35947v_69451tri.ply",
                         "horse_cyberware_48485v_96966tri_binbe.ply",
                         "turbine_blade_99519v_199034tri_binle.ply"};
  for (const char* file : files) {
    SCOPED_TRACE(file);
    TriangleMesh mesh;
    std::string error;
    ASSERT_TRUE(readMeshFile(std::string(MRSV_SHARED_DATA) + "/surface/" + file, "", &mesh, &error))
        << error;
    std::string message;
    const bool was_valid = isOrientedManifold(mesh, &message);
    MeshRepairOptions options;
    options.detach_overfull_edges = true;
    options.allow_non_orientable = true;
    MeshRepairReport report;
    ASSERT_TRUE(repairMesh(&mesh, options, &report, nullptr, &error)) << error;
    std::printf("[ repair   ] %s: %s%s\n", file, describe(report).c_str(),
                was_valid ? " (valid as read)" : (" (as read: " + message + ")").c_str());
    if (report.non_orientable_components == 0) {
      EXPECT_TRUE(isOrientedManifold(mesh, &message)) << message;
    }
  }
}

}  // namespace
}  // namespace mrsv
