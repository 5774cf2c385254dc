// spec: 3 (encoder side). Stored coding.
#include "mrsv/encode.h"

namespace mrsv {

Error encodeStoredGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                       const Metadata& metadata, std::vector<uint8_t>* out) {
  auto invalid = [](std::string field, std::string message) {
    return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
  };
  GridHeader h = header;
  h.coding = GridCoding::kStored;
  if (std::string problem = gridHeaderProblem(h); !problem.empty())
    return invalid("grid_header", problem);
  uint64_t bytes = h.sampleCount() * sampleSize(h.sample_type);
  if (bytes > kMaxChunkPayload)
    return invalid("GRAW", "stored samples of " + std::to_string(bytes) +
                               " bytes exceed the chunk limit of " +
                               std::to_string(kMaxChunkPayload));
  if (samples.size() != bytes)
    return invalid("samples", "got " + std::to_string(samples.size()) + " bytes, grid needs " +
                                  std::to_string(bytes));
  for (size_t i = 0; i < metadata.entries.size(); ++i) {
    const auto& e = metadata.entries[i];
    if (std::string problem = metadataEntryProblem(e.first, e.second); !problem.empty())
      return invalid("meta", problem);
    for (size_t j = 0; j < i; ++j)
      if (metadata.entries[j].first == e.first)
        return invalid("meta", "key '" + e.first + "' given twice");
  }
  std::vector<uint8_t> meta = serializeMetadata(metadata);
  if (meta.size() > kMaxMetadataPayload || metadata.entries.size() > kMaxMetadataEntries)
    return invalid("meta", "metadata exceeds the limits of Annex B.2");

  ContainerWriter writer;
  writer.addChunk(kChunkGridHeader, serializeGridHeader(h));
  if (!metadata.entries.empty()) writer.addChunk(kChunkMeta, meta);
  writer.addChunk(kChunkGridStored, samples);
  *out = writer.finish();
  return {};
}

}  // namespace mrsv
