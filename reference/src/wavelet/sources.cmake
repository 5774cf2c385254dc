# Source lists of the wavelet module, included by the top-level CMakeLists.txt.
#   MRSV_WAVELET_DECODE_SOURCES  -> mrsv_decode (integer synthesis, plans, tables; no Eigen)
#   MRSV_WAVELET_ENCODE_SOURCES  -> mrsv_encode (floating-point analysis/synthesis; may use Eigen)
#   MRSV_WAVELET_DECODE_TESTS / MRSV_WAVELET_ENCODE_TESTS -> the unit-test executables
# Paths are relative to the project root.
set(MRSV_WAVELET_DECODE_SOURCES
  reference/src/wavelet/filter_tables.cpp
  reference/src/wavelet/axis_plan.cpp
  reference/src/wavelet/synthesis_fixed.cpp
  reference/src/wavelet/cdf97_fixed.cpp
  reference/src/wavelet/window_synthesis.cpp
  reference/src/wavelet/cdf97_kernels.cpp
  reference/src/wavelet/cdf97_kernels_avx2.cpp
  reference/src/wavelet/cdf97_kernels_avx512.cpp)
set(MRSV_WAVELET_ENCODE_SOURCES
  reference/src/wavelet/transform_float.cpp
  reference/src/wavelet/cdf97_float.cpp
  reference/src/wavelet/strip_analysis.cpp)
set(MRSV_WAVELET_DECODE_TESTS
  reference/tests/wavelet_plan_test.cpp
  reference/tests/wavelet_fixed_test.cpp
  reference/tests/wavelet_cdf97_kernels_test.cpp
  reference/tests/window_synthesis_test.cpp)
set(MRSV_WAVELET_ENCODE_TESTS
  reference/tests/wavelet_transform_test.cpp
  reference/tests/wavelet_cdf97_test.cpp)

# The benchmark (tools/bench/wavelet_bench.cpp) needs the encoder for analyze().
if(NOT MRSV_DECODER_ONLY)
  find_package(benchmark QUIET)
  if(benchmark_FOUND)
    add_executable(wavelet_bench tools/bench/wavelet_bench.cpp)
    target_include_directories(wavelet_bench PRIVATE reference/src)
    target_link_libraries(wavelet_bench PRIVATE mrsv_encode benchmark::benchmark)
  endif()
endif()
