// Fuzz parameters come from the last byte of the input, so the corpus stays
// plain .mrsv files: a file ending in MEND's CRC gives arbitrary but fixed options.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mrsv/container.h"

namespace mrsv::fuzz {

inline ContainerOptions containerOptionsFromTail(const uint8_t* data, size_t size) {
  ContainerOptions options;
  uint8_t tail = size ? data[size - 1] : 0;
  options.verify_checksums = (tail & 1) == 0;     // half the runs get past the CRC
  options.allow_partial_tail = (tail & 2) != 0;
  return options;
}

}  // namespace mrsv::fuzz
