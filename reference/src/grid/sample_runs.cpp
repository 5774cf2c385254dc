#include "grid/sample_runs.h"

#include <cstring>
#include <limits>

namespace mrsv {
namespace {

// C++17 leaves >> of a negative value to the implementation; the compilers we
// build with shift arithmetically (the flooring shift of spec 5.8.2).
static_assert((int64_t{-3} >> 1) == -2, "the sample mapping needs an arithmetic right shift");

template <class T>
inline void run(const int64_t* values, uint8_t* out, size_t n, int w, int64_t offset) {
  constexpr int64_t lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
  const int64_t half = w == 0 ? 0 : int64_t{1} << (w - 1);
  for (size_t i = 0; i < n; ++i) {
    int64_t v = ((values[i] + half) >> w) + offset;
    v = v < lo ? lo : v > hi ? hi : v;
    const T t = static_cast<T>(v);
    std::memcpy(out + i * sizeof(T), &t, sizeof(T));  // little-endian hosts (spec 5.8.2)
  }
}

template <class T>
void runPortable(const int64_t* values, uint8_t* out, size_t n, int w, int64_t offset) {
  run<T>(values, out, n, w, offset);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
template <class T>
__attribute__((target("avx512f"))) void runAvx512(const int64_t* values, uint8_t* out, size_t n,
                                                  int w, int64_t offset) {
  run<T>(values, out, n, w, offset);
}

bool hasAvx512() {
  static const bool yes = __builtin_cpu_supports("avx512f");
  return yes;
}
#endif

}  // namespace

template <class T>
void integerSampleRun(const int64_t* values, uint8_t* out, size_t n, int w, int64_t offset) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (hasAvx512()) return runAvx512<T>(values, out, n, w, offset);
#endif
  runPortable<T>(values, out, n, w, offset);
}

template void integerSampleRun<uint8_t>(const int64_t*, uint8_t*, size_t, int, int64_t);
template void integerSampleRun<int16_t>(const int64_t*, uint8_t*, size_t, int, int64_t);
template void integerSampleRun<uint16_t>(const int64_t*, uint8_t*, size_t, int, int64_t);
template void integerSampleRun<int32_t>(const int64_t*, uint8_t*, size_t, int, int64_t);

}  // namespace mrsv
