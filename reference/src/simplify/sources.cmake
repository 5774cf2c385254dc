# Edge-collapse simplification (the PM encoder's first stage).
#   MRSV_SIMPLIFY_SOURCES -> mrsv_encode
#   MRSV_SIMPLIFY_TESTS   -> mrsv_mesh_tests
set(MRSV_SIMPLIFY_SOURCES)
set(MRSV_SIMPLIFY_TESTS)
