// Progressive-mesh decoding speed (issue: at least 5 M vertex splits per
// second on one core). For each mesh, a PM stream is built in memory as
// `mrsv encode` builds it (repair, simplify, encode), once with the default
// options and once with --bits 14, and then timed:
//
//   Decode/<mesh>/<bits>     decodeProgressiveMesh() of the whole stream from
//                            memory (container, PHDR, PBAS, every PSPL chunk);
//   LevelUp/<mesh>/<bits>    ProgressiveMesh::setLevel(finest) from level 0,
//                            the records already parsed (vertex splits only);
//   LevelDown/<mesh>/<bits>  setLevel(0) from the finest level (edge collapses).
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

#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "simplify/simplify.h"

#ifndef MRSV_SHARED_DATA
#define MRSV_SHARED_DATA "../shared/data"
#endif

namespace {

using namespace mrsv;

struct Stream {
  std::string name;  // mesh/bits
  std::vector<uint8_t> bytes;
  uint32_t splits = 0;
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

// As `mrsv encode [--bits B] MESH OUT.mrsv` with every other option at its default.
bool buildStreams(const std::string& dir, const std::string& file, std::vector<Stream>* out) {
  TriangleMesh mesh;
  std::string error;
  MeshRepairReport repair;
  std::vector<uint32_t> origin;
  SimplifyResult collapses;
  if (!readMeshFile(dir + "/" + file, "", &mesh, &error) ||
      !repairMesh(&mesh, MeshRepairOptions{}, &repair, &origin, &error) ||
      !simplifyMesh(mesh, SimplifyOptions{}, &collapses, &error)) {
    std::fprintf(stderr, "pm_decode_bench: %s: %s\n", file.c_str(), error.c_str());
    return false;
  }
  const std::string stem = file.substr(0, file.find('_'));
  for (int bits : {int{PmEncodeOptions{}.position_bits}, 14}) {
    PmEncodeOptions options;
    options.position_bits = static_cast<uint8_t>(bits);
    Stream s;
    s.name = stem + "/bits" + std::to_string(bits);
    PmEncodeReport report;
    if (!encodeProgressiveMesh(mesh, collapses, options, Metadata{}, &s.bytes, &report, &error)) {
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
  for (const Stream& s : streams) {
    benchmark::RegisterBenchmark(("Decode/" + s.name).c_str(), BM_Decode, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("LevelUp/" + s.name).c_str(), BM_LevelUp, &s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("LevelDown/" + s.name).c_str(), BM_LevelDown, &s)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
