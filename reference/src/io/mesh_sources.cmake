# Mesh file formats (OBJ, PLY, OFF), mesh repair and terrain-to-mesh.
#   MRSV_MESH_IO_SOURCES -> mrsv_io
#   MRSV_MESH_IO_TESTS   -> mrsv_mesh_tests
set(MRSV_MESH_IO_SOURCES)
set(MRSV_MESH_IO_TESTS)
