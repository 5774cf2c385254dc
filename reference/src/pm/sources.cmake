# Progressive meshes (spec 6): the PM stream decoder, encoder and their tests.
#   MRSV_PM_DECODE_SOURCES -> mrsv_decode (no dependencies)
#   MRSV_PM_ENCODE_SOURCES -> mrsv_encode
#   MRSV_PM_TESTS          -> mrsv_mesh_tests
set(MRSV_PM_DECODE_SOURCES)
set(MRSV_PM_ENCODE_SOURCES)
set(MRSV_PM_TESTS)
