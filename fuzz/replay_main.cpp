// Replays files through a fuzz target without libFuzzer, so every target is
// also an ordinary test under any compiler (and under the sanitizers).
#include <dirent.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

int replayPath(const std::string& path) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) {
    std::fprintf(stderr, "replay: %s: not found\n", path.c_str());
    return -1;
  }
  if (S_ISDIR(st.st_mode)) {
    int count = 0;
    DIR* dir = opendir(path.c_str());
    if (!dir) return -1;
    while (dirent* entry = readdir(dir)) {
      if (entry->d_name[0] == '.') continue;
      int n = replayPath(path + "/" + entry->d_name);
      if (n < 0) {
        closedir(dir);
        return -1;
      }
      count += n;
    }
    closedir(dir);
    return count;
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes(std::istreambuf_iterator<char>(in), {});
  // An exact-size heap copy, so sanitizers catch reads past the end.
  std::vector<uint8_t> exact(bytes.begin(), bytes.end());
  LLVMFuzzerTestOneInput(exact.data(), exact.size());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  int total = 0;
  for (int i = 1; i < argc; ++i) {
    int n = replayPath(argv[i]);
    if (n < 0) return 1;
    total += n;
  }
  std::printf("replayed %d inputs\n", total);
  return total > 0 ? 0 : 1;
}
