# Surface distances (Metro-like Hausdorff, mean and RMS) with CGAL's AABB tree.
#   MRSV_METRICS_SOURCES      -> mrsv_metrics (uses CGAL; tools and tests only)
#   MRSV_METRICS_TOOL_SOURCES -> the mrsv executable (the compare subcommand)
#   MRSV_METRICS_TESTS        -> mrsv_mesh_tests
set(MRSV_METRICS_SOURCES)
set(MRSV_METRICS_TOOL_SOURCES)
set(MRSV_METRICS_TESTS)
