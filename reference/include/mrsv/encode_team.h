// Several processes coding one stream together (decision D92): what the
// out-of-core precinct encoder needs from them. mrsv-mpi implements it with
// MPI; a team of one (the library's own) is the single-process encoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mrsv/status.h"

namespace mrsv {

// A file that every member writes at offsets and reads back.
class SharedScratch {
 public:
  virtual ~SharedScratch() = default;
  virtual Error writeAt(uint64_t offset, const void* data, size_t n) = 0;
  virtual Error readAt(uint64_t offset, size_t n, void* out) = 0;
  // Collective: every member's writes before it are seen by every member's
  // reads after it.
  virtual Error sync() = 0;
};

// Items 0 to n - 1 handed out one at a time, each to the member that asks
// first: work of uneven cost shared evenly.
class WorkQueue {
 public:
  virtual ~WorkQueue() = default;  // collective
  virtual uint64_t take() = 0;     // the next item, or n when none is left
};

class EncodeTeam {
 public:
  virtual ~EncodeTeam() = default;
  virtual int member() const = 0;   // 0 to members() - 1
  virtual int members() const = 0;
  // Collective: ok when no member failed, else the error of the failing
  // member with the lowest number, for every member.
  virtual Error agree(const Error& mine) = 0;
  // Collective, element by element over the members, in place.
  virtual void sum(std::vector<uint64_t>* values) = 0;
  virtual void min(std::vector<double>* values) = 0;
  virtual void max(std::vector<double>* values) = 0;
  // Collective: a new, empty scratch file, removed when released.
  virtual std::unique_ptr<SharedScratch> scratch(Error* error) = 0;
  // Collective: a queue of n items.
  virtual std::unique_ptr<WorkQueue> queue(uint64_t n) = 0;
};

}  // namespace mrsv
