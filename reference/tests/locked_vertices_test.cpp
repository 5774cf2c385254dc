// The radix heap behind spec 6.7.1's locked vertices against std::multiset,
// on random batches shaped like real ones: keys pushed above the last split
// vertex, taken out in rising steps.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "pm/locked_vertices.h"

namespace mrsv::pm {
namespace {

TEST(LockedVertices, MatchesAnOrderedSetOnRandomBatches) {
  std::mt19937 rng(20261122);
  LockedVertices locked;
  for (int batch = 0; batch < 200; ++batch) {
    locked.clear();
    std::multiset<uint32_t> reference;
    const uint32_t n = 1 + rng() % 100000;
    uint32_t vs = 0;
    while (true) {
      vs += 1 + rng() % 64;
      if (vs >= n) break;
      uint32_t expected = 0;
      while (!reference.empty() && *reference.begin() <= vs) reference.erase(reference.begin()), ++expected;
      ASSERT_EQ(locked.takeUpTo(vs), expected) << "batch " << batch << " vs " << vs;
      ASSERT_EQ(locked.smallest(), reference.empty() ? UINT32_MAX : *reference.begin());
      for (int k = rng() % 12; k > 0; --k) {
        const uint32_t w = vs + 1 + rng() % (n - vs);  // may repeat: a multiset
        locked.push(w);
        reference.insert(w);
      }
    }
  }
}

TEST(LockedVertices, KeysAtTheTopOfTheRange) {
  LockedVertices locked;
  locked.push(0xFFFFFFFEu);
  locked.push(0x80000000u);
  locked.push(1);
  EXPECT_EQ(locked.takeUpTo(0), 0u);
  EXPECT_EQ(locked.takeUpTo(1), 1u);
  EXPECT_EQ(locked.smallest(), 0x80000000u);
  EXPECT_EQ(locked.takeUpTo(0xFFFFFFFEu), 2u);
  EXPECT_EQ(locked.smallest(), UINT32_MAX);
}

}  // namespace
}  // namespace mrsv::pm
