# Tet-mesh simplification (the PT encoder's first stage, issue 21).
#   MRSV_TETSIMPLIFY_SOURCES -> mrsv_encode
#   MRSV_TETSIMPLIFY_TESTS   -> mrsv_mesh_tests
set(MRSV_TETSIMPLIFY_SOURCES
  reference/src/tetsimplify/exact_predicates.cpp
  reference/src/tetsimplify/tet_complex.cpp
  reference/src/tetsimplify/link_condition.cpp
  reference/src/tetsimplify/boundary_index.cpp
  reference/src/tetsimplify/tet_costs.cpp
  reference/src/tetsimplify/tet_quality.cpp
  reference/src/tetsimplify/tet_replay.cpp
  reference/src/tetsimplify/tet_simplify.cpp)
set(MRSV_TETSIMPLIFY_TESTS
  reference/tests/tet_simplify_test.cpp
  reference/tests/tet_test_meshes.cpp)

# tools/bench/tet_simplify_bench: build time, collapses per second, batch
# sizes and scalar PSNR per level of the CT crop (and the LOX post).
function(mrsv_add_tet_simplify_bench)
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_encode OR NOT TARGET mrsv_io OR NOT ZSTD_LIBRARY)
    return()
  endif()
  add_executable(tet_simplify_bench tools/bench/tet_simplify_bench.cpp reference/tests/tet_test_meshes.cpp)
  target_include_directories(tet_simplify_bench PRIVATE reference/src reference/tests ${ZSTD_INCLUDE_DIR})
  target_link_libraries(tet_simplify_bench PRIVATE mrsv_encode mrsv_io ${ZSTD_LIBRARY})
  target_compile_definitions(tet_simplify_bench PRIVATE MRSV_SHARED_DATA="${MRSV_SHARED_DATA}")
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_tet_simplify_bench)
endif()
