# Tiled grids (spec 11): tiles, the index, region decoding, the tiled encoder.
#   MRSV_TILES_DECODE_SOURCES -> mrsv_decode (threads from the standard library)
#   MRSV_TILES_ENCODE_SOURCES -> mrsv_encode
set(MRSV_TILES_DECODE_SOURCES
  reference/src/tiles/tiling.cpp
  reference/src/tiles/tiled_decode.cpp
  reference/src/tiles/tile_rows_decode.cpp
  reference/src/tiles/region_decode.cpp)
set(MRSV_TILES_ENCODE_SOURCES
  reference/src/tiles/tiled_encode.cpp
  reference/src/tiles/tiled_stream_encode.cpp)
