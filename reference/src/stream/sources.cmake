# Incremental decoding (spec 2.7): the streaming decoder, on which the one-shot
# decoders are built.
#   MRSV_STREAM_DECODE_SOURCES -> mrsv_decode (no dependencies)
set(MRSV_STREAM_DECODE_SOURCES
  reference/src/stream/stream_decoder.cpp)

# tools/bench/stream_decode_bench: one-shot against byte-by-byte and 1460-byte
# pieces, from stream files; it needs only the decoder.
add_executable(stream_decode_bench tools/bench/stream_decode_bench.cpp)
target_link_libraries(stream_decode_bench PRIVATE mrsv_decode)
