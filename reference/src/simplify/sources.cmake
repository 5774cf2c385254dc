# Edge-collapse simplification (the PM encoder's first stage).
#   MRSV_SIMPLIFY_SOURCES -> mrsv_encode
#   MRSV_SIMPLIFY_TESTS   -> mrsv_mesh_tests
set(MRSV_SIMPLIFY_SOURCES
  reference/src/simplify/edge_topology.cpp
  reference/src/simplify/collapse_checks.cpp
  reference/src/simplify/collapse_costs.cpp
  reference/src/simplify/deviation_guard.cpp
  reference/src/simplify/simplify.cpp)
set(MRSV_SIMPLIFY_TESTS
  reference/tests/simplify_test.cpp)

# tools/bench/simplify_bench: speed and quality against CGAL's Lindstrom-Turk.
# tools/bench/mesh_peers: one peer simplifier (CGAL Lindstrom-Turk, meshoptimizer)
# or MRSV's, timed, for tools/bench/mesh_bench.py; only when meshoptimizer is
# found (Debian libmeshoptimizer-dev), as the benchmark is optional.
# This file is included before the libraries exist, so the targets are added
# when the top-level directory has been processed.
function(mrsv_add_simplify_bench)
  if(MRSV_DECODER_ONLY OR NOT TARGET mrsv_encode OR NOT TARGET mrsv_io OR NOT TARGET CGAL::CGAL)
    return()
  endif()
  add_executable(simplify_bench tools/bench/simplify_bench.cpp)
  target_include_directories(simplify_bench PRIVATE reference/src)
  target_link_libraries(simplify_bench PRIVATE mrsv_encode mrsv_io CGAL::CGAL)

  find_package(meshoptimizer QUIET)
  if(TARGET meshoptimizer::meshoptimizer)
    add_executable(mesh_peers tools/bench/mesh_peers.cpp)
    target_include_directories(mesh_peers PRIVATE reference/src)
    target_link_libraries(mesh_peers PRIVATE mrsv_encode mrsv_io CGAL::CGAL meshoptimizer::meshoptimizer)
  else()
    message(STATUS "meshoptimizer not found: tools/bench/mesh_peers is not built (tools/bench/setup_peers.sh)")
  endif()
endfunction()
# (DEFER needs CMake 3.19; older ones simply build no bench.)
if(NOT MRSV_DECODER_ONLY AND CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL mrsv_add_simplify_bench)
endif()
