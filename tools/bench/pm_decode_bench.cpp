// Progressive-mesh decoding speed (issue: at least 5 M vertex splits per
// second on one core). For each mesh, PM streams are built in memory as
// `mrsv encode` builds them (repair, simplify, encode): with the default
// options (free placement, 16 bits), with --bits 14, and with --bits 14
// --placement endpoint. Each is then timed:
//
//   Decode/<mesh>/<stream>     decodeProgressiveMesh() of the whole stream
//                              from memory (container, PHDR, PBAS, every PSPL);
//   Entropy/<mesh>/<stream>    the range decoder alone on the same payloads,
//                              making the stream's own decisions (bit models
//                              and direct bits, recorded once) with nothing
//                              else: the ceiling that the coding of spec 6.5
//                              and 6.7 puts on any decoder of the stream;
//   Rest/<mesh>/<stream>       the decoder's own loop (records, predictions,
//                              rings, splits) with every decision's outcome
//                              read back from the recording instead of range
//                              decoded: the ceiling that the rest of spec 6
//                              puts on a decoder whose entropy decoding were
//                              free;
//   LevelUp/<mesh>/<stream>    ProgressiveMesh::setLevel(finest) from level 0,
//                              the records already parsed (vertex splits only);
//   LevelDown/<mesh>/<stream>  setLevel(0) from the finest level (collapses).
//
// items_per_second is splits (or collapses) per second. The level benchmarks
// move the mesh back outside the timed region between iterations.
//
//   build/pm_decode_bench [--data DIR] [--mesh SUBSTRING] [--benchmark_filter=...]
//
// DIR defaults to the shared data's surface/ directory; every .obj/.ply/.off in
// it is used unless --mesh picks the ones whose file name contains SUBSTRING.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <string>
#include <vector>

#include "common/byte_reader.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "pm/pm_records.h"
#include "simplify/simplify.h"

#ifndef MRSV_SHARED_DATA
#define MRSV_SHARED_DATA "../shared/data"
#endif

namespace {

using namespace mrsv;

// One coded payload (PBAS or PSPL) and the decisions its decoding makes:
// an index into PmContexts' bit models, or -n for n direct bits, and what
// each decoded (the bit, or the n bits' value).
struct Payload {
  const uint8_t* data = nullptr;
  size_t size = 0;
  uint32_t split_count = 0;  // 0 for PBAS
  std::vector<int32_t> decisions;
  std::vector<uint32_t> outcomes;
};

struct Stream {
  std::string name;  // mesh/placement and bits
  std::vector<uint8_t> bytes;
  uint32_t splits = 0;
  PmHeader header;
  std::vector<Payload> payloads;  // into `bytes`
};

bool endsWith(const std::string& s, const char* suffix) {
  const size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

std::vector<std::string> meshFiles(const std::string& dir, const std::string& filter) {
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d)) {
      std::string name = e->d_name;
      if ((endsWith(name, ".obj") || endsWith(name, ".ply") || endsWith(name, ".off")) &&
          name.find(filter) != std::string::npos)
        names.push_back(name);
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A range decoder that writes down which decisions it makes and what they
// decode.
struct RecordingCoder {
  static constexpr bool kEncoding = false;
  RangeDecoder rc;
  const pm::PmContexts* contexts;
  Payload* payload;
  int bit(BitModel* m, int) {
    payload->decisions.push_back(static_cast<int32_t>(m - reinterpret_cast<const BitModel*>(contexts)));
    const int b = rc.bit(m);
    payload->outcomes.push_back(static_cast<uint32_t>(b));
    return b;
  }
  int bitUnpredictable(BitModel* m, int b) { return bit(m, b); }
  uint32_t direct(uint32_t, int n) {
    payload->decisions.push_back(-n);
    const uint32_t value = rc.direct(n);
    payload->outcomes.push_back(value);
    return value;
  }
  bool overrun() const { return rc.overrun() != 0; }
};
static_assert(sizeof(pm::PmContexts) % sizeof(BitModel) == 0, "PmContexts is an array of bit models");

// A coder whose decisions come out as recorded, with no range decoding.
struct ReplayCoder {
  static constexpr bool kEncoding = false;
  const uint32_t* next;
  int bit(BitModel*, int) { return static_cast<int>(*next++); }
  int bitUnpredictable(BitModel*, int) { return static_cast<int>(*next++); }
  uint32_t direct(uint32_t, int) { return *next++; }
  bool overrun() const { return false; }
};

// The decoder's loop over the records of every payload (as PmSteps::batch() in
// pm_decode.cpp runs it, without its checks: the stream is our own), each
// payload through the coder that coderFor(payload) makes.
template <class CoderFor>
bool decodeRecords(const PmHeader& h, std::vector<Payload>& payloads, ProgressiveMesh* pm, CoderFor&& coderFor) {
  ProgressiveMesh::Impl& state = pm->state();
  state.header = h;
  pm::PmContexts contexts;
  for (Payload& p : payloads) {
    auto coder = coderFor(p, contexts);
    if (p.split_count == 0) {
      std::vector<std::array<uint32_t, 3>> triangles;
      if (!pm::codeBaseMesh(coder, contexts, state, &triangles).empty() ||
          !state.table.build(h.base_vertex_count, triangles).empty())
        return false;
      state.reserveForSplits(h.splitCount());
    } else {
      BatchCursor cursor = state.beginBatch();
      for (uint32_t k = p.split_count; k > 0; --k) {
        SplitRecord record;
        if (!pm::codeSplit(coder, contexts, state, &cursor, &record).empty()) return false;
        state.splits.push_back(record);
        state.applySplit(state.ring);
      }
    }
  }
  return true;
}

// Finds s->bytes' payloads and records every payload's decisions.
bool recordDecisions(Stream* s) {
  Container c;
  if (!readContainer(s->bytes.data(), s->bytes.size(), DecodeOptions{}.container, &c).ok() ||
      !parsePmHeader(c.chunks[0], &s->header).ok())
    return false;
  for (size_t i = 1; i < c.chunks.size(); ++i) {
    const ChunkView& chunk = c.chunks[i];
    if (chunk.chunk_type == kChunkBaseMesh)
      s->payloads.push_back(Payload{chunk.payload, chunk.chunk_length, 0, {}, {}});
    else if (chunk.chunk_type == kChunkSplits)  // after the batch's split_count
      s->payloads.push_back(
          Payload{chunk.payload + 4, chunk.chunk_length - 4, ByteReader(chunk.payload, 4).u32(), {}, {}});
  }
  ProgressiveMesh pm;
  return decodeRecords(s->header, s->payloads, &pm, [](Payload& p, const pm::PmContexts& contexts) {
    return RecordingCoder{RangeDecoder(p.data, p.size), &contexts, &p};
  });
}

// As `mrsv encode [--bits B] [--placement endpoint] MESH OUT.mrsv`, every
// other option at its default.
bool buildStreams(const std::string& dir, const std::string& file, std::vector<Stream>* out) {
  TriangleMesh mesh;
  std::string error;
  MeshRepairReport repair;
  std::vector<uint32_t> origin;
  if (!readMeshFile(dir + "/" + file, "", &mesh, &error) ||
      !repairMesh(&mesh, MeshRepairOptions{}, &repair, &origin, &error)) {
    std::fprintf(stderr, "pm_decode_bench: %s: %s\n", file.c_str(), error.c_str());
    return false;
  }
  const std::string stem = file.substr(0, file.find('_'));
  struct Variant {
    Placement placement;
    int bits;
  };
  SimplifyResult collapses[2];  // by placement: endpoint, free
  for (const Placement placement : {Placement::kEndpoint, Placement::kFree}) {
    SimplifyOptions simplify;
    simplify.placement = placement;
    if (!simplifyMesh(mesh, simplify, &collapses[placement == Placement::kFree], &error)) {
      std::fprintf(stderr, "pm_decode_bench: %s: %s\n", file.c_str(), error.c_str());
      return false;
    }
  }
  const int default_bits = PmEncodeOptions{}.position_bits;
  for (const Variant v : {Variant{Placement::kFree, default_bits}, Variant{Placement::kFree, 14},
                          Variant{Placement::kEndpoint, 14}}) {
    const bool free = v.placement == Placement::kFree;
    PmEncodeOptions options;
    options.placement = v.placement;
    options.position_bits = static_cast<uint8_t>(v.bits);
    Stream s;
    s.name = stem + "/" + (free ? "free" : "endpoint") + std::to_string(v.bits);
    PmEncodeReport report;
    if (!encodeProgressiveMesh(mesh, collapses[free], options, Metadata{}, &s.bytes, &report, &error)) {
      std::fprintf(stderr, "pm_decode_bench: %s: %s\n", file.c_str(), error.c_str());
      return false;
    }
    s.splits = report.splits;
    out->push_back(std::move(s));
  }
  return true;
}

// Decodes `s` or stops the benchmark with the error.
bool decode(benchmark::State& state, const Stream& s, DecodedMesh* out) {
  Error e = decodeProgressiveMesh(s.bytes.data(), s.bytes.size(), DecodeOptions{}, out);
  if (!e.ok() || out->mesh.splitsDecoded() != s.splits) {
    state.SkipWithError("the stream does not decode");
    return false;
  }
  return true;
}

void BM_Decode(benchmark::State& state, const Stream* s) {
  DecodedMesh decoded;
  for (auto _ : state) {
    if (!decode(state, *s, &decoded)) return;
    benchmark::DoNotOptimize(decoded.mesh.triangleCount());
  }
  state.SetItemsProcessed(int64_t{s->splits} * state.iterations());
  state.counters["splits"] = s->splits;
  state.counters["bytes"] = static_cast<double>(s->bytes.size());
}

// The recorded decisions through a fresh range decoder and fresh models. Bits
// are decoded without a branch on their outcome (bitUnpredictable, the same
// arithmetic): replayed like this, that was 20 to 35 % faster than bit(), so
// these rows are the higher, more generous ceiling.
void BM_Entropy(benchmark::State& state, const Stream* s) {
  uint32_t sink = 0;
  for (auto _ : state) {
    pm::PmContexts contexts;
    BitModel* models = reinterpret_cast<BitModel*>(&contexts);
    for (const Payload& p : s->payloads) {
      RangeDecoder rc(p.data, p.size);
      for (int32_t d : p.decisions) sink += d >= 0 ? rc.bitUnpredictable(&models[d]) : rc.direct(-d);
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(int64_t{s->splits} * state.iterations());
  size_t decisions = 0;
  for (const Payload& p : s->payloads) decisions += p.decisions.size();
  state.counters["decisions_per_split"] = static_cast<double>(decisions) / s->splits;
}

void BM_Rest(benchmark::State& state, Stream* s) {
  for (auto _ : state) {
    ProgressiveMesh pm;
    if (!decodeRecords(s->header, s->payloads, &pm, [](const Payload& p, const pm::PmContexts&) {
          return ReplayCoder{p.outcomes.data()};
        })) {
      state.SkipWithError("the recorded decisions do not decode");
      return;
    }
    benchmark::DoNotOptimize(pm.triangleCount());
  }
  state.SetItemsProcessed(int64_t{s->splits} * state.iterations());
}

void BM_LevelUp(benchmark::State& state, const Stream* s) {
  DecodedMesh decoded;
  if (!decode(state, *s, &decoded)) return;
  ProgressiveMesh& pm = decoded.mesh;
  for (auto _ : state) {
    state.PauseTiming();
    pm.setLevel(0);
    state.ResumeTiming();
    pm.setLevel(s->splits);
    benchmark::DoNotOptimize(pm.triangleCount());
  }
  state.SetItemsProcessed(int64_t{s->splits} * state.iterations());
}

void BM_LevelDown(benchmark::State& state, const Stream* s) {
  DecodedMesh decoded;
  if (!decode(state, *s, &decoded)) return;
  ProgressiveMesh& pm = decoded.mesh;
  for (auto _ : state) {
    state.PauseTiming();
    pm.setLevel(s->splits);
    state.ResumeTiming();
    pm.setLevel(0);
    benchmark::DoNotOptimize(pm.triangleCount());
  }
  state.SetItemsProcessed(int64_t{s->splits} * state.iterations());
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = std::string(MRSV_SHARED_DATA) + "/surface", filter;
  // Our own options first; the rest goes to Google Benchmark.
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--data") == 0 && i + 1 < argc) dir = argv[++i];
    else if (std::strcmp(argv[i], "--mesh") == 0 && i + 1 < argc) filter = argv[++i];
    else rest.push_back(argv[i]);
  }
  int rest_count = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_count, rest.data());

  static std::vector<Stream> streams;  // outlives the registered benchmarks
  const std::vector<std::string> files = meshFiles(dir, filter);
  if (files.empty()) {
    std::fprintf(stderr, "pm_decode_bench: no .obj/.ply/.off mesh in %s\n", dir.c_str());
    return 1;
  }
  for (const std::string& file : files)
    if (!buildStreams(dir, file, &streams)) return 1;
  for (Stream& s : streams)
    if (!recordDecisions(&s)) {
      std::fprintf(stderr, "pm_decode_bench: %s: the stream does not decode\n", s.name.c_str());
      return 1;
    }
  for (Stream& s : streams) {
    benchmark::RegisterBenchmark(("Decode/" + s.name).c_str(), BM_Decode, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Entropy/" + s.name).c_str(), BM_Entropy, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Rest/" + s.name).c_str(), BM_Rest, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("LevelUp/" + s.name).c_str(), BM_LevelUp, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("LevelDown/" + s.name).c_str(), BM_LevelDown, &s)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
