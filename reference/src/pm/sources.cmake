# Progressive meshes (spec 6): the PM stream decoder, encoder and their tests.
#   MRSV_PM_DECODE_SOURCES -> mrsv_decode (no dependencies)
#   MRSV_PM_ENCODE_SOURCES -> mrsv_encode
#   MRSV_PM_TESTS          -> mrsv_mesh_tests
set(MRSV_PM_DECODE_SOURCES
  reference/src/mesh/corner_table.cpp
  reference/src/pm/pm_header.cpp
  reference/src/pm/progressive_mesh.cpp
  reference/src/pm/pm_decode.cpp)
set(MRSV_PM_ENCODE_SOURCES
  reference/src/pm/pm_encode.cpp)
set(MRSV_PM_TESTS
  reference/tests/corner_table_test.cpp
  reference/tests/split_flags_test.cpp
  reference/tests/move_grid_test.cpp
  reference/tests/grid_point_test.cpp)

# tools/bench/pm_decode_bench: Google Benchmark of decoding and level switching
# on streams built from the shared meshes, so it needs the encoder and mrsv_io.
# Added once the top-level directory has been processed (the libraries and
# MRSV_SHARED_DATA exist then), as simplify_bench is.
function(mrsv_add_pm_decode_bench)
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_encode OR NOT TARGET mrsv_io)
    return()
  endif()
  find_package(benchmark QUIET)
  if(NOT benchmark_FOUND)
    return()
  endif()
  set(data "${MRSV_SHARED_DATA}")
  if(NOT data)
    set(data "${PROJECT_SOURCE_DIR}/../shared/data")
  endif()
  add_executable(pm_decode_bench tools/bench/pm_decode_bench.cpp)
  target_include_directories(pm_decode_bench PRIVATE reference/src)
  target_link_libraries(pm_decode_bench PRIVATE mrsv_encode mrsv_io benchmark::benchmark)
  target_compile_definitions(pm_decode_bench PRIVATE MRSV_SHARED_DATA="${data}")
endfunction()
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_pm_decode_bench)
endif()
