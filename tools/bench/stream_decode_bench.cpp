// stream_decode_bench: the streaming decoder (stream_decoder.h) fed a stream
// byte by byte and in 1460-byte pieces (a TCP segment's payload), against the
// one-shot decode of the same file (which is the same decoder fed all at once).
// Issue 25's goal: byte by byte within 1.2x of one-shot.
//
//   stream_decode_bench [--repeat N] [--mode all|oneshot|bytes|1460] FILE.mrsv...
//
// Per file and mode: the best of N decodes (the machine is shared, the best is
// the least disturbed) and the ratio to one-shot. Grids, PM and PT streams
// alike (the first chunk says which). For instructions rather than time, run
// one mode at a time under `valgrind --tool=callgrind` with --repeat 1 and
// compare the totals.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mrsv/stream_decoder.h"

namespace {

using namespace mrsv;

StreamContent contentOf(const std::vector<uint8_t>& b) {
  return isProgressiveMeshStream(b.data(), b.size())  ? StreamContent::kMesh
         : isProgressiveTetStream(b.data(), b.size()) ? StreamContent::kTetMesh
                                                      : StreamContent::kGrid;
}

// One decode of `bytes` in pieces of `piece` bytes (0: one-shot call).
Error decodeOnce(const std::vector<uint8_t>& bytes, size_t piece) {
  const StreamContent content = contentOf(bytes);
  if (piece == 0) {
    switch (content) {
      case StreamContent::kMesh: {
        DecodedMesh m;
        return decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &m);
      }
      case StreamContent::kTetMesh: {
        DecodedTetMesh t;
        return decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &t);
      }
      default: {
        DecodedGrid g;
        return decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &g);
      }
    }
  }
  StreamDecoder d(DecodeOptions{}, content);
  for (size_t at = 0; at < bytes.size(); at += piece)
    if (Error e = d.feed(bytes.data() + at, std::min(piece, bytes.size() - at)); !e.ok()) return e;
  return d.finish();
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::string mode = "all";
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--mode" && i + 1 < argc) {
      mode = argv[++i];
    } else if (!arg.empty() && arg[0] != '-') {
      files.push_back(arg);
    } else {
      std::fprintf(stderr, "usage: stream_decode_bench [--repeat N] [--mode all|oneshot|bytes|1460] FILE.mrsv...\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  struct Mode {
    const char* name;
    size_t piece;
  };
  std::vector<Mode> modes;
  if (mode == "all" || mode == "oneshot") modes.push_back({"one-shot", 0});
  if (mode == "all" || mode == "bytes") modes.push_back({"byte by byte", 1});
  if (mode == "all" || mode == "1460") modes.push_back({"1460-byte pieces", 1460});
  if (modes.empty()) {
    std::fprintf(stderr, "stream_decode_bench: --mode must be all, oneshot, bytes or 1460\n");
    return 2;
  }
  int status = 0;
  for (const std::string& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    double one_shot = 0;
    for (const Mode& m : modes) {
      double best = 1e30;
      for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const Error e = decodeOnce(bytes, m.piece);
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!e.ok()) {
          std::fprintf(stderr, "%s: %s\n", file.c_str(), e.describe().c_str());
          status = 1;
          break;
        }
      }
      if (m.piece == 0) one_shot = best;
      if (one_shot > 0 && m.piece != 0)
        std::printf("%s: %zu bytes, %s: best of %d %.2f ms, %.3fx one-shot\n", file.c_str(), bytes.size(), m.name,
                    repeat, 1e3 * best, best / one_shot);
      else
        std::printf("%s: %zu bytes, %s: best of %d %.2f ms\n", file.c_str(), bytes.size(), m.name, repeat, 1e3 * best);
    }
  }
  return status;
}
