// pt_decode_bench: PT decoding alone (issue 21's speed goal, 10^6 splits/s),
// from stream files, so that a profiler sees nothing but the decoder.
//
//   pt_decode_bench [--repeat N] FILE.mrsv...
//
// Per file: the splits decoded, the best of N whole decodes (container to the
// finest level; the machine is shared, the best is the least disturbed) and
// splits per second; then the best of N decodes of the base mesh alone and the
// splits per second of the rest (whole minus base). Under `valgrind --tool=callgrind` run it with
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
    // The best of `repeat` decodes with `options`; splits decoded in *splits.
    auto bestOf = [&](const mrsv::DecodeOptions& options, uint32_t* splits) {
      double best = 1e30;
      for (int r = 0; r < repeat; ++r) {
        mrsv::DecodedTetMesh decoded;
        const auto start = std::chrono::steady_clock::now();
        const mrsv::Error e = mrsv::decodeProgressiveTetMesh(bytes.data(), bytes.size(), options, &decoded);
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!e.ok()) {
          std::fprintf(stderr, "%s: %s\n", file.c_str(), e.message.c_str());
          return -1.0;
        }
        *splits = decoded.mesh.splitsDecoded();
      }
      return best;
    };
    uint32_t splits = 0, none = 0;
    const double whole = bestOf(mrsv::DecodeOptions{}, &splits);
    // The base mesh alone (the stop at the base's vertices): its decoding and
    // checks (7.4) are not splits: 6 % of the hand's whole decode.
    mrsv::DecodeOptions base_only;
    base_only.stop_at_vertices = 1;
    const double base = whole < 0 ? -1.0 : bestOf(base_only, &none);
    if (whole < 0 || base < 0) {
      status = 1;
      continue;
    }
    std::printf("%s: %u splits, best of %d %.2f ms, %.0f splits/s; base mesh alone %.2f ms, splits alone %.0f splits/s\n",
                file.c_str(), splits, repeat, 1e3 * whole, splits / whole, 1e3 * base,
                splits / std::max(whole - base, 1e-9));
  }
  return status;
}
