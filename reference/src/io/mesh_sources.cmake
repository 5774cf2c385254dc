# Mesh file formats (OBJ, PLY, OFF), mesh repair and terrain-to-mesh.
#   MRSV_MESH_IO_SOURCES -> mrsv_io
#   MRSV_MESH_IO_TESTS   -> mrsv_mesh_tests
set(MRSV_MESH_IO_SOURCES
  reference/src/io/mesh_formats.cpp
  reference/src/io/mesh_obj.cpp
  reference/src/io/mesh_off.cpp
  reference/src/io/mesh_ply.cpp
  reference/src/io/mesh_repair.cpp
  reference/src/io/terrain_mesh.cpp)
set(MRSV_MESH_IO_TESTS
  reference/tests/mesh_formats_test.cpp
  reference/tests/mesh_repair_test.cpp
  reference/tests/terrain_mesh_test.cpp)
