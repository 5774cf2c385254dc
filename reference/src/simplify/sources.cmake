# Edge-collapse simplification (the PM encoder's first stage).
#   MRSV_SIMPLIFY_SOURCES -> mrsv_encode
#   MRSV_SIMPLIFY_TESTS   -> mrsv_mesh_tests
set(MRSV_SIMPLIFY_SOURCES
  reference/src/simplify/edge_topology.cpp
  reference/src/simplify/collapse_checks.cpp
  reference/src/simplify/collapse_costs.cpp
  reference/src/simplify/simplify.cpp)
set(MRSV_SIMPLIFY_TESTS
  reference/tests/simplify_test.cpp)
