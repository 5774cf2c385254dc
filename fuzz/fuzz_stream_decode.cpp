// Fuzz target: the streaming decoder (stream_decoder.h) fed the input in
// random pieces gives what the one-shot decoder gives on the same bytes: the
// same error (status, offset, field, message) and the same canonical output.
// The piece sizes come from a generator seeded with a hash of the input's
// first bytes (so the corpus stays plain .mrsv files, as fuzz_params.h's
// options do). For half the inputs (a bit of the same hash) the grid levels handed out
// while the bytes arrive are also compared with one-shot decodes of the
// prefix at that reduced resolution.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_params.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/stream_decoder.h"

namespace {

using namespace mrsv;

// splitmix64: small, and the same on every platform.
struct Pieces {
  uint64_t state;
  size_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    // Mostly a few bytes (chunk headers and CRCs split anywhere), sometimes
    // up to 4 KiB (chunks whole in one piece, decoded in place).
    switch (z & 3) {
      case 0: return 1;
      case 1: return 1 + (z >> 8) % 16;
      default: return 1 + (z >> 8) % 4096;
    }
  }
};

uint64_t seedOf(const uint8_t* data, size_t size) {
  uint64_t h = 0xcbf29ce484222325ull ^ size;  // FNV-1a of the first 64 bytes
  for (size_t i = 0; i < std::min<size_t>(size, 64); ++i) h = (h ^ data[i]) * 0x100000001b3ull;
  return h;
}

bool sameError(const Error& a, const Error& b) {
  return a.status == b.status && a.offset == b.offset && a.field == b.field && a.message == b.message;
}

// One-shot decode of data[0, size) (a grid, PM or PT stream).
struct OneShot {
  Error error;
  std::vector<uint8_t> canonical;
};
OneShot oneShot(const uint8_t* data, size_t size, const DecodeOptions& options, StreamContent content) {
  OneShot r;
  if (content == StreamContent::kMesh) {
    DecodedMesh m;
    r.error = decodeProgressiveMesh(data, size, options, &m);
    if (r.error.ok() && m.has_mesh) r.canonical = canonicalMeshOutput(m.mesh);
  } else if (content == StreamContent::kTetMesh) {
    DecodedTetMesh t;
    r.error = decodeProgressiveTetMesh(data, size, options, &t);
    if (r.error.ok() && t.has_mesh) r.canonical = canonicalTetMeshOutput(t.mesh);
  } else {
    DecodedGrid g;
    r.error = decodeGrid(data, size, options, &g);
    if (r.error.ok()) r.canonical = g.samples;
  }
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  DecodeOptions options;
  options.container = fuzz::containerOptionsFromTail(data, size);
  options.max_output_bytes = 64u << 20;
  const uint64_t seed = seedOf(data, size);
  const bool check_levels = (seed >> 63) != 0;
  StreamContent content = isProgressiveMeshStream(data, size)  ? StreamContent::kMesh
                          : isProgressiveTetStream(data, size) ? StreamContent::kTetMesh
                                                               : StreamContent::kGrid;
  const OneShot expected = oneShot(data, size, options, content);

  DecodeOptions stream_options = options;
  stream_options.whole_array_synthesis = check_levels;  // the same samples (see DecodeOptions)
  StreamDecoder decoder(stream_options, content);
  Pieces pieces{seed};
  Error e;
  int next_level = -1;  // the coarsest level not yet asked for
  for (size_t at = 0; at < size && e.ok();) {
    const size_t n = std::min(pieces.next(), size - at);
    e = decoder.feed(data + at, n);
    at += n;
    if (!check_levels || !e.ok() || content != StreamContent::kGrid) continue;
    for (const StreamUnit& unit : decoder.takeUnits()) {
      if (unit.complete_level < 1) continue;
      if (next_level < 0) next_level = unit.complete_level + 100;  // above any plan
      // Each complete level from the coarsest, once (the decoder's contract).
      for (int r = std::min(next_level - 1, 64); r >= unit.complete_level && r >= 1; --r) {
        uint32_t level_size[3];
        std::vector<uint8_t> samples;
        if (r > decoder.grid().wavelet.levels[0] && r > decoder.grid().wavelet.levels[1] &&
            r > decoder.grid().wavelet.levels[2])
          continue;  // no such level
        Error le = decoder.gridLevelSamples(r, level_size, &samples);
        next_level = r;
        if (!le.ok()) {
          if (le.status != Status::kResourceLimit) std::abort();
          continue;
        }
        DecodeOptions prefix_options = options;
        prefix_options.container.allow_partial_tail = true;
        prefix_options.reduce_levels = r;
        const OneShot prefix = oneShot(data, unit.end_offset, prefix_options, content);
        if (prefix.error.ok() && prefix.canonical != samples) std::abort();
      }
    }
  }
  if (e.ok()) e = decoder.finish();
  if (!sameError(e, expected.error)) std::abort();
  if (!e.ok()) return 0;
  std::vector<uint8_t> got;
  if (content == StreamContent::kMesh) {
    if (decoder.mesh().has_mesh) got = canonicalMeshOutput(decoder.mesh().mesh);
  } else if (content == StreamContent::kTetMesh) {
    if (decoder.tetMesh().has_mesh) got = canonicalTetMeshOutput(decoder.tetMesh().mesh);
  } else {
    got = decoder.grid().samples;
  }
  if (got != expected.canonical) std::abort();
  return 0;
}
