# Progressive tetrahedral meshes (spec 7): the PT stream decoder, encoder and their tests.
#   MRSV_PT_DECODE_SOURCES -> mrsv_decode (no dependencies)
#   MRSV_PT_ENCODE_SOURCES -> mrsv_encode
set(MRSV_PT_DECODE_SOURCES
  reference/src/tetmesh/tet_complex.cpp
  reference/src/tetmesh/vertex_split.cpp
  reference/src/pt/pt_header.cpp
  reference/src/pt/progressive_tet_mesh.cpp
  reference/src/pt/pt_decode.cpp)
set(MRSV_PT_ENCODE_SOURCES
  reference/src/pt/pt_encode.cpp)
set(MRSV_PT_TESTS
  reference/tests/pt_stream_test.cpp)
