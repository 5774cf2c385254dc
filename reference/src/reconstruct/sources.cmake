# Mesh reconstructors (spec 8): adaptive meshes of decoded grids by Delaunay
# vertex insertion (2-D and 3-D) and quadtree vertex removal (2-D).
#   MRSV_RECONSTRUCT_SOURCES -> mrsv_decode (exact integer arithmetic, no dependencies)
set(MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/grid_mesh.cpp
  reference/src/reconstruct/grid_stages.cpp
  reference/src/reconstruct/delaunay2.cpp
  reference/src/reconstruct/line_insertion.cpp
  reference/src/reconstruct/run_scan.cpp
  reference/src/reconstruct/terrain_insertion.cpp
  reference/src/reconstruct/delaunay3.cpp
  reference/src/reconstruct/volume_insertion.cpp)
set(MRSV_RECONSTRUCT_TESTS
  reference/tests/grid_mesh_test.cpp
  reference/tests/terrain_insertion_test.cpp
  reference/tests/grid_mesh_checks.cpp
  reference/tests/volume_insertion_test.cpp)

# Quadtree vertex removal (spec 9).
list(APPEND MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/detail_signal.cpp
  reference/src/reconstruct/quadtree_border.cpp
  reference/src/reconstruct/quadtree_error.cpp
  reference/src/reconstruct/quadtree_mesh.cpp
  reference/src/reconstruct/quadtree_removal.cpp
  reference/src/reconstruct/quadtree_tree.cpp
  reference/src/reconstruct/border_cleanup.cpp)
list(APPEND MRSV_RECONSTRUCT_TESTS
  reference/tests/quadtree_test.cpp)

# The benchmarks of issue 22, peers in the same run: terrain_mesh_bench against
# Delatin and MARTINI (node, tools/bench/setup_peers.sh), volume_insertion_bench
# against CGAL's Delaunay_triangulation_3, which the tests also use for their
# checks: CGAL for them, never for mrsv_decode.
function(mrsv_add_reconstruct_benches)
  if(MRSV_DECODER_ONLY OR NOT TARGET CGAL::CGAL OR NOT TARGET mrsv_encode OR NOT TARGET GTest::gtest)
    return()
  endif()
  if(TARGET mrsv_reconstruct_tests)
    target_link_libraries(mrsv_reconstruct_tests PRIVATE CGAL::CGAL)
  endif()
  find_library(MRSV_RECONSTRUCT_BENCH_ZSTD zstd)
  find_path(MRSV_RECONSTRUCT_BENCH_ZSTD_INCLUDE zstd.h)
  if(NOT MRSV_RECONSTRUCT_BENCH_ZSTD OR NOT MRSV_RECONSTRUCT_BENCH_ZSTD_INCLUDE)
    return()
  endif()
  # shared_data.cpp (the real grids of ../shared/data) reports through GoogleTest.
  add_executable(terrain_mesh_bench tools/bench/terrain_mesh_bench.cpp reference/tests/grid_mesh_checks.cpp
                                    reference/tests/shared_data.cpp reference/tests/test_support.cpp)
  target_link_libraries(terrain_mesh_bench PRIVATE mrsv_encode mrsv_io)
  add_executable(volume_insertion_bench tools/bench/volume_insertion_bench.cpp reference/tests/shared_data.cpp
                                        reference/tests/test_support.cpp)
  target_link_libraries(volume_insertion_bench PRIVATE mrsv_decode CGAL::CGAL)
  foreach(bench terrain_mesh_bench volume_insertion_bench)
    target_include_directories(${bench} PRIVATE reference/src reference/tests ${MRSV_RECONSTRUCT_BENCH_ZSTD_INCLUDE})
    target_link_libraries(${bench} PRIVATE ${MRSV_RECONSTRUCT_BENCH_ZSTD} GTest::gtest)
    target_compile_definitions(${bench} PRIVATE MRSV_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data"
                                                MRSV_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  endforeach()
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_reconstruct_benches)
endif()
