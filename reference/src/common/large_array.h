// Uninitialised arrays of many megabytes (the decoder's padded coefficient
// array), allocated so that the operating system can back them with large
// pages where it offers them.
//
// A 256^3 grid of int64 coefficients is 128 MiB: with 4 KiB pages the first
// write to each page is a page fault, 32768 of them, which measured about 13 %
// of a whole decode. On Linux the allocation is aligned to 2 MiB and marked
// MADV_HUGEPAGE (a hint; it takes effect when transparent huge pages are set
// to "madvise" or "always"), which makes it 64 faults. Elsewhere, and for
// arrays below 1 MiB, it is an ordinary allocation. Nothing computed depends on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

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

// An allocator for std::vector through allocateLarge() (large pages for
// arrays of 1 MiB or more): a decoder's mesh arrays (PT, spec 7), which it reserves
// once from the sizes its header announces and then fills split by split.
// With 4 KiB pages the first touch of each page faulted: about 10 % of a
// PT decode of the CT crop (perf; 2,600 faults per decode).
template <class T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) {}
  T* allocate(size_t n) {
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
    void* p = allocateLarge(n * sizeof(T));
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) { std::free(p); }
  template <class U>
  bool operator==(const LargePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const LargePageAllocator<U>&) const { return false; }
};

template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace mrsv
