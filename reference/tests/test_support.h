// Helpers shared by the unit tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrsv::test {

// Reads a file; fails the current test (and returns empty) when it cannot.
std::vector<uint8_t> readFileOrFail(const std::string& path);

// Path of a file in the source tree, e.g. sourcePath("conformance/manifest.json").
std::string sourcePath(const std::string& relative);

// The conformance vectors listed in conformance/manifest.json (a minimal
// reader for that file's fixed layout: one vector object per line).
struct VectorEntry {
  std::string file;
  bool valid = false;
  int error = 0;
  uint64_t offset = 0;
};
std::vector<VectorEntry> manifestVectors();

}  // namespace mrsv::test
