// The vertices a batch has locked ahead of its last split vertex (spec
// 6.7.1), kept so that `gap` can skip them without walking the vertex
// numbers. Keys only grow past the last one taken out, so this is a radix
// heap: a key sits in bucket bit_width(key XOR floor), where floor is the last
// key taken out; taking keys out moves the others to lower buckets only, so
// each key moves at most 32 times and a push is O(1). A binary heap here cost
// half the decoding time of a split on large meshes (cache misses on every
// sift).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace mrsv::pm {

class LockedVertices {
 public:
  void clear() {
    for (int i = 0; i < kBuckets; ++i) buckets_[i].clear();
    nonempty_ = 0;
    floor_ = 0;
  }

  // `v` must be above every key taken out so far.
  void push(uint32_t v) {
    const int i = bucketOf(v);
    if (buckets_[i].empty() || v < bucket_min_[i]) bucket_min_[i] = v;
    buckets_[i].push_back(v);
    nonempty_ |= uint64_t{1} << i;
  }

  // Takes out every key <= limit and returns how many there were.
  uint32_t takeUpTo(uint32_t limit) {
    uint32_t taken = 0;
    while (nonempty_ != 0) {
      const int i = lowestNonempty();
      if (bucket_min_[i] > limit) break;
      if (i == 0) {
        taken += static_cast<uint32_t>(buckets_[0].size());
        buckets_[0].clear();
        nonempty_ &= ~uint64_t{1};
        continue;
      }
      // The smallest key becomes the floor; the bucket's keys all fall lower.
      floor_ = bucket_min_[i];
      std::vector<uint32_t> moving;
      moving.swap(buckets_[i]);
      nonempty_ &= ~(uint64_t{1} << i);
      for (uint32_t v : moving) push(v);
      moving.clear();
      moving.swap(buckets_[i]);  // keep the capacity
    }
    return taken;
  }

  // The smallest key, or UINT32_MAX when empty (for the encoder's check).
  uint32_t smallest() const {
    return nonempty_ == 0 ? UINT32_MAX : bucket_min_[lowestNonempty()];
  }

 private:
  static constexpr int kBuckets = 33;

  // GCC and Clang builtins (C++20 has std::bit_width and std::countr_zero).
  int bucketOf(uint32_t v) const {
    const uint32_t x = v ^ floor_;
    return x == 0 ? 0 : 32 - __builtin_clz(x);
  }
  int lowestNonempty() const { return __builtin_ctzll(nonempty_); }

  std::vector<uint32_t> buckets_[kBuckets];
  uint32_t bucket_min_[kBuckets] = {};
  uint64_t nonempty_ = 0;
  uint32_t floor_ = 0;
};

}  // namespace mrsv::pm
