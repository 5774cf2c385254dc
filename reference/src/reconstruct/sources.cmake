# Mesh reconstructors (spec 8): adaptive meshes of decoded grids by Delaunay
# vertex insertion (2-D and 3-D) and quadtree vertex removal (2-D).
#   MRSV_RECONSTRUCT_SOURCES -> mrsv_decode (exact integer arithmetic, no dependencies)
set(MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/grid_mesh.cpp
  reference/src/reconstruct/delaunay3.cpp)
set(MRSV_RECONSTRUCT_TESTS
  reference/tests/grid_mesh_test.cpp)
