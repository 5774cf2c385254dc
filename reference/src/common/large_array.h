// Uninitialised arrays of many megabytes (the decoder's padded coefficient
// array), allocated so that the operating system can back them with large
// pages where it offers them.
//
// A 256^3 grid of int64 coefficients is 128 MiB: with 4 KiB pages the first
// write to each page is a page fault, 32768 of them, which measured about 13 %
// of a whole decode. On Linux the allocation is aligned to 2 MiB and marked
// MADV_HUGEPAGE (a hint; it takes effect when transparent huge pages are set
// to "madvise" or "always"), which makes it 64 faults. Elsewhere, and for
// small arrays, it is an ordinary allocation. Nothing computed depends on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

namespace mrsv {

struct LargeArrayFree {
  void operator()(void* p) const;
};

template <class T>
using LargeArray = std::unique_ptr<T[], LargeArrayFree>;

// `bytes` of uninitialised storage; null when it cannot be had.
void* allocateLarge(size_t bytes);

// An uninitialised array of n values of T (a trivial type); null when it
// cannot be had.
template <class T>
LargeArray<T> makeLargeArray(uint64_t n) {
  if (n > SIZE_MAX / sizeof(T)) return nullptr;
  return LargeArray<T>(static_cast<T*>(allocateLarge(static_cast<size_t>(n) * sizeof(T))));
}

}  // namespace mrsv
