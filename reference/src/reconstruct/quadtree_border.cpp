// spec: 9.5 the tile border rule.
#include "reconstruct/quadtree_border.h"

#include <utility>

namespace mrsv::quadtree {

std::vector<uint32_t> sideCuts(const ErrorTest& test, uint64_t first, uint64_t step, uint32_t length) {
  // Dyadic segments [a, a + t] from the root 2^K >= length, depth first from
  // the left: a segment is kept when it lies on the side and its samples are
  // within E of its chord, else halved. The cuts are the kept ends.
  int top = 0;
  while ((uint64_t{1} << top) < length) ++top;
  std::vector<uint32_t> cuts{0};
  std::vector<std::pair<uint64_t, int>> stack{{0, top}};
  while (!stack.empty()) {
    const auto [a, level] = stack.back();
    stack.pop_back();
    if (a >= length) continue;
    const uint64_t t = uint64_t{1} << level;
    if (a + t <= length && (level == 0 || test.runWithin(first + a * step, step, static_cast<uint32_t>(t)))) {
      cuts.push_back(static_cast<uint32_t>(a + t));
      continue;
    }
    stack.push_back({a + t / 2, level - 1});  // the right half after the left one
    stack.push_back({a, level - 1});
  }
  return cuts;
}

void zipStrip(const std::vector<std::array<uint32_t, 2>>& outer,
              const std::vector<std::array<uint32_t, 2>>& inner, int along,
              std::vector<std::array<std::array<uint32_t, 2>, 3>>* out) {
  auto emit = [&](std::array<uint32_t, 2> p, std::array<uint32_t, 2> q, std::array<uint32_t, 2> r) {
    const int64_t cross = (int64_t{q[0]} - p[0]) * (int64_t{r[1]} - p[1]) -
                          (int64_t{q[1]} - p[1]) * (int64_t{r[0]} - p[0]);
    if (cross < 0) std::swap(q, r);
    out->push_back({p, q, r});
  };
  size_t a = 0, b = 0;
  // Advance along the line whose next vertex comes first (the outer on a tie).
  while (a + 1 < outer.size() || b + 1 < inner.size()) {
    const bool step_outer = b + 1 == inner.size() ||
                            (a + 1 < outer.size() && outer[a + 1][along] <= inner[b + 1][along]);
    if (step_outer) {
      emit(outer[a], outer[a + 1], inner[b]);
      ++a;
    } else {
      emit(outer[a], inner[b + 1], inner[b]);
      ++b;
    }
  }
}

}  // namespace mrsv::quadtree
