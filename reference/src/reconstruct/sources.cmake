# Mesh reconstructors (spec 8): adaptive meshes of decoded grids by Delaunay
# vertex insertion (2-D and 3-D) and quadtree vertex removal (2-D).
#   MRSV_RECONSTRUCT_SOURCES -> mrsv_decode (exact integer arithmetic, no dependencies)
set(MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/grid_mesh.cpp
  reference/src/reconstruct/grid_stages.cpp
  reference/src/reconstruct/delaunay2.cpp
  reference/src/reconstruct/line_insertion.cpp
  reference/src/reconstruct/terrain_insertion.cpp)
set(MRSV_RECONSTRUCT_TESTS
  reference/tests/grid_mesh_test.cpp
  reference/tests/terrain_insertion_test.cpp
  reference/tests/grid_mesh_checks.cpp)

# tools/bench/terrain_mesh_bench: issue 22's terrain goals beside Delatin and
# MARTINI (node, tools/bench/setup_peers.sh) in the same run.
function(mrsv_add_terrain_mesh_bench)
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_encode OR NOT TARGET GTest::gtest)
    return()
  endif()
  find_library(MRSV_TERRAIN_BENCH_ZSTD zstd)
  find_path(MRSV_TERRAIN_BENCH_ZSTD_INCLUDE zstd.h)
  if(NOT MRSV_TERRAIN_BENCH_ZSTD OR NOT MRSV_TERRAIN_BENCH_ZSTD_INCLUDE)
    return()
  endif()
  add_executable(terrain_mesh_bench tools/bench/terrain_mesh_bench.cpp reference/tests/grid_mesh_checks.cpp
                                    reference/tests/shared_data.cpp reference/tests/test_support.cpp)
  target_include_directories(terrain_mesh_bench PRIVATE reference/src reference/tests ${MRSV_TERRAIN_BENCH_ZSTD_INCLUDE})
  target_link_libraries(terrain_mesh_bench PRIVATE mrsv_encode mrsv_io ${MRSV_TERRAIN_BENCH_ZSTD} GTest::gtest)
  target_compile_definitions(terrain_mesh_bench PRIVATE MRSV_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data"
                                                        MRSV_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_terrain_mesh_bench)
endif()

# Quadtree vertex removal (spec 9).
list(APPEND MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/detail_signal.cpp
  reference/src/reconstruct/quadtree_border.cpp
  reference/src/reconstruct/quadtree_error.cpp
  reference/src/reconstruct/quadtree_mesh.cpp
  reference/src/reconstruct/quadtree_tree.cpp)
list(APPEND MRSV_RECONSTRUCT_TESTS
  reference/tests/quadtree_test.cpp)
