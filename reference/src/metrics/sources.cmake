# Surface distances (Metro-like Hausdorff, mean and RMS) with CGAL's AABB tree.
#   MRSV_METRICS_SOURCES      -> mrsv_metrics (uses CGAL; tools and tests only)
#   MRSV_METRICS_TOOL_SOURCES -> the mrsv executable (the compare subcommand)
#   MRSV_METRICS_TESTS        -> mrsv_mesh_tests
# Tet-mesh metrics (mrsv/tet_metrics.h, issue 21): point location, field PSNR,
# volume, boundary, quality and validity checks.
# CGAL's headers are included by surface_distance.cpp, tet_predicates.cpp and
# tet_self_intersection.cpp only (they are slow to compile).
set(MRSV_METRICS_SOURCES
  reference/src/metrics/surface_sampling.cpp
  reference/src/metrics/surface_distance.cpp
  reference/src/metrics/tet_check.cpp
  reference/src/metrics/tet_predicates.cpp
  reference/src/metrics/tet_faces.cpp
  reference/src/metrics/tet_boundary.cpp
  reference/src/metrics/tet_locator.cpp
  reference/src/metrics/tet_manifold.cpp
  reference/src/metrics/tet_self_intersection.cpp
  reference/src/metrics/tet_quality.cpp
  reference/src/metrics/tet_field_probe.cpp
  reference/src/metrics/tet_field_error.cpp
  reference/src/metrics/tet_compare.cpp)
set(MRSV_METRICS_TOOL_SOURCES
  tools/mrsv/cmd_compare.cpp)
set(MRSV_METRICS_TESTS
  reference/tests/surface_distance_test.cpp
  reference/tests/tet_metrics_test.cpp
  reference/tests/tet_test_meshes.cpp)
