// spec: 8.6 the border rule, 1-D insertion along each side.
#include "reconstruct/line_insertion.h"

#include <utility>

namespace mrsv::reconstruct {

void insertAlongLine(const std::vector<int64_t>& positions, const std::vector<int64_t>& values,
                     __int128 bound_num, int64_t bound_den, std::vector<uint8_t>* kept) {
  std::vector<std::pair<size_t, size_t>> segments;
  size_t last = SIZE_MAX;
  for (size_t k = 0; k < positions.size(); ++k) {
    if (!(*kept)[k]) continue;
    if (last != SIZE_MAX && k > last + 1) segments.push_back({last, k});
    last = k;
  }
  while (!segments.empty()) {
    const auto [i, j] = segments.back();
    segments.pop_back();
    const int64_t pi = positions[i], pj = positions[j], span = pj - pi;
    // The errors of one segment share the denominator span: compare numerators.
    __int128 best = -1;
    size_t best_k = 0;
    for (size_t k = i + 1; k < j; ++k) {
      const int64_t pk = positions[k];
      __int128 e = __int128{values[k]} * span - __int128{values[i]} * (pj - pk) - __int128{values[j]} * (pk - pi);
      if (e < 0) e = -e;
      if (e > best) best = e, best_k = k;
    }
    if (best * bound_den <= bound_num * span) continue;
    (*kept)[best_k] = 1;
    if (best_k > i + 1) segments.push_back({i, best_k});
    if (j > best_k + 1) segments.push_back({best_k, j});
  }
}

}  // namespace mrsv::reconstruct
