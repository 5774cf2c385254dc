#include "shared_data.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <regex>

#include "test_support.h"

namespace mrsv::test {

std::vector<std::string> sharedGridFiles() {
  std::vector<std::string> files;
  for (const char* sub : {"terrain", "volume"}) {
    std::string dir = std::string(MRSV_SHARED_DATA) + "/" + sub;
    DIR* d = opendir(dir.c_str());
    if (!d) {
      ADD_FAILURE() << "missing " << dir << " (../shared/data must sit beside the project)";
      continue;
    }
    while (dirent* entry = readdir(d)) {
      std::string name = entry->d_name;
      if (name.size() > 8 && name.compare(name.size() - 8, 8, ".raw.zst") == 0)
        files.push_back(dir + "/" + name);
    }
    closedir(d);
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool loadSharedGrid(const std::string& path, SharedGrid* out) {
  static const std::regex kName(R"(_(\d+)x(\d+)(?:x(\d+))?_(uint8|int16le|uint16le)\.raw\.zst$)");
  std::smatch m;
  if (!std::regex_search(path, m, kName)) {
    ADD_FAILURE() << path << ": name does not give dims and type";
    return false;
  }
  out->name = path.substr(path.find_last_of('/') + 1);
  GridHeader& h = out->header;
  h = GridHeader{};
  h.size_x = static_cast<uint32_t>(std::stoul(m[1]));
  h.size_y = static_cast<uint32_t>(std::stoul(m[2]));
  h.num_dims = m[3].matched ? 3 : 2;
  if (m[3].matched) h.size_z = static_cast<uint32_t>(std::stoul(m[3]));
  std::string type = m[4];
  h.sample_type = type == "uint8" ? SampleType::kUint8
                  : type == "int16le" ? SampleType::kInt16 : SampleType::kUint16;
  std::vector<uint8_t> packed = readFileOrFail(path);
  unsigned long long size = ZSTD_getFrameContentSize(packed.data(), packed.size());
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN) {
    ADD_FAILURE() << path << ": not a zstd frame with a content size";
    return false;
  }
  out->samples.resize(size);
  size_t got = ZSTD_decompress(out->samples.data(), size, packed.data(), packed.size());
  if (ZSTD_isError(got) || got != size) {
    ADD_FAILURE() << path << ": zstd: " << (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short");
    return false;
  }
  if (size != h.sampleCount() * sampleSize(h.sample_type)) {
    ADD_FAILURE() << path << ": size does not match the name";
    return false;
  }
  return true;
}

}  // namespace mrsv::test
