// Tet simplifier benchmark (issue 21): build time, collapses per second,
// batch sizes, evasions per test, and per level (50, 20, 10, 5, 2, 1 % of the tets)
// the scalar PSNR at random points (the paper's 7.2 measure) and the worst and
// mean minimum dihedral angles.
//
//   tet_simplify_bench [--mesh ct|ct-peer|lox|lox-io|bluntfin-io|bunny|hand] [--cost quadric|paper]
//                      [--no-intersection] [--min-dihedral D] [--levels]
//                      [--samples N] [--repeat N] [--boundary-weight W] [--cases-2-3]
//                      [--ratio R] [--quantile Q] [--w-grad W] [--w-vol W] [--w-equi W]
//                      [--w-len W] [--w-normal W]
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mrsv/tet_formats.h"
#include "tet_test_meshes.h"
#include "tetsimplify/tet_simplify.h"

using namespace mrsv;

namespace {

const char kUsage[] =
    "usage: tet_simplify_bench [--mesh ct|ct-peer|lox|lox-io|bluntfin-io|combustion-io|bunny|hand]\n"
    "                          [--cost quadric|paper] [--no-intersection] [--min-dihedral D] [--levels]\n"
    "                          [--samples N] [--repeat N] [--boundary-weight W] [--cases-2-3]\n"
    "                          [--ratio R] [--quantile Q] [--w-grad W] [--w-vol W] [--w-equi W]\n"
    "                          [--w-len W] [--w-normal W]\n"
    "The tet simplifier alone (issue 21): build time (wall and CPU, best of --repeat), collapses\n"
    "per second, batches, collapses evaded by each test; with --levels the field PSNR and the\n"
    "minimum dihedral angles at 50/20/10/5/2/1 % of the tets.\n";

// Live tets after each collapse (index i: after i collapses).
std::vector<uint64_t> tetCounts(const QuantizedTetMesh& mesh, const TetSimplifyResult& result) {
  std::vector<std::array<uint32_t, 4>> tets = mesh.tets;
  std::vector<uint8_t> alive(tets.size(), 1);
  std::vector<std::vector<uint32_t>> star(mesh.positions.size());
  for (uint32_t t = 0; t < tets.size(); ++t) {
    for (uint32_t v : tets[t]) star[v].push_back(t);
  }
  std::vector<uint64_t> counts = {tets.size()};
  uint64_t live = tets.size();
  for (const auto& batch : result.batches) {
    for (const TetCollapse& c : batch) {
      for (uint32_t t : star[c.vt]) {
        if (!alive[t]) continue;
        auto& v = tets[t];
        if (std::find(v.begin(), v.end(), c.vs) != v.end()) {
          alive[t] = 0;
          --live;
          continue;
        }
        *std::find(v.begin(), v.end(), c.vt) = c.vs;
        star[c.vs].push_back(t);
      }
      counts.push_back(live);
    }
  }
  return counts;
}

}  // namespace

int main(int argc, char** argv) {
  std::string which = "ct", cost = "quadric";
  bool levels = false;
  uint64_t samples = 1000000;
  int repeat = 1;
  TetSimplifyOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--mesh") which = next();
    else if (a == "--cost") cost = next();
    else if (a == "--no-intersection") options.boundary_intersection_test = false;
    else if (a == "--cases-2-3") options.allow_boundary_cases_2_3 = true;
    else if (a == "--min-dihedral") options.min_dihedral_degrees = std::atof(next().c_str());
    else if (a == "--levels") levels = true;
    else if (a == "--samples") samples = std::strtoull(next().c_str(), nullptr, 10);
    else if (a == "--repeat") repeat = std::atoi(next().c_str());
    else if (a == "--boundary-weight") options.quadric_boundary_weight = std::atof(next().c_str());
    else if (a == "--ratio") options.batch_cost_ratio = std::atof(next().c_str());
    else if (a == "--quantile") options.batch_min_fraction = std::atof(next().c_str());
    else if (a == "--w-grad") options.weight_gradient = std::atof(next().c_str());
    else if (a == "--w-vol") options.weight_volume = std::atof(next().c_str());
    else if (a == "--w-equi") options.weight_equilateral = std::atof(next().c_str());
    else if (a == "--w-len") options.weight_edge_length = std::atof(next().c_str());
    else if (a == "--w-normal") options.weight_normal = std::atof(next().c_str());
    else {
      std::fprintf(stderr, "tet_simplify_bench: unknown option %s\n", a.c_str());
      std::fputs(kUsage, stderr);
      return 2;
    }
  }
  options.cost = cost == "paper" ? TetCost::kPaper : TetCost::kQuadric;
  QuantizedTetMesh mesh;
  std::string error;
  bool ok = false;
  if (which == "ct") ok = test::paperCtCrop(&mesh, &error);
  // tet_peer_bench --ct's crop: corner (112, 112, 33), slices 2 apart.
  else if (which == "ct-peer") ok = test::ctHeadCrop(32, 112, 112, 33, &mesh, &error, 2);
  else if (which == "lox") ok = test::loxPost(&mesh, &error);
  else if (which == "lox-io" || which == "bluntfin-io" || which == "combustion-io") {
    // The formats' PLOT3D generator (welded seams), quantised to 2^29 over
    // the longest side, the x momentum as the scalar.
    const std::string base = std::string(MRSV_SHARED_DATA) + "/tet/" +
                             (which == "lox-io" ? "lox_post_plot3d_38x76x38_f32be" :
                              which == "bluntfin-io" ? "bluntfin_plot3d_40x32x32_f32be" :
                                                       "combustion_chamber_plot3d_57x33x25_f32be");
    Plot3dData data;
    TetMesh tets;
    TetBuildReport report;
    ok = readPlot3d(base + (which == "lox-io" ? "_iblank.xyz" : ".xyz"), base + ".q", &data, &error) &&
         tetrahedralizePlot3d(data, &tets, &report, &error);
    if (ok) {
      std::array<double, 3> lo = tets.positions[0], hi = lo;
      for (const auto& p : tets.positions) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
      }
      const double scale = double((1 << 29) - 1) / std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
      for (const auto& p : tets.positions) {
        mesh.positions.push_back({int32_t(std::lround((p[0] - lo[0]) * scale)), int32_t(std::lround((p[1] - lo[1]) * scale)),
                                  int32_t(std::lround((p[2] - lo[2]) * scale))});
      }
      mesh.tets = tets.tets;
      mesh.fields.push_back(tets.fields.size() > 1 ? tets.fields[1].values : std::vector<double>(tets.positions.size(), 0.0));
    }
  }
  else if (which == "bunny") ok = test::readMeditTets(std::string(MRSV_SHARED_DATA) + "/tet/bunny_5433v_34055tet.mesh", &mesh, &error);
  else if (which == "hand") ok = test::readMeditTets(std::string(MRSV_SHARED_DATA) + "/tet/hand_7234v_29998tet.mesh", &mesh, &error);
  if (!ok) {
    std::fprintf(stderr, "%s: %s\n", which.c_str(), error.c_str());
    return 1;
  }
  std::printf("mesh %s: %zu vertices, %zu tets; cost %s, intersection test %s, min dihedral %.1f\n", which.c_str(),
              mesh.positions.size(), mesh.tets.size(), cost.c_str(), options.boundary_intersection_test ? "on" : "off",
              options.min_dihedral_degrees);
  TetSimplifyResult result;
  // Wall time and this process's CPU time (the machine is shared: CPU time
  // is the steadier of the two), best of --repeat runs each.
  double best = 1e300, best_cpu = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const Error e = simplifyTets(mesh, options, &result);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best_cpu = std::min(best_cpu, double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    if (!e.ok()) {
      std::fprintf(stderr, "simplifyTets: %s\n", e.describe().c_str());
      return 1;
    }
    best = std::min(best, s);
  }
  const TetSimplifyStats& st = result.stats;
  std::printf("build %.3f s wall, %.3f s CPU (best of %d), %llu collapses, %.0f collapses/s of CPU, %llu batches, "
              "%.1f collapses per batch\n",
              best, best_cpu, repeat, (unsigned long long)st.collapses, double(st.collapses) / best_cpu,
              (unsigned long long)st.batches, st.averageBatchSize());
  std::printf("final %llu tets, %llu vertices\n", (unsigned long long)st.final_tets,
              (unsigned long long)st.final_vertices);
  std::printf("evaded: table %llu, link %llu, inversion %llu, degenerate %llu, min dihedral %llu, self-intersection %llu\n",
              (unsigned long long)st.evaded_boundary_table, (unsigned long long)st.evaded_link,
              (unsigned long long)st.evaded_inversion, (unsigned long long)st.evaded_degenerate,
              (unsigned long long)st.evaded_min_dihedral, (unsigned long long)st.evaded_self_intersection);
  if (!levels) return 0;
  const bool has_field = !mesh.fields.empty();
  const DihedralStats full = dihedralStats(mesh);
  std::printf("%-8s %9s %9s %10s %9s %11s %12s\n", "level", "tets", "vertices", "psnr_dB", "outside", "worst_dih",
              "mean_min_dih");
  std::printf("%-8s %9zu %9zu %10s %9s %11.2f %12.2f\n", "100%", mesh.tets.size(), mesh.positions.size(), "-", "-",
              full.worst, full.mean_minimum);
  const std::vector<uint64_t> counts = tetCounts(mesh, result);
  for (double fraction : {0.5, 0.2, 0.1, 0.05, 0.02, 0.01}) {
    const uint64_t target = uint64_t(fraction * double(mesh.tets.size()));
    size_t k = 0;
    while (k < counts.size() && counts[k] > target) ++k;
    if (k == counts.size()) {
      std::printf("%-7.0f%% not reached (coarsest %llu tets)\n", 100 * fraction, (unsigned long long)counts.back());
      continue;
    }
    QuantizedTetMesh level;
    applyTetCollapses(mesh, result, k, &level);
    const DihedralStats d = dihedralStats(level);
    char name[16];
    std::snprintf(name, sizeof(name), "%.0f%%", 100 * fraction);
    if (has_field) {
      const test::PsnrResult p = test::scalarPsnr(mesh, level, samples, 1);
      std::printf("%-8s %9zu %9zu %10.2f %9llu %11.2f %12.2f\n", name, level.tets.size(), level.positions.size(),
                  p.psnr, (unsigned long long)p.outside, d.worst, d.mean_minimum);
    } else {
      std::printf("%-8s %9zu %9zu %10s %9s %11.2f %12.2f\n", name, level.tets.size(), level.positions.size(), "-",
                  "-", d.worst, d.mean_minimum);
    }
  }
  return 0;
}
