// splitmix64: the small random generator of the metrics' samplers.
#pragma once

#include <cstdint>

namespace mrsv {

// Good output from any seed, so that every element (face, edge, sample) can
// have its own stream: the samples of one element do not depend on how many
// numbers the elements before it used.
struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

// The stream of element `index` of kind `kind` under `seed`.
inline SplitMix64 splitMixStream(uint64_t seed, uint64_t kind, uint64_t index) {
  SplitMix64 mix{seed};
  mix.state ^= mix.next() + kind * 0x632be59bd9b4e019ULL + index * 0xd1b54a32d192ed03ULL;
  mix.next();
  return mix;
}

}  // namespace mrsv
