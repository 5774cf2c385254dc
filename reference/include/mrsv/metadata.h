// The meta chunk: key-value text. spec: 2.6.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mrsv/status.h"

namespace mrsv {

// Entries in file order; keys are unique.
struct Metadata {
  std::vector<std::pair<std::string, std::string>> entries;

  const std::string* find(const std::string& key) const;
  // Replaces the value of an existing key, or appends.
  void set(const std::string& key, const std::string& value);
};

// Parses a meta payload. `payload_offset` is its offset in the file, so that
// errors point at the offending byte.
Error parseMetadata(const uint8_t* payload, size_t size, uint64_t payload_offset, Metadata* out);

// Checks one entry against the rules of spec 2.6 (used by encoders before
// writing, so that a tool refuses bad input instead of writing a bad file).
// Returns an empty string when valid, otherwise the rule broken.
std::string metadataEntryProblem(const std::string& key, const std::string& value);

std::vector<uint8_t> serializeMetadata(const Metadata& metadata);

}  // namespace mrsv
