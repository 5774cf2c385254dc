# Progressive tetrahedral meshes (spec 7): the PT stream decoder, encoder and their tests.
#   MRSV_PT_DECODE_SOURCES -> mrsv_decode (no dependencies)
#   MRSV_PT_ENCODE_SOURCES -> mrsv_encode
set(MRSV_PT_DECODE_SOURCES
  reference/src/tetmesh/tet_complex.cpp
  reference/src/tetmesh/star_link.cpp
  reference/src/tetmesh/vertex_split.cpp
  reference/src/tetmesh/star_split.cpp
  reference/src/pt/pt_header.cpp
  reference/src/pt/progressive_tet_mesh.cpp
  reference/src/pt/pt_decode.cpp)
set(MRSV_PT_ENCODE_SOURCES
  reference/src/pt/pt_encode.cpp)
set(MRSV_PT_TESTS
  reference/tests/pt_stream_test.cpp
  reference/tests/incidence_lists_test.cpp
  reference/tests/pt_real_data_test.cpp
  reference/tests/shared_data.cpp)

# tools/bench/pt_decode_bench: decoding alone from stream files, for the
# decode speed goal and profiling; it needs only the decoder.
add_executable(pt_decode_bench tools/bench/pt_decode_bench.cpp)
target_link_libraries(pt_decode_bench PRIVATE mrsv_decode)

# tools/bench/pt_bench: issue 21's measured goals (build, size, decode,
# levels) beside xz -9 and CGAL's Tetrahedral_remeshing in the same run.
function(mrsv_add_pt_bench)
  # shared_data.cpp (the CT head from ../shared/data) reports through GoogleTest.
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_metrics OR NOT TARGET mrsv_io OR NOT TARGET GTest::gtest)
    return()
  endif()
  find_library(MRSV_PT_BENCH_ZSTD zstd)
  find_path(MRSV_PT_BENCH_ZSTD_INCLUDE zstd.h)
  if(NOT MRSV_PT_BENCH_ZSTD OR NOT MRSV_PT_BENCH_ZSTD_INCLUDE)
    return()
  endif()
  add_executable(pt_bench tools/bench/pt_bench.cpp tools/bench/tet_cgal_peer.cpp tools/bench/cgal_delaunay_peer.cpp
                          reference/tests/shared_data.cpp reference/tests/test_support.cpp)
  target_include_directories(pt_bench PRIVATE reference/src reference/tests tools/bench ${MRSV_PT_BENCH_ZSTD_INCLUDE})
  target_link_libraries(pt_bench PRIVATE mrsv_encode mrsv_io mrsv_metrics ${MRSV_PT_BENCH_ZSTD} GTest::gtest)
  target_compile_definitions(pt_bench PRIVATE MRSV_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data"
                                             MRSV_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_pt_bench)
endif()
