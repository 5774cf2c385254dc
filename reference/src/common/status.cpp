#include "mrsv/status.h"

namespace mrsv {

const char* statusName(Status status) {
  switch (status) {
    case Status::kOk: return "ok";
    case Status::kTruncatedFileHeader: return "truncated_file_header";
    case Status::kBadSignature: return "bad_signature";
    case Status::kSignatureTransferDamage: return "signature_transfer_damage";
    case Status::kUnsupportedVersion: return "unsupported_version";
    case Status::kReservedNonZero: return "reserved_nonzero";
    case Status::kTruncatedChunkHeader: return "truncated_chunk_header";
    case Status::kChunkPastEnd: return "chunk_past_end";
    case Status::kOversizedChunk: return "oversized_chunk";
    case Status::kChecksumMismatch: return "checksum_mismatch";
    case Status::kBadChunkType: return "bad_chunk_type";
    case Status::kUnknownCriticalChunk: return "unknown_critical_chunk";
    case Status::kChunkOrder: return "chunk_order";
    case Status::kBadChunkLength: return "bad_chunk_length";
    case Status::kTrailingBytes: return "trailing_bytes";
    case Status::kTooManyChunks: return "too_many_chunks";
    case Status::kBadMetadata: return "bad_metadata";
    case Status::kBadGridHeader: return "bad_grid_header";
    case Status::kUnsupportedCoding: return "unsupported_coding";
    case Status::kSampleDataMismatch: return "sample_data_mismatch";
    case Status::kBadWaveletHeader: return "bad_wavelet_header";
    case Status::kBadBandHeader: return "bad_band_header";
    case Status::kBadEntropyPayload: return "bad_entropy_payload";
    case Status::kBadTiling: return "bad_tiling";
    case Status::kBadTileIndex: return "bad_tile_index";
    case Status::kBadMeshHeader: return "bad_mesh_header";
    case Status::kBadBaseMesh: return "bad_base_mesh";
    case Status::kBadVertexSplit: return "bad_vertex_split";
    case Status::kSplitCountMismatch: return "split_count_mismatch";
    case Status::kResourceLimit: return "resource_limit";
    case Status::kIoError: return "io_error";
    case Status::kInvalidArgument: return "invalid_argument";
    case Status::kUnsupportedProfile: return "unsupported_profile";
  }
  return "unknown_status";
}

std::string statusCode(Status status) {
  return "E" + std::to_string(static_cast<int>(status));
}

std::string Error::describe() const {
  std::string out = "offset " + std::to_string(offset) + ": " + statusCode(status) + " " +
                    statusName(status) + ": ";
  if (!field.empty()) out += field + ": ";
  out += message;
  return out;
}

}  // namespace mrsv
