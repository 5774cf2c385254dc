// spec: 6.2 mesh_header() (PHDR).
#include <cmath>

#include "common/byte_reader.h"
#include "common/byte_writer.h"
#include "mrsv/limits.h"
#include "mrsv/progressive_mesh.h"

namespace mrsv {

Error parsePmHeader(const ChunkView& chunk, PmHeader* out) {
  auto fail = [&](Status s, uint64_t at, const char* field, std::string msg) {
    return Error{s, chunk.payloadOffset() + at, std::string("PHDR.") + field, std::move(msg)};
  };
  if (chunk.chunk_length != kMeshHeaderSize)
    return Error{Status::kBadChunkLength, chunk.offset + 4, "PHDR.chunk_length",
                 "PHDR payload must be " + std::to_string(kMeshHeaderSize) + " bytes, not " +
                     std::to_string(chunk.chunk_length)};
  ByteReader r(chunk.payload, chunk.chunk_length);
  PmHeader h;
  h.placement = r.u8();
  h.position_bits = r.u8();
  h.scalar_bits = r.u8();
  h.move_detail = r.u8();
  h.vertex_count = r.u32();
  h.base_vertex_count = r.u32();
  h.base_triangle_count = r.u32();
  h.batch_count = r.u32();
  uint32_t reserved32 = r.u32();
  for (double& o : h.origin) o = r.f64();
  h.position_step = r.f64();
  h.scalar_origin = r.f64();
  h.scalar_step = r.f64();

  if (h.placement != kPlacementEndpoint && h.placement != kPlacementFree)
    return fail(Status::kBadMeshHeader, 0, "placement", "placement must be 0 or 1");
  if (h.position_bits < 1 || h.position_bits > kMaxPositionBits)
    return fail(Status::kBadMeshHeader, 1, "position_bits", "position_bits must be 1 to 30");
  if (h.scalar_bits > kMaxPositionBits)
    return fail(Status::kBadMeshHeader, 2, "scalar_bits", "scalar_bits must be 0 to 30");
  if (h.move_detail > kMaxPositionBits || (h.placement == kPlacementEndpoint && h.move_detail != 0))
    return fail(Status::kBadMeshHeader, 3, "move_detail", "move_detail must be 0 with placement 0, else 0 to 30");
  if (h.vertex_count > kMaxMeshVertices)
    return fail(Status::kBadMeshHeader, 4, "vertex_count", "vertex_count above 2^28");
  if (h.base_vertex_count < 3 || h.base_vertex_count > h.vertex_count)
    return fail(Status::kBadMeshHeader, 8, "base_vertex_count",
                "base_vertex_count must be at least 3 and at most vertex_count");
  if (h.base_triangle_count < 1 || h.base_triangle_count > kMaxBaseTriangles)
    return fail(Status::kBadMeshHeader, 12, "base_triangle_count",
                "base_triangle_count must be 1 to 2^29");
  if (h.batch_count > h.splitCount())
    return fail(Status::kBadMeshHeader, 16, "batch_count",
                "batch_count above the number of splits (every batch holds at least one)");
  if ((h.batch_count == 0) != (h.splitCount() == 0))
    return fail(Status::kBadMeshHeader, 16, "batch_count", "splits need at least one batch");
  if (reserved32 != 0) return fail(Status::kReservedNonZero, 20, "reserved", "must be 0");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(h.origin[a]))
      return fail(Status::kBadMeshHeader, 24 + 8 * a, "origin", "must be finite");
  if (!std::isfinite(h.position_step) || !(h.position_step > 0))
    return fail(Status::kBadMeshHeader, 48, "position_step", "must be finite and positive");
  if (h.scalar_bits > 0) {
    if (!std::isfinite(h.scalar_origin))
      return fail(Status::kBadMeshHeader, 56, "scalar_origin", "must be finite");
    if (!std::isfinite(h.scalar_step) || !(h.scalar_step > 0))
      return fail(Status::kBadMeshHeader, 64, "scalar_step", "must be finite and positive");
  } else {
    // Without scalars each field must be +0 (its bits all zero), checked at its own offset.
    if (h.scalar_origin != 0 || std::signbit(h.scalar_origin))
      return fail(Status::kBadMeshHeader, 56, "scalar_origin", "must be +0 without scalars");
    if (h.scalar_step != 0 || std::signbit(h.scalar_step))
      return fail(Status::kBadMeshHeader, 64, "scalar_step", "must be +0 without scalars");
  }
  *out = h;
  return {};
}

std::vector<uint8_t> serializePmHeader(const PmHeader& h) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  w.u8(h.placement);
  w.u8(h.position_bits);
  w.u8(h.scalar_bits);
  w.u8(h.move_detail);
  w.u32(h.vertex_count);
  w.u32(h.base_vertex_count);
  w.u32(h.base_triangle_count);
  w.u32(h.batch_count);
  w.u32(0);
  for (double o : h.origin) w.f64(o);
  w.f64(h.position_step);
  w.f64(h.scalar_origin);
  w.f64(h.scalar_step);
  return out;
}

}  // namespace mrsv
