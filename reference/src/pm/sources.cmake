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
  reference/tests/corner_table_test.cpp)
