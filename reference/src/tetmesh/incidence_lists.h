// The tet slots of each vertex of a TetComplex, all in one pool.
// spec: 7.3 (tets(v), the stars a decoder reads), 7.6.4 (how a split changes them).
//
// A PT decoder changes a few lists per split: vs loses its moved tets and
// gains the new ones, vt's list is new, each cut vertex gains one or two.
// As one std::vector per vertex that was a malloc per split, reallocations
// and their copies, and the flag loop of 7.7.1 read each vertex's count
// from a 24-byte vector header (issue 21's profile: about 900 instructions
// and 25 first-level cache misses per split on the CT crop). Here each list
// is a block of the pool with room to grow; a full block moves to the end
// of the pool with twice the room, leaving a hole, and the pool is packed
// again when the holes outgrow the blocks in use.
//
// A push may move the pool: pointers from data() or of() are good until the
// next push(), reserve() or addVertex().
//
// The PT decoder keeps every list in increasing slot order (buildIncidence,
// and every split and its undoing keep it: spec 7.6.5's undo then finds a
// split's new tets, the last slots, at the ends of their lists, and puts the
// moved tets back where they were).
#pragma once

#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

#include "common/large_array.h"

namespace mrsv {

class IncidenceLists {
 public:
  // A list as the star loops read it.
  struct View {
    const uint32_t* first;
    uint32_t count;
    const uint32_t* begin() const { return first; }
    const uint32_t* end() const { return first + count; }
    uint32_t size() const { return count; }
    bool empty() const { return count == 0; }
    uint32_t operator[](uint32_t i) const { return first[i]; }
  };

  uint32_t vertexCount() const { return static_cast<uint32_t>(list_.size()); }
  // n empty lists.
  void assign(uint32_t n) {
    pool_.clear();
    list_.assign(n, List{});
    count8_.assign(n, 0);
    holes_ = 0;
  }
  // Room for `vertices` lists and `entries` entries in all, without filling it.
  void reserveTotal(uint32_t vertices, size_t entries) {
    list_.reserve(vertices);
    count8_.reserve(vertices);
    pool_.reserve(std::min<size_t>(entries, UINT32_MAX));
  }
  // One more vertex, with an empty list.
  void addVertex() {
    list_.push_back(List{static_cast<uint32_t>(pool_.size()), 0, 0, 0});
    count8_.push_back(0);
  }
  // Forgets the last vertex's list (its block becomes a hole).
  void removeLastVertex() {
    holes_ += list_.back().capacity;
    list_.pop_back();
    count8_.pop_back();
  }

  uint32_t size(uint32_t v) const { return list_[v].size; }
  // min(size(v), 255), from a byte per vertex: the flag loop of 7.7.1 reads
  // one per vertex of each flagged group, and through the 16-byte records it
  // streamed 223 MB per decode of the LOX post (when every vertex up to the
  // last split had a flag: 130 per split, 107,167 splits).
  uint32_t sizeUpTo255(uint32_t v) const { return count8_[v]; }
  bool empty(uint32_t v) const { return list_[v].size == 0; }
  View of(uint32_t v) const { return View{pool_.data() + list_[v].offset, list_[v].size}; }
  uint32_t* data(uint32_t v) { return pool_.data() + list_[v].offset; }
  // Starts loading v's list record, for a caller that knows which lists it
  // changes next (undoing splits, 7.3).
  void prefetch(uint32_t v) const {
    __builtin_prefetch(&list_[v]);
    __builtin_prefetch(&count8_[v]);
  }
  // Starts loading v's entries (the first and last cache lines of them; a
  // star's list is about 24 entries), once its record is at hand.
  void prefetchEntries(uint32_t v) const {
    const List& l = list_[v];
    const uint32_t* first = pool_.data() + l.offset;
    __builtin_prefetch(first);
    if (l.size > 0) __builtin_prefetch(first + l.size - 1);
  }

  void push(uint32_t v, uint32_t slot) {
    List& l = list_[v];
    if (l.size == l.capacity) grow(v, l.size + 1);
    const uint32_t n = list_[v].size++;
    pool_[list_[v].offset + n] = slot;
    setCount8(v, n + 1);
  }
  void pop(uint32_t v) { setCount8(v, --list_[v].size); }
  // The first n entries of v's block are its list: n up to the room that
  // reserve() made (entries past the old size written through data()).
  void resize(uint32_t v, uint32_t n) {
    list_[v].size = n;
    setCount8(v, n);
  }
  void clear(uint32_t v) { resize(v, 0); }
  void reserve(uint32_t v, uint32_t n) {
    if (list_[v].capacity < n) grow(v, n);
  }

 private:
  // One record per vertex, so that a push touches one cache line of them.
  struct List {
    uint32_t offset = 0;  // into pool_
    uint32_t size = 0;
    uint32_t capacity = 0;
    uint32_t unused = 0;
  };

  void grow(uint32_t v, uint32_t need) {
    const uint32_t room = std::max({need, 2 * list_[v].capacity, uint32_t{8}});
    if (list_[v].offset + uint64_t{list_[v].capacity} == pool_.size()) {  // the last block grows in place
      extendPool(list_[v].offset + uint64_t{room});
      list_[v].capacity = room;
      return;
    }
    if (holes_ + list_[v].capacity > pool_.size() / 2 + 4096) pack();
    List& l = list_[v];
    const uint64_t to = pool_.size();
    extendPool(to + room);
    const uint32_t* from = pool_.data() + l.offset;
    uint32_t* into = pool_.data() + to;
    const uint32_t size = l.size;
    for (uint32_t i = 0; i < size; ++i) into[i] = from[i];
    holes_ += l.capacity;
    l.offset = static_cast<uint32_t>(to);
    l.capacity = room;
  }
  // Offsets are 32 bits: 2^32 entries (16 GiB) are more than any mesh the
  // decoder's memory limit lets through; beyond them it is out of memory.
  void extendPool(uint64_t size) {
    if (size > UINT32_MAX) throw std::bad_alloc();
    pool_.resize(size);
  }
  // Every block again in vertex order, without holes.
  void pack() {
    LargeVector<uint32_t> packed;
    packed.reserve(pool_.size() - holes_);
    for (List& l : list_) {
      const uint64_t to = packed.size();
      packed.insert(packed.end(), pool_.begin() + l.offset, pool_.begin() + l.offset + l.size);
      packed.resize(to + l.capacity);
      l.offset = static_cast<uint32_t>(to);
    }
    pool_.swap(packed);
    holes_ = 0;
  }

  void setCount8(uint32_t v, uint32_t n) { count8_[v] = static_cast<uint8_t>(std::min<uint32_t>(n, 255)); }

  LargeVector<uint32_t> pool_;
  LargeVector<List> list_;
  LargeVector<uint8_t> count8_;  // min(size, 255) per vertex
  uint64_t holes_ = 0;  // pool entries in no vertex's block
};

}  // namespace mrsv
