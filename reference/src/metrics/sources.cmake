# Surface distances (Metro-like Hausdorff, mean and RMS) with CGAL's AABB tree.
#   MRSV_METRICS_SOURCES      -> mrsv_metrics (uses CGAL; tools and tests only)
#   MRSV_METRICS_TOOL_SOURCES -> the mrsv executable (the compare subcommand)
#   MRSV_METRICS_TESTS        -> mrsv_mesh_tests
# surface_distance.cpp is the only file that includes CGAL's geometry headers.
set(MRSV_METRICS_SOURCES
  reference/src/metrics/surface_sampling.cpp
  reference/src/metrics/surface_distance.cpp)
set(MRSV_METRICS_TOOL_SOURCES
  tools/mrsv/cmd_compare.cpp)
set(MRSV_METRICS_TESTS
  reference/tests/surface_distance_test.cpp)
