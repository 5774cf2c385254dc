// pt_bench: the measured goals of issue 21 for progressive tet meshes, each
// printed beside its peer measured in the same run.
//
//   build    simplification with every consistency test on (and without the
//            boundary intersection test): seconds and collapses per second,
//            collapses evaded by each test (the paper: 41'03" and 10'40").
//   size     stream bytes, bits per split of connectivity and geometry, bits
//            per tet and per vertex, against `xz -9` of the same quantised mesh
//            in binary (positions and fields in their bytes, 32-bit indices).
//   decode   splits per second, decoding the whole stream (best of 3), against
//            CGAL's Delaunay_triangulation_3 of the finest level's vertices.
//   levels   at 50/20/10/5 % of the tets: time to reach the level from the
//            finest (setLevel) against rebuilding it (simplifying the input to
//            that tet count); field PSNR at 10^6 random positions, boundary
//            Hausdorff and dihedral angles against CGAL's Tetrahedral_remeshing
//            coarsened to the same tet count (its field resampled), validity.
//
//   pt_bench [--meshes ct,bunny,hand,bluntfin,lox] [--no-peer] [--samples N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cgal_delaunay_peer.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/tet_formats.h"
#include "mrsv/tet_metrics.h"
#include "pt/pt_encode.h"
#include "shared_data.h"
#include "tet_cgal_peer.h"
#include "tetsimplify/tet_simplify.h"

namespace {

using namespace mrsv;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

const std::string kData = MRSV_SHARED_DATA;

bool loadMesh(const std::string& name, TetMesh* mesh) {
  std::string error;
  if (name == "ct") {
    test::SharedGrid grid;
    if (!test::loadSharedGrid(kData + "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst", &grid)) return false;
    GridCrop crop;
    const uint32_t origin[3] = {112, 112, 40};
    for (int a = 0; a < 3; ++a) crop.origin[a] = origin[a], crop.size[a] = 32;
    const double spacing[3] = {1, 1, 2};
    TetBuildReport report;
    return tetrahedralizeGrid(grid.header, grid.samples, spacing, crop, mesh, &report, &error);
  }
  if (name == "bunny") return readTetFile(kData + "/tet/bunny_5433v_34055tet.mesh", mesh, nullptr, &error);
  if (name == "hand") return readTetFile(kData + "/tet/hand_7234v_29998tet.mesh", mesh, nullptr, &error);
  const char* plot3d = name == "bluntfin"  ? "bluntfin_plot3d_40x32x32_f32be"
                       : name == "lox"     ? "lox_post_plot3d_38x76x38_f32be"
                       : name == "chamber" ? "combustion_chamber_plot3d_57x33x25_f32be"
                                           : nullptr;
  if (!plot3d) return false;
  Plot3dData data;
  const std::string base = kData + "/tet/" + plot3d;
  if (!readPlot3d(base + (name == "lox" ? "_iblank.xyz" : ".xyz"), base + ".q", &data, &error)) return false;
  TetBuildReport report;
  if (!tetrahedralizePlot3d(data, mesh, &report, &error)) return false;
  mesh->fields.resize(1);  // density
  return true;
}

// xz -9 of the quantised mesh in binary: what a user would get without us.
size_t xzBytes(const QuantizedTets& q) {
  const int pb = (q.header.position_bits + 7) / 8;
  std::vector<uint8_t> raw;
  auto put = [&](uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) raw.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  const size_t fc = q.header.fields.size();
  for (size_t v = 0; v < q.positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) put(static_cast<uint32_t>(q.positions[v][a]), pb);
    for (size_t f = 0; f < fc; ++f) put(static_cast<uint32_t>(q.scalars[v * fc + f]), (q.header.fields[f].bits + 7) / 8);
  }
  for (const Tet& t : q.tets)
    for (uint32_t v : t) put(v, 4);
  std::string temp = (std::filesystem::temp_directory_path() / "pt_bench_XXXXXX").string();
  char* path = temp.data();
  const int fd = mkstemp(path);
  if (fd < 0) return 0;
  FILE* f = fdopen(fd, "wb");
  std::fwrite(raw.data(), 1, raw.size(), f);
  std::fclose(f);
  const std::string command = std::string("xz -9 -c ") + path + " | wc -c";
  FILE* p = popen(command.c_str(), "r");
  unsigned long long size = 0;
  if (p) {
    if (std::fscanf(p, "%llu", &size) != 1) size = 0;
    pclose(p);
  }
  std::remove(path);
  return static_cast<size_t>(size);
}

void runMesh(const std::string& name, bool peer, uint64_t samples) {
  TetMesh mesh;
  if (!loadMesh(name, &mesh)) {
    std::printf("%s: cannot load\n", name.c_str());
    return;
  }
  QuantizedTets q;
  int bits = 16;
  while (!quantizeTetMesh(mesh, bits, 16, &q).ok() && bits < 30) bits += 2;
  QuantizedTetMesh input{q.positions, q.tets, {}};
  for (const ScalarField& f : mesh.fields) input.fields.push_back(f.values);
  std::printf("\n## %s: %zu vertices, %zu tets, %zu fields, %d position bits\n", name.c_str(), mesh.positions.size(),
              mesh.tets.size(), mesh.fields.size(), bits);

  // build
  TetSimplifyResult result, fast;
  auto t0 = Clock::now();
  Error e = simplifyTets(input, TetSimplifyOptions{}, &result);
  auto t1 = Clock::now();
  TetSimplifyOptions no_intersections;
  no_intersections.boundary_intersection_test = false;
  simplifyTets(input, no_intersections, &fast);
  auto t2 = Clock::now();
  if (!e.ok()) {
    std::printf("%s: simplify: %s\n", name.c_str(), e.message.c_str());
    return;
  }
  const TetSimplifyStats& s = result.stats;
  std::printf("build: %.3f s, %.0f collapses/s (every test on); %.3f s without the intersection test; "
              "%llu collapses in %llu batches (%.1f per batch), base %llu tets\n",
              seconds(t0, t1), s.collapses / seconds(t0, t1), seconds(t1, t2),
              (unsigned long long)s.collapses, (unsigned long long)s.batches, s.averageBatchSize(),
              (unsigned long long)s.final_tets);
  std::printf("evaded: %llu boundary table, %llu link, %llu inversion, %llu degenerate, %llu self-intersection\n",
              (unsigned long long)s.evaded_boundary_table, (unsigned long long)s.evaded_link,
              (unsigned long long)s.evaded_inversion, (unsigned long long)s.evaded_degenerate,
              (unsigned long long)s.evaded_self_intersection);

  // size
  std::vector<std::vector<PtCollapse>> batches(result.batches.size());
  for (size_t b = 0; b < batches.size(); ++b)
    for (const TetCollapse& c : result.batches[b]) batches[b].push_back({c.vs, c.vt});
  std::vector<uint8_t> stream;
  PtStreamStats st;
  e = writePtStream(q, batches, &stream, &st);
  if (!e.ok()) {
    std::printf("%s: write: %s\n", name.c_str(), e.message.c_str());
    return;
  }
  const size_t xz = xzBytes(q);
  const double splits = std::max(1u, st.splits);
  std::printf("size: %zu bytes (%.2f bits/tet, %.2f bits/vertex); per split %.2f bits connectivity "
              "(%.2f flags in %.1f decisions + %.2f cut), %.2f geometry; xz -9 of the binary mesh %zu bytes: xz/mrsv %.2f\n",
              stream.size(), 8.0 * stream.size() / mesh.tets.size(), 8.0 * stream.size() / mesh.positions.size(),
              (st.flag_bits + st.cut_bits) / splits, st.flag_bits / splits, st.flag_decisions / splits, st.cut_bits / splits,
              st.value_bits / splits, xz, xz ? double(xz) / stream.size() : 0.0);

  // decode, and its peer in turn (a slow spell falls on both): CGAL's
  // Delaunay triangulation of the finest level's vertices, the paper's other
  // way to a tet mesh of them (7.2).
  double best = 1e9, delaunay = 1e9;
  size_t delaunay_tets = 0;
  DecodedTetMesh d;
  std::vector<std::array<double, 3>> vertices;
  for (int i = 0; i < 3; ++i) {
    auto a = Clock::now();
    decodeProgressiveTetMesh(stream.data(), stream.size(), DecodeOptions{}, &d);
    best = std::min(best, seconds(a, Clock::now()));
    if (i == 0) vertices = d.mesh.mesh().positions;
    delaunay = std::min(delaunay, bench::cgalDelaunaySeconds(vertices, &delaunay_tets));
  }
  std::printf("decode: %.3f s for %u splits: %.0f splits/s; CGAL Delaunay_triangulation_3 of its %zu vertices "
              "%.3f s (%zu tets, %.0f vertices/s): decode/CGAL %.2fx\n",
              best, st.splits, st.splits / best, vertices.size(), delaunay, delaunay_tets, vertices.size() / delaunay,
              (st.splits / best) / (vertices.size() / delaunay));

  // levels
  std::printf("| tets %% | PT tets | reach (ms) | rebuild (ms) | rebuild/reach | PT PSNR | CGAL PSNR | PT-CGAL dB |"
              " PT Hausdorff | CGAL Hausdorff | PT min dih worst/mean | CGAL min dih worst/mean | PT valid | CGAL s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  ProgressiveTetMesh& pt = d.mesh;
  for (double fraction : {0.5, 0.2, 0.1, 0.05}) {
    // Reaching the level from the finest, best of 3 (the machine is shared).
    const uint64_t target = static_cast<uint64_t>(fraction * mesh.tets.size());
    double reach = 1e9;
    for (int i = 0; i < 3; ++i) {
      pt.setLevel(pt.splitsDecoded());
      auto start = Clock::now();
      pt.setLevel(pt.finestLevelWithin(target));
      reach = std::min(reach, seconds(start, Clock::now()));
    }
    auto a = Clock::now();
    TetSimplifyOptions rebuild_options;
    rebuild_options.min_base_tets = pt.tetCount();
    TetSimplifyResult rebuilt;
    a = Clock::now();
    simplifyTets(input, rebuild_options, &rebuilt);
    const double rebuild = seconds(a, Clock::now());
    const TetMesh level = pt.mesh();
    TetCompareOptions options;
    options.field.sample_count = samples;
    const bool has_field = !mesh.fields.empty();
    options.field.field = has_field ? mesh.fields[0].name : "";
    const TetCompareReport ours = compareTetMeshes(mesh, level, options);
    double cgal_psnr = NAN, cgal_h = NAN, cgal_worst = NAN, cgal_mean = NAN, cgal_s = NAN;
    if (peer) {
      bench::CgalPeerResult peer_result;
      std::string error;
      if (bench::cgalCoarsen(mesh, pt.tetCount(), bench::CgalPeerOptions{}, &peer_result, &error)) {
        const TetCompareReport theirs = compareTetMeshes(mesh, peer_result.mesh, options);
        cgal_psnr = theirs.field.psnr_db;
        cgal_h = theirs.boundary.hausdorff / theirs.boundary.bbox_diagonal;
        cgal_worst = theirs.quality_b.min_dihedral_worst;
        cgal_mean = theirs.quality_b.min_dihedral_mean;
        cgal_s = peer_result.seconds_all;
      } else {
        std::printf("CGAL: %s\n", error.c_str());
      }
    }
    std::printf("| %.0f | %u | %.2f | %.0f | %.0f | %.2f | %.2f | %+.2f | %.4f | %.4f | %.1f / %.1f | %.1f / %.1f | %s | %.1f |\n",
                100 * fraction, pt.tetCount(), 1e3 * reach, 1e3 * rebuild, rebuild / std::max(reach, 1e-9),
                has_field ? ours.field.psnr_db : NAN, cgal_psnr, has_field ? ours.field.psnr_db - cgal_psnr : NAN,
                ours.boundary.hausdorff / ours.boundary.bbox_diagonal, cgal_h, ours.quality_b.min_dihedral_worst,
                ours.quality_b.min_dihedral_mean, cgal_worst, cgal_mean, ours.quality_b.valid() ? "yes" : "NO", cgal_s);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes{"ct", "bunny", "hand", "bluntfin", "lox"};
  bool peer = true;
  uint64_t samples = 1000000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no-peer") {
      peer = false;
    } else if (arg == "--samples" && i + 1 < argc) {
      samples = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--meshes" && i + 1 < argc) {
      meshes.clear();
      std::string list = argv[++i];
      for (size_t at = 0; at <= list.size();) {
        size_t comma = list.find(',', at);
        if (comma == std::string::npos) comma = list.size();
        meshes.push_back(list.substr(at, comma - at));
        at = comma + 1;
      }
    } else {
      std::fprintf(stderr,
                   "usage: pt_bench [--meshes ct,bunny,hand,bluntfin,lox,chamber] [--no-peer] [--samples N]\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  std::printf("# pt_bench: PT streams (issue 21) against xz -9 and CGAL's Tetrahedral_remeshing, one run\n");
  for (const std::string& name : meshes) runMesh(name, peer, samples);
  return 0;
}
