# Source lists of the wavelet module, included by the top-level CMakeLists.txt.
#   MRSV_WAVELET_DECODE_SOURCES  -> mrsv_decode (integer synthesis, plans, tables; no Eigen)
#   MRSV_WAVELET_ENCODE_SOURCES  -> mrsv_encode (floating-point analysis/synthesis; may use Eigen)
#   MRSV_WAVELET_DECODE_TESTS / MRSV_WAVELET_ENCODE_TESTS -> the unit-test executables
# Paths are relative to the project root.
set(MRSV_WAVELET_DECODE_SOURCES)
set(MRSV_WAVELET_ENCODE_SOURCES)
set(MRSV_WAVELET_DECODE_TESTS)
set(MRSV_WAVELET_ENCODE_TESTS)
