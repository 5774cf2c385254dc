// tet_peer_bench: CGAL's Tetrahedral_remeshing coarsening a tet mesh to 50,
// 20, 10 and 5 % of its tets, measured as the PT levels will be (issue 21):
// field PSNR against the original at 10^6 random positions, boundary
// Hausdorff distance, volume change, dihedral angles, validity.
//
//   tet_peer_bench --ct                 the 32^3 crop of the Stanford CT head (178,746 tets)
//   tet_peer_bench --mesh FILE.mesh     a MEDIT tet mesh, with a synthetic field
//   tet_peer_bench --plot3d PREFIX      PREFIX.xyz + PREFIX.q (5 tets per hex, density)
//   options: --fractions 50,20,10,5  --samples N  --data DIR (../shared/data)
//            --iterations I (CGAL's, default 3)  --crop X,Y,Z (the crop's corner)
#include <zstd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mrsv/tet_metrics.h"
#include "tet_cgal_peer.h"
#include "tet_metric_meshes.h"

namespace {

using namespace mrsv;

constexpr int kCrop = 32;  // the paper's crop: 32^3 samples

bool readZst(const std::string& path, std::vector<uint8_t>* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::vector<char> packed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const unsigned long long size = ZSTD_getFrameContentSize(packed.data(), packed.size());
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN) return false;
  out->resize(size);
  const size_t got = ZSTD_decompress(out->data(), out->size(), packed.data(), packed.size());
  return !ZSTD_isError(got) && got == size;
}

// The 32^3 crop of the CT head with its corner at `corner`, voxel spacing
// (1, 1, 2) (the data's aspect), the CT values as the field "density".
bool ctCrop(const std::string& data, const int (&corner)[3], TetMesh* mesh) {
  const int nx = 256, ny = 256, nz = 99;
  std::vector<uint8_t> v;
  if (!readZst(data + "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst", &v) ||
      v.size() != static_cast<size_t>(nx) * ny * nz)
    return false;
  for (int d = 0; d < 3; ++d)
    if (corner[d] < 0 || corner[d] + kCrop > (d == 2 ? nz : nx)) return false;
  *mesh = test::gridTetMesh(
      kCrop, kCrop, kCrop, {0, 0, 0}, {1, 1, 2},
      [&](int i, int j, int k) {
        return static_cast<double>(
            v[(static_cast<size_t>(corner[2] + k) * ny + corner[1] + j) * nx + corner[0] + i]);
      },
      "density");
  return true;
}

// A smooth field for meshes that come without one: with x, y, z scaled to
// [0, 1] over the bounding box, sin(4x + 1) cos(3y) + z^2 (a few swings
// across the shape, not linear, so that interpolation has something to lose).
void syntheticField(TetMesh* m) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& p : m->positions)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  ScalarField f{"synthetic", {}};
  for (const auto& p : m->positions) {
    double u[3];
    for (int d = 0; d < 3; ++d) u[d] = hi[d] > lo[d] ? (p[d] - lo[d]) / (hi[d] - lo[d]) : 0.0;
    f.values.push_back(std::sin(4.0 * u[0] + 1.0) * std::cos(3.0 * u[1]) + u[2] * u[2]);
  }
  m->fields = {f};
}

void printQuality(const char* label, const TetQuality& q) {
  std::printf(
      "%s: %llu tets, %llu vertices, volume %.6g, %llu boundary faces; inverted %llu, "
      "degenerate %llu, manifold %s, boundary self-intersections %lld; min dihedral "
      "worst %.2f mean %.2f deg\n",
      label, static_cast<unsigned long long>(q.tets), static_cast<unsigned long long>(q.vertices),
      q.volume, static_cast<unsigned long long>(q.boundary_faces),
      static_cast<unsigned long long>(q.inverted), static_cast<unsigned long long>(q.degenerate),
      q.manifold.manifold() ? "yes" : "NO", static_cast<long long>(q.boundary_self_intersections),
      q.min_dihedral_worst, q.min_dihedral_mean);
}

int usage() {
  std::fprintf(
      stderr,
      "usage: tet_peer_bench (--ct | --mesh FILE.mesh | --plot3d PREFIX) [--fractions 50,20,10,5] "
      "[--samples N] [--data DIR] [--iterations I] [--crop X,Y,Z] [--json]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = MRSV_SHARED_DATA, mesh_file, plot3d;
  bool ct = false, json = false;
  std::vector<double> fractions = {50, 20, 10, 5};
  uint64_t samples = kDefaultTetSampleCount;
  int corner[3] = {112, 112, 33};  // the middle of the head
  bench::CgalPeerOptions peer;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool more = i + 1 < argc;
    if (a == "--ct") {
      ct = true;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--mesh" && more) {
      mesh_file = argv[++i];
    } else if (a == "--plot3d" && more) {
      plot3d = argv[++i];
    } else if (a == "--data" && more) {
      data = argv[++i];
    } else if (a == "--samples" && more) {
      samples = std::stoull(argv[++i]);
    } else if (a == "--iterations" && more) {
      peer.iterations = static_cast<unsigned>(std::stoul(argv[++i]));
    } else if (a == "--crop" && more) {
      if (std::sscanf(argv[++i], "%d,%d,%d", &corner[0], &corner[1], &corner[2]) != 3)
        return usage();
    } else if (a == "--fractions" && more) {
      fractions.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) fractions.push_back(std::stod(item));
    } else {
      return usage();
    }
  }
  if (ct + !mesh_file.empty() + !plot3d.empty() != 1) return usage();

  TetMesh original;
  std::string error, name;
  if (ct) {
    if (!ctCrop(data, corner, &original)) {
      std::fprintf(stderr, "tet_peer_bench: cannot read the CT head under %s\n", data.c_str());
      return 1;
    }
    name = "CT head crop 32^3 at (" + std::to_string(corner[0]) + ", " + std::to_string(corner[1]) +
           ", " + std::to_string(corner[2]) + ")";
  } else if (!plot3d.empty()) {
    if (!test::readPlot3dTetMesh(plot3d + ".xyz", plot3d + ".q", &original, &error)) {
      std::fprintf(stderr, "tet_peer_bench: %s\n", error.c_str());
      return 1;
    }
    name = plot3d.substr(plot3d.find_last_of('/') + 1);
  } else {
    if (!test::readMeditTetMesh(mesh_file, &original, &error)) {
      std::fprintf(stderr, "tet_peer_bench: %s\n", error.c_str());
      return 1;
    }
    syntheticField(&original);
    name = mesh_file.substr(mesh_file.find_last_of('/') + 1);
  }
  if (!checkTetMesh(original, &error)) {
    std::fprintf(stderr, "tet_peer_bench: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s, field '%s', %llu samples, CGAL %u iterations per run, feature angle %.0f deg\n",
              name.c_str(), original.fields[0].name.c_str(),
              static_cast<unsigned long long>(samples), peer.iterations, peer.feature_angle);
  printQuality("original", measureTetQuality(original));

  std::printf("\n%6s %8s %8s %5s %8s %8s %8s %9s %9s %7s %10s %7s %7s %5s %4s %4s %6s %6s %6s\n",
              "frac", "target", "tets", "runs", "cgal_s", "all_s", "psnr_db", "max_err",
              "hausdorff", "h_rel", "vol_rel", "dih_min", "dih_avg", "inv", "man", "self", "out%",
              "psnr_s", "cmp_s");
  for (double fraction : fractions) {
    const auto target = static_cast<size_t>(std::llround(original.tets.size() * fraction / 100.0));
    bench::CgalPeerResult peer_result;
    if (!bench::cgalCoarsen(original, target, peer, &peer_result, &error)) {
      std::fprintf(stderr, "tet_peer_bench: %s\n", error.c_str());
      return 1;
    }
    TetCompareOptions o;
    o.field.sample_count = samples;
    o.threads = 1;
    auto start = std::chrono::steady_clock::now();
    const TetCompareReport r = compareTetMeshes(original, peer_result.mesh, o);
    const double compare_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The field error alone (the figure that must stay fast: 10^6 samples).
    start = std::chrono::steady_clock::now();
    TetFieldError field_only;
    measureTetFieldError(original, peer_result.mesh, o.field, &field_only, &error);
    const double field_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!r.error.empty()) {
      std::fprintf(stderr, "tet_peer_bench: %s\n", r.error.c_str());
      return 1;
    }
    const TetQuality& q = r.quality_b;
    std::printf(
        "%5.0f%% %8zu %8llu %5d %8.2f %8.2f %8.2f %9.4g %9.4g %7.4f %10.2e %7.2f %7.2f %5llu "
        "%4s %4lld %6.2f %6.2f %6.2f%s\n",
        fraction, target, static_cast<unsigned long long>(q.tets), peer_result.runs,
        peer_result.seconds, peer_result.seconds_all, r.field.psnr_db, r.field.max_abs,
        r.boundary.hausdorff, r.boundary.hausdorff / r.boundary.bbox_diagonal,
        r.volume_difference_relative, q.min_dihedral_worst, q.min_dihedral_mean,
        static_cast<unsigned long long>(q.inverted), q.manifold.manifold() ? "yes" : "NO",
        static_cast<long long>(q.boundary_self_intersections),
        100.0 * static_cast<double>(r.field.outside_b) / static_cast<double>(r.field.samples),
        field_s, compare_s, peer_result.within_tolerance ? "" : "  (count off by more than 5 %)");
    if (json) std::printf("%s\n", tetCompareJson(r).c_str());
    std::fflush(stdout);
  }
  return 0;
}
