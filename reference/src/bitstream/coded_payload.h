// The end of a range-coded payload (spec 5.6): a coded string decodes to
// exactly its bytes, no byte wanted past its end and none left over. Shared
// by the PM and PT decoders.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "bitstream/range_decoder.h"
#include "mrsv/status.h"

namespace mrsv {

inline Error checkPayloadEnd(const RangeDecoder& rc, size_t size, uint64_t offset, const std::string& field) {
  if (rc.overrun() != 0)
    return Error{Status::kBadEntropyPayload, offset, field, "coded data ends before the records do"};
  if (rc.consumed() != size)
    return Error{Status::kBadEntropyPayload, offset, field,
                 std::to_string(size - rc.consumed()) + " bytes of coded data left over"};
  return {};
}

}  // namespace mrsv
