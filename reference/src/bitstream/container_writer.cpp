// spec: 2.2, 2.3. The encoder side of the container.
#include <cassert>
#include <cstring>

#include "common/byte_writer.h"
#include "common/crc32c.h"
#include "mrsv/container.h"

namespace mrsv {

ContainerWriter::ContainerWriter() {
  bytes_.assign(kSignature, kSignature + sizeof kSignature);
  bytes_.push_back(kVersionMajor);
  bytes_.push_back(kVersionMinor);
  bytes_.push_back(0);  // header_flags
}

void ContainerWriter::addChunk(const ChunkType& type, const std::vector<uint8_t>& payload) {
  assert(payload.size() <= kMaxChunkPayload);
  size_t start = bytes_.size();
  ByteWriter w(&bytes_);
  w.bytes(reinterpret_cast<const uint8_t*>(type.c), 4);
  w.u32(static_cast<uint32_t>(payload.size()));
  w.bytes(payload.data(), payload.size());
  w.u32(crc32c(0, bytes_.data() + start, bytes_.size() - start));
}

std::vector<uint8_t> ContainerWriter::finish() {
  addChunk(kChunkEnd, {});
  std::vector<uint8_t> out;
  out.swap(bytes_);
  *this = ContainerWriter();
  return out;
}

}  // namespace mrsv
