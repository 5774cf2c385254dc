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
  reference/tests/tet_metric_meshes.cpp)

# tools/bench/tet_peer_bench: CGAL's Tetrahedral_remeshing coarsening a tet
# mesh to 50/20/10/5 % of its tets, measured with the tet metrics (the peer of
# issue 21's quality goal). Its tet meshes come from the tests' helper until
# the tet formats and generators are in the library. Added once the
# libraries exist, as simplify/sources.cmake does.
function(mrsv_add_tet_peer_bench)
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_metrics)
    return()
  endif()
  find_library(MRSV_TET_BENCH_ZSTD zstd)
  find_path(MRSV_TET_BENCH_ZSTD_INCLUDE zstd.h)
  if(NOT MRSV_TET_BENCH_ZSTD OR NOT MRSV_TET_BENCH_ZSTD_INCLUDE)
    message(STATUS "libzstd not found: tools/bench/tet_peer_bench is not built")
    return()
  endif()
  add_executable(tet_peer_bench tools/bench/tet_peer_bench.cpp tools/bench/tet_cgal_peer.cpp
                                reference/tests/tet_metric_meshes.cpp)
  target_include_directories(tet_peer_bench PRIVATE reference/src reference/tests
                                                    ${MRSV_TET_BENCH_ZSTD_INCLUDE})
  target_link_libraries(tet_peer_bench PRIVATE mrsv_metrics ${MRSV_TET_BENCH_ZSTD})
  target_compile_definitions(tet_peer_bench PRIVATE
    MRSV_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data")
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_tet_peer_bench)
endif()
