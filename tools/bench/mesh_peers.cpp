// One mesh simplifier, run on one mesh to one face count, timed: the in-process
// half of the progressive-mesh peer benchmark (tools/bench/mesh_bench.py, issue 3).
//
//   mesh_peers METHOD IN [OUT] [--faces N] [--runs R] [--chain K] [--bits B]
//
// METHOD
//   lt          CGAL edge_collapse, Lindstrom-Turk cost and placement
//   meshopt     meshopt_simplify (meshoptimizer), no error limit, no options
//   mrsv        MRSV's simplifier (the first stage of `mrsv encode`), with the
//               tool's defaults (free placement)
//   mrsv-endpoint ... with --placement endpoint
//   mrsv-paper  ... with --cost paper
//   mrsv-encode MRSV's whole encoder in-process, as `mrsv encode --bits B` runs it:
//               simplification to the base mesh (or to --faces N) and stream
//               coding; OUT is not written, the stream's size is reported
//   repair      no simplification: OUT is the repaired input (e.g. as .obj for
//               tools that cannot read every PLY variant)
//
// Every method starts from IN read and repaired as `mrsv encode` reads it, so all
// get the same indexed triangles. The time is the best of R runs (the machine is
// shared; the best run is the one least disturbed) of the simplification alone:
// input index arrays in, simplified mesh out, file reading and writing excluded.
// Both wall-clock and CPU time of the process are taken (every method runs on
// one thread); on a loaded machine the CPU time is the steadier of the two.
// For lt it includes building CGAL's Surface_mesh, which is how CGAL takes its
// input; for mrsv it is simplifyMesh() alone, the "simplify" part that
// `mrsv encode` reports.
//
// --chain K (meshopt only) builds K levels instead of one, each simplified from
// the one before, with face targets spaced geometrically from the input's count
// down to N: a level-of-detail chain comparable to the K batches of a PM stream.
// The time covers all K levels; OUT is the last one.
//
// OUT (optional; .ply, .obj or .off) receives the result, unused vertices
// dropped. One JSON line goes to stdout; notes go to stderr.
#include <meshoptimizer.h>

#include <time.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mesh_simplifiers.h"
#include "mrsv/file_io.h"
#include "mrsv/metadata.h"
#include "pm/pm_encode.h"

namespace {

using mrsv::TriangleMesh;
using mrsv::bench::secondsSince;

const char kUsage[] =
    "usage: mesh_peers lt|meshopt|mrsv|mrsv-endpoint|mrsv-paper|mrsv-encode|repair IN [OUT] [--faces N] [--runs R]\n"
    "                  [--chain K] [--bits B]\n";

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Outcome {
  TriangleMesh mesh;
  double seconds = 0.0;       // what is compared (see the file comment)
  double cpu_seconds = 0.0;   // the same span in CPU time
  double extra_seconds = -1;  // lt: edge_collapse alone; negative when not applicable
  double error = -1;          // meshopt: its own relative error estimate of the last level
  uint64_t levels = 1;
  uint64_t batches = 0;       // mrsv: batches of collapses
  uint64_t stream_bytes = 0;  // mrsv-encode
};

// meshopt_simplify with no error limit (FLT_MAX: the target count alone stops
// it) and no options, the library's documented safe default. It keeps a subset
// of the input vertices, so the positions are the input's doubles.
Outcome runMeshopt(const TriangleMesh& mesh, uint64_t target, uint64_t levels) {
  std::vector<float> positions;
  positions.reserve(mesh.positions.size() * 3);
  for (const auto& p : mesh.positions)
    for (double c : p) positions.push_back(static_cast<float>(c));
  std::vector<unsigned> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());

  Outcome o;
  o.levels = levels;
  const double cpu_start = cpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  std::vector<unsigned> current = indices, next(indices.size());
  float error = 0.0f;
  const double from = static_cast<double>(mesh.triangles.size());
  for (uint64_t level = 1; level <= levels; ++level) {
    // Geometric spacing; the last level is exactly the target.
    const double ratio = std::pow(static_cast<double>(target) / from, static_cast<double>(level) / levels);
    const uint64_t faces = level == levels ? target : static_cast<uint64_t>(std::llround(from * ratio));
    // meshopt asserts target <= current: when topology stopped an earlier level short,
    // this level asks for no more than that level has.
    const size_t target_indices = std::min<size_t>(3 * faces, current.size());
    const size_t n = meshopt_simplify(next.data(), current.data(), current.size(), positions.data(),
                                      mesh.positions.size(), 3 * sizeof(float), target_indices, FLT_MAX, 0, &error);
    next.resize(n);
    std::swap(current, next);
    next.resize(current.size());
  }
  o.seconds = secondsSince(start);
  o.cpu_seconds = cpuSeconds() - cpu_start;
  o.error = error;
  o.mesh.positions = mesh.positions;
  for (size_t i = 0; i + 2 < current.size(); i += 3)
    o.mesh.triangles.push_back({current[i], current[i + 1], current[i + 2]});
  mrsv::dropUnusedVertices(&o.mesh, nullptr);
  return o;
}

// MRSV's simplifier; for mrsv-encode also the stream coding that follows it in
// `mrsv encode` (same calls, same options, no metadata, no file).
bool runMrsv(const TriangleMesh& mesh, uint64_t target, const std::string& method, uint64_t bits, Outcome* o,
             std::string* error) {
  mrsv::SimplifyOptions options;
  // As `mrsv encode` sets it (the library's own default is endpoint).
  options.placement = method == "mrsv-endpoint" ? mrsv::Placement::kEndpoint : mrsv::Placement::kFree;
  if (method == "mrsv-paper") options.cost = mrsv::CollapseCost::kPaper;
  options.target_triangles = target;
  mrsv::SimplifyResult result;
  const double cpu_start = cpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  if (!mrsv::simplifyMesh(mesh, options, &result, error)) return false;
  if (method == "mrsv-encode") {
    mrsv::PmEncodeOptions encode;
    encode.position_bits = static_cast<uint8_t>(bits);
    encode.placement = options.placement;
    std::vector<uint8_t> stream;
    mrsv::PmEncodeReport report;
    if (!mrsv::encodeProgressiveMesh(mesh, result, encode, mrsv::Metadata{}, &stream, &report, error)) return false;
    o->stream_bytes = stream.size();
  }
  o->seconds = secondsSince(start);
  o->cpu_seconds = cpuSeconds() - cpu_start;
  o->batches = result.batches.size();
  o->levels = result.batches.size();
  o->mesh = mrsv::bench::meshAfterCollapses(mesh, result);
  return true;
}

bool parseCount(const char* text, uint64_t* out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 10);
  if (*text == '\0' || *end != '\0' || *text == '-') return false;
  *out = v;
  return true;
}

std::string jsonEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  std::vector<std::string> positional;
  uint64_t faces = 0, runs = 1, chain = 1, bits = 14;
  bool have_faces = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    uint64_t* value = a == "--faces"   ? &faces
                      : a == "--runs"  ? &runs
                      : a == "--chain" ? &chain
                      : a == "--bits"  ? &bits
                                       : nullptr;
    if (value) {
      if (i + 1 >= argc || !parseCount(argv[i + 1], value)) {
        std::fprintf(stderr, "mesh_peers: %s needs a whole number\n%s", a.c_str(), kUsage);
        return 2;
      }
      have_faces |= value == &faces;
      ++i;
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "mesh_peers: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() < 2 || positional.size() > 3 || runs < 1 || chain < 1 || bits < 1 || bits > 30) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string& method = positional[0];
  const std::string& in = positional[1];
  const std::string out = positional.size() == 3 ? positional[2] : "";
  const bool is_mrsv = method == "mrsv" || method == "mrsv-endpoint" || method == "mrsv-paper" || method == "mrsv-encode";
  if (method != "lt" && method != "meshopt" && method != "repair" && !is_mrsv) {
    std::fprintf(stderr, "mesh_peers: unknown method %s\n%s", method.c_str(), kUsage);
    return 2;
  }
  // mrsv-encode without --faces goes to the base mesh, as `mrsv encode` does.
  if (method != "repair" && method != "mrsv-encode" && !have_faces) {
    std::fprintf(stderr, "mesh_peers: %s needs --faces N\n", method.c_str());
    return 2;
  }
  if (chain != 1 && method != "meshopt") {
    std::fprintf(stderr, "mesh_peers: --chain is for meshopt only\n");
    return 2;
  }

  TriangleMesh mesh;
  mrsv::MeshRepairReport report;
  std::string error;
  const auto read_start = std::chrono::steady_clock::now();
  if (!mrsv::bench::readRepairedMesh(in, &mesh, &report, &error)) {
    std::fprintf(stderr, "mesh_peers: %s\n", error.c_str());
    return 1;
  }
  const double read_seconds = secondsSince(read_start);
  std::fprintf(stderr, "mesh_peers: %s: %s\n", in.c_str(), mrsv::describe(report).c_str());

  Outcome best;
  std::vector<double> times;
  double best_cpu = 0.0;
  for (uint64_t run = 0; run < (method == "repair" ? 1 : runs); ++run) {
    Outcome o;
    if (method == "repair") {
      o.mesh = mesh;
    } else if (method == "meshopt") {
      o = runMeshopt(mesh, faces, chain);
    } else if (method == "lt") {
      const double cpu_start = cpuSeconds();
      const mrsv::bench::LindstromTurkRun r = mrsv::bench::simplifyLindstromTurk(mesh, faces, &o.mesh);
      o.cpu_seconds = cpuSeconds() - cpu_start;  // includes copying the result out; small next to the collapses
      o.seconds = r.build_seconds + r.collapse_seconds;
      o.extra_seconds = r.collapse_seconds;
      if (r.rejected_faces)
        std::fprintf(stderr, "mesh_peers: note: CGAL refused %zu faces of the repaired mesh\n", r.rejected_faces);
    } else if (!runMrsv(mesh, faces, method, bits, &o, &error)) {
      std::fprintf(stderr, "mesh_peers: %s: %s\n", in.c_str(), error.c_str());
      return 1;
    }
    times.push_back(o.seconds);
    // Best wall and best CPU are taken separately: each is the least disturbed run by its own measure.
    if (run == 0 || o.cpu_seconds < best_cpu) best_cpu = o.cpu_seconds;
    if (run == 0 || o.seconds < best.seconds) best = std::move(o);
  }

  if (!out.empty() && method != "mrsv-encode") {
    std::vector<uint8_t> bytes;
    if (!mrsv::encodeMeshFile(out, best.mesh, &bytes, &error) ||
        !mrsv::writeFileAtomically(out, bytes, &error)) {
      std::fprintf(stderr, "mesh_peers: %s: %s\n", out.c_str(), error.c_str());
      return 3;
    }
  }

  std::string all;
  for (double t : times) all += (all.empty() ? "" : ", ") + std::to_string(t);
  std::printf("{\"method\": \"%s\", \"input\": \"%s\", \"input_vertices\": %zu, \"input_triangles\": %zu, "
              "\"read_seconds\": %.6f, \"target\": %llu, \"vertices\": %zu, \"triangles\": %zu, \"levels\": %llu, "
              "\"batches\": %llu, \"runs\": %zu, \"seconds\": %.6f, \"seconds_all\": [%s], "
              "\"cpu_seconds\": %.6f, \"collapse_seconds\": %.6f, \"meshopt_error\": %.6g, \"stream_bytes\": %llu}\n",
              method.c_str(), jsonEscape(in).c_str(), mesh.positions.size(), mesh.triangles.size(), read_seconds,
              static_cast<unsigned long long>(faces), best.mesh.positions.size(), best.mesh.triangles.size(),
              static_cast<unsigned long long>(best.levels), static_cast<unsigned long long>(best.batches),
              times.size(), best.seconds, all.c_str(), best_cpu, best.extra_seconds, best.error,
              static_cast<unsigned long long>(best.stream_bytes));
  return 0;
}
