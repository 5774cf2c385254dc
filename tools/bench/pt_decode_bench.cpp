// pt_decode_bench: PT decoding alone (issue 21's speed goal, 10^6 splits/s),
// from stream files, so that a profiler sees nothing but the decoder.
//
//   pt_decode_bench [--repeat N] FILE.mrsv...
//
// Per file: the splits decoded, the best of N whole decodes (container to the
// finest level; the machine is shared, the best is the least disturbed) and
// splits per second. Under `valgrind --tool=callgrind` run it with
// --repeat 1: instructions per split = total / splits.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mrsv/progressive_tet_mesh.h"

int main(int argc, char** argv) {
  int repeat = 10;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (!arg.empty() && arg[0] != '-') {
      files.push_back(arg);
    } else {
      std::fprintf(stderr, "usage: pt_decode_bench [--repeat N] FILE.mrsv...\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  int status = 0;
  for (const std::string& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    double best = 1e30;
    uint32_t splits = 0;
    for (int r = 0; r < repeat; ++r) {
      mrsv::DecodedTetMesh decoded;
      const auto start = std::chrono::steady_clock::now();
      const mrsv::Error e = mrsv::decodeProgressiveTetMesh(bytes.data(), bytes.size(), mrsv::DecodeOptions{}, &decoded);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (!e.ok()) {
        std::fprintf(stderr, "%s: %s\n", file.c_str(), e.message.c_str());
        status = 1;
        break;
      }
      splits = decoded.mesh.splitsDecoded();
    }
    std::printf("%s: %u splits, best of %d %.2f ms, %.0f splits/s\n", file.c_str(), splits, repeat, 1e3 * best,
                splits / best);
  }
  return status;
}
