#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>

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
  static const std::regex kFile("\"file\": \"([^\"]+)\"");
  static const std::regex kValid("\"valid\": (true|false)");
  static const std::regex kError("\"error\": ([0-9]+)");
  static const std::regex kOffset("\"offset\": ([0-9]+)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, kFile)) continue;
    VectorEntry e;
    e.file = m[1];
    if (std::regex_search(line, m, kValid)) e.valid = m[1] == "true";
    if (std::regex_search(line, m, kError)) e.error = std::stoi(m[1]);
    if (std::regex_search(line, m, kOffset)) e.offset = std::stoull(m[1]);
    out.push_back(e);
  }
  return out;
}

}  // namespace mrsv::test
