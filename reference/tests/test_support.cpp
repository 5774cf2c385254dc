#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace mrsv::test {

std::vector<uint8_t> readFileOrFail(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    ADD_FAILURE() << "cannot open " << path;
    return {};
  }
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

std::string sourcePath(const std::string& relative) {
  return std::string(MRSV_SOURCE_DIR) + "/" + relative;
}

std::vector<VectorEntry> manifestVectors() {
  std::ifstream in(sourcePath("conformance/manifest.json"));
  std::vector<VectorEntry> out;
  std::string line;
  // The value after "key": up to the next ',' or '"' (strings lose their quotes).
  auto field = [](const std::string& text, const std::string& key) -> std::string {
    size_t at = text.find("\"" + key + "\": ");
    if (at == std::string::npos) return {};
    at += key.size() + 4;
    if (at < text.size() && text[at] == '"') return text.substr(at + 1, text.find('"', at + 1) - at - 1);
    return text.substr(at, text.find_first_of(",}", at) - at);
  };
  while (std::getline(in, line)) {
    VectorEntry e;
    e.file = field(line, "file");
    if (e.file.empty()) continue;
    e.valid = field(line, "valid") == "true";
    if (std::string v = field(line, "error"); !v.empty()) e.error = std::stoi(v);
    if (std::string v = field(line, "offset"); !v.empty()) e.offset = std::stoull(v);
    out.push_back(e);
  }
  return out;
}

wavelet::GridPlan cdf97Plan(int dims, uint32_t nx, uint32_t ny, uint32_t nz, int lx, int ly, int lz) {
  const uint32_t n[3] = {nx, ny, nz};
  const int levels[3] = {lx, ly, lz};
  wavelet::GridPlan plan;
  EXPECT_TRUE(wavelet::makeGridPlan(dims, n, wavelet::kOrderCdf97, levels, &plan));
  return plan;
}

}  // namespace mrsv::test
