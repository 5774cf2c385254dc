#include "common/large_array.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mrsv {
namespace {

constexpr size_t kLargePage = size_t{2} << 20;  // 2 MiB, x86-64 and arm64 with 4 KiB pages

}  // namespace

void* allocateLarge(size_t bytes) {
  if (bytes == 0) bytes = 1;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kLargePage / 2) {
    // aligned_alloc wants a multiple of the alignment.
    const size_t rounded = (bytes + kLargePage - 1) / kLargePage * kLargePage;
    if (rounded < bytes) return nullptr;
    void* p = std::aligned_alloc(kLargePage, rounded);
    if (p) madvise(p, rounded, MADV_HUGEPAGE);  // a hint: its failure changes nothing
    return p;
  }
#endif
  return std::malloc(bytes);
}

void LargeArrayFree::operator()(void* p) const { std::free(p); }

}  // namespace mrsv
