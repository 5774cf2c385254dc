# Mesh reconstructors (spec 8): adaptive meshes of decoded grids by Delaunay
# vertex insertion (2-D and 3-D) and quadtree vertex removal (2-D).
#   MRSV_RECONSTRUCT_SOURCES -> mrsv_decode (exact integer arithmetic, no dependencies)
set(MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/grid_mesh.cpp)
set(MRSV_RECONSTRUCT_TESTS
  reference/tests/grid_mesh_test.cpp)

# Quadtree vertex removal (spec 9).
list(APPEND MRSV_RECONSTRUCT_SOURCES
  reference/src/reconstruct/detail_signal.cpp
  reference/src/reconstruct/quadtree_border.cpp
  reference/src/reconstruct/quadtree_error.cpp
  reference/src/reconstruct/quadtree_mesh.cpp
  reference/src/reconstruct/quadtree_tree.cpp)
list(APPEND MRSV_RECONSTRUCT_TESTS
  reference/tests/quadtree_test.cpp)
