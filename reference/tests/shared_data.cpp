#include "shared_data.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>

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
  // NAME_<X>x<Y>[x<Z>]_<type>.raw.zst: the last two '_' fields give dims and type.
  out->name = path.substr(path.find_last_of('/') + 1);
  std::string stem = out->name.substr(0, out->name.size() - 8);
  size_t type_at = stem.find_last_of('_');
  size_t dims_at = type_at == std::string::npos ? std::string::npos : stem.find_last_of('_', type_at - 1);
  if (dims_at == std::string::npos) {
    ADD_FAILURE() << path << ": name does not give dims and type";
    return false;
  }
  std::string type = stem.substr(type_at + 1);
  std::vector<uint32_t> dims;
  std::string dims_text = stem.substr(dims_at + 1, type_at - dims_at - 1);
  for (size_t start = 0; start <= dims_text.size();) {
    size_t x = dims_text.find('x', start);
    if (x == std::string::npos) x = dims_text.size();
    dims.push_back(static_cast<uint32_t>(std::stoul(dims_text.substr(start, x - start))));
    start = x + 1;
  }
  if (dims.size() < 2 || dims.size() > 3 || (type != "uint8" && type != "int16le" && type != "uint16le")) {
    ADD_FAILURE() << path << ": name does not give dims and type";
    return false;
  }
  GridHeader& h = out->header;
  h = GridHeader{};
  h.num_dims = static_cast<uint8_t>(dims.size());
  h.size_x = dims[0];
  h.size_y = dims[1];
  if (dims.size() == 3) h.size_z = dims[2];
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
