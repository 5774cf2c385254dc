# Tet mesh file formats (MEDIT, TetGen, VTU, legacy VTK), the exact orientation
# test, and tet meshes from grids and PLOT3D data.
#   MRSV_TET_IO_SOURCES -> mrsv_io
#   MRSV_TET_IO_TESTS   -> mrsv_tet_tests
set(MRSV_TET_IO_SOURCES
  reference/src/io/tet_formats.cpp
  reference/src/io/tet_orient.cpp
  reference/src/io/tet_medit.cpp
  reference/src/io/tet_tetgen.cpp
  reference/src/io/tet_vtu.cpp
  reference/src/io/tet_vtk_legacy.cpp
  reference/src/io/tets_from_grid.cpp
  reference/src/io/plot3d.cpp)
# The error-free transformations of the exact orientation test need every
# multiply and add rounded on its own.
set_source_files_properties(reference/src/io/tet_orient.cpp PROPERTIES COMPILE_OPTIONS -ffp-contract=off)
set(MRSV_TET_IO_TESTS
  reference/tests/tet_formats_test.cpp)
