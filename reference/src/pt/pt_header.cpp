// spec: 7.2 tet_header() (THDR).
#include <cmath>

#include "common/byte_reader.h"
#include "common/byte_writer.h"
#include "mrsv/limits.h"
#include "mrsv/progressive_tet_mesh.h"

namespace mrsv {

namespace {

constexpr uint32_t kMaxTets = 1u << 30;  // B.6: THDR.tet_count

bool validFieldName(const uint8_t* name) {
  size_t n = 0;
  while (n < kTetFieldNameSize && name[n] != 0) {
    if (name[n] < 0x20 || name[n] > 0x7E) return false;
    ++n;
  }
  for (size_t i = n; i < kTetFieldNameSize; ++i)
    if (name[i] != 0) return false;
  return true;
}

}  // namespace

Error parsePtHeader(const ChunkView& chunk, PtHeader* out) {
  auto fail = [&](Status s, uint64_t at, const std::string& field, std::string msg) {
    return Error{s, chunk.payloadOffset() + at, "THDR." + field, std::move(msg)};
  };
  auto lengthError = [&](const std::string& why) {
    return Error{Status::kBadChunkLength, chunk.offset + 4, "THDR.chunk_length", why};
  };
  if (chunk.chunk_length < kTetHeaderFixedSize)
    return lengthError("THDR payload must be at least " + std::to_string(kTetHeaderFixedSize) + " bytes, not " +
                       std::to_string(chunk.chunk_length));
  ByteReader r(chunk.payload, chunk.chunk_length);
  PtHeader h;
  h.position_bits = r.u8();
  const uint8_t field_count = r.u8();
  const uint16_t reserved16 = r.u16();
  h.vertex_count = r.u32();
  h.base_vertex_count = r.u32();
  h.base_tet_count = r.u32();
  h.tet_count = r.u32();
  h.batch_count = r.u32();
  for (double& o : h.origin) o = r.f64();
  h.position_step = r.f64();
  // spec 7.2: checks in field order; the length once field_count is known.
  if (h.position_bits < 1 || h.position_bits > kMaxPositionBits)
    return fail(Status::kBadMeshHeader, 0, "position_bits", "position_bits must be 1 to 30");
  if (field_count > kMaxTetFields) return fail(Status::kBadMeshHeader, 1, "field_count", "field_count must be 0 to 8");
  if (chunk.chunk_length != kTetHeaderFixedSize + kTetFieldRecordSize * field_count)
    return lengthError("THDR payload must be " +
                       std::to_string(kTetHeaderFixedSize + kTetFieldRecordSize * field_count) + " bytes with " +
                       std::to_string(field_count) + " fields, not " + std::to_string(chunk.chunk_length));
  if (reserved16 != 0) return fail(Status::kReservedNonZero, 2, "reserved", "must be 0");
  if (h.vertex_count > kMaxMeshVertices)
    return fail(Status::kBadMeshHeader, 4, "vertex_count", "vertex_count above 2^28");
  if (h.base_vertex_count < 4 || h.base_vertex_count > h.vertex_count)
    return fail(Status::kBadMeshHeader, 8, "base_vertex_count",
                "base_vertex_count must be at least 4 and at most vertex_count");
  if (h.base_tet_count < 1 || h.base_tet_count > kMaxTets)
    return fail(Status::kBadMeshHeader, 12, "base_tet_count", "base_tet_count must be 1 to 2^30");
  if (h.tet_count < h.base_tet_count || h.tet_count > kMaxTets)
    return fail(Status::kBadMeshHeader, 16, "tet_count", "tet_count must be base_tet_count to 2^30");
  if (h.batch_count > h.splitCount())
    return fail(Status::kBadMeshHeader, 20, "batch_count",
                "batch_count above the number of splits (every batch holds at least one)");
  if ((h.batch_count == 0) != (h.splitCount() == 0))
    return fail(Status::kBadMeshHeader, 20, "batch_count", "splits need at least one batch");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(h.origin[a])) return fail(Status::kBadMeshHeader, 24 + 8 * a, "origin", "must be finite");
  if (!std::isfinite(h.position_step) || !(h.position_step > 0))
    return fail(Status::kBadMeshHeader, 48, "position_step", "must be finite and positive");
  for (uint32_t f = 0; f < field_count; ++f) {
    const uint64_t at = kTetHeaderFixedSize + kTetFieldRecordSize * f;
    const std::string name = "field[" + std::to_string(f) + "].";
    PtField field;
    field.bits = r.u8();
    uint8_t reserved_bytes = 0;
    for (int i = 0; i < 7; ++i) reserved_bytes |= r.u8();
    field.origin = r.f64();
    field.step = r.f64();
    const uint8_t* raw_name = chunk.payload + at + 24;
    for (size_t i = 0; i < kTetFieldNameSize; ++i) r.u8();
    if (field.bits < 1 || field.bits > kMaxPositionBits)
      return fail(Status::kBadMeshHeader, at, name + "bits", "bits must be 1 to 30");
    if (reserved_bytes != 0) return fail(Status::kReservedNonZero, at + 1, name + "reserved", "must be 0");
    if (!std::isfinite(field.origin)) return fail(Status::kBadMeshHeader, at + 8, name + "origin", "must be finite");
    if (!std::isfinite(field.step) || !(field.step > 0))
      return fail(Status::kBadMeshHeader, at + 16, name + "step", "must be finite and positive");
    if (!validFieldName(raw_name))
      return fail(Status::kBadMeshHeader, at + 24, name + "name",
                  "printable ASCII padded with zero bytes, nothing after the first zero");
    size_t n = 0;
    while (n < kTetFieldNameSize && raw_name[n] != 0) ++n;
    field.name.assign(reinterpret_cast<const char*>(raw_name), n);
    h.fields.push_back(field);
  }
  *out = h;
  return {};
}

std::vector<uint8_t> serializePtHeader(const PtHeader& h) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  w.u8(h.position_bits);
  w.u8(static_cast<uint8_t>(h.fields.size()));
  w.u16(0);
  w.u32(h.vertex_count);
  w.u32(h.base_vertex_count);
  w.u32(h.base_tet_count);
  w.u32(h.tet_count);
  w.u32(h.batch_count);
  for (double o : h.origin) w.f64(o);
  w.f64(h.position_step);
  for (const PtField& f : h.fields) {
    w.u8(f.bits);
    for (int i = 0; i < 7; ++i) w.u8(0);
    w.f64(f.origin);
    w.f64(f.step);
    for (size_t i = 0; i < kTetFieldNameSize; ++i)
      w.u8(i < f.name.size() ? static_cast<uint8_t>(f.name[i]) : 0);
  }
  return out;
}

}  // namespace mrsv
