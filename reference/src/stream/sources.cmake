# Incremental decoding (spec 2.7): the streaming decoder, on which the one-shot
# decoders are built.
#   MRSV_STREAM_DECODE_SOURCES -> mrsv_decode (no dependencies)
set(MRSV_STREAM_DECODE_SOURCES
  reference/src/stream/stream_decoder.cpp)
