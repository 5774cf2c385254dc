// Helpers shared by the unit tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "wavelet/axis_plan.h"

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

// The plan of a CDF 9/7 grid (spec 4.11.1) with these sizes and levels per
// axis; fails the current test when there is none.
wavelet::GridPlan cdf97Plan(int dims, uint32_t nx, uint32_t ny, uint32_t nz, int lx, int ly, int lz);

}  // namespace mrsv::test
