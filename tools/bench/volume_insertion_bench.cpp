// volume_insertion_bench: issue 22's measured goals for volumes (spec 10).
// On crops of the Stanford CT head:
// - tets against PSNR: the greedy mesh at several maximum errors, one shot
//   and band by band, and with the paper's trilinear distance; the field
//   sampled at N random positions (fixed seed) in the mesh (point location,
//   linear interpolation) against the full grid's 6-tet interpolant (the
//   paper's "original mesh"), PSNR with peak 255;
// - insertion speed: the band-by-band vertex set, in its insertion order,
//   inserted by our Delaunay3 and by CGAL's Delaunay_triangulation_3 (each
//   point walked to from the last one's cell) in the same run, best of 3;
//   CGAL's spatially sorted range insert and the whole greedy inserter
//   (error scans included) beside them. Ratios are within one run.
//
// Usage: volume_insertion_bench [samples] (default 1,000,000).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "mrsv/volume_insertion.h"
#include "reconstruct/delaunay3.h"
#include "shared_data.h"

namespace {

using mrsv::GridMesh;
using mrsv::InsertionLimits;
using mrsv::SampleField;
using mrsv::VolumeDistance;
using mrsv::VolumeInserter;
using mrsv::reconstruct::Delaunay3;
using mrsv::reconstruct::GridPoint;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalDelaunay = CGAL::Delaunay_triangulation_3<Kernel>;

double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SampleField crop(const mrsv::test::SharedGrid& grid, const uint32_t origin[3], const uint32_t size[3]) {
  SampleField f;
  for (int a = 0; a < 3; ++a) f.size[a] = size[a];
  const uint64_t gx = grid.header.size_x, gy = grid.header.size_y;
  for (uint32_t z = 0; z < size[2]; ++z)
    for (uint32_t y = 0; y < size[1]; ++y)
      for (uint32_t x = 0; x < size[0]; ++x)
        f.values.push_back(grid.samples[((origin[2] + z) * gy + origin[1] + y) * gx + origin[0] + x]);
  return f;
}

// The full grid's piecewise-linear interpolant over the 6 tets of each cube
// (Freudenthal: sort the fractional parts, walk the cube's corners).
double gridValue(const SampleField& f, const double p[3]) {
  int i[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    i[a] = std::min(static_cast<int>(p[a]), static_cast<int>(f.size[a]) - 2);
    t[a] = p[a] - i[a];
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return t[a] > t[b]; });
  int c[3] = {i[0], i[1], i[2]};
  double v = (1 - t[order[0]]) * f.at(c[0], c[1], c[2]);
  for (int k = 0; k < 3; ++k) {
    c[order[k]] += 1;
    const double w = t[order[k]] - (k < 2 ? t[order[k + 1]] : 0);
    v += w * f.at(c[0], c[1], c[2]);
  }
  return v;
}

double orientD(const double* a, const double* b, const double* c, const double* d) {
  const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
  const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
  const double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
  return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
}

// PSNR of the mesh against the grid at n random positions (seed 1): each
// position located by a walk in the mesh's tetrahedralization (rebuilt from
// its points: the same tets), from the last one's tet.
double psnr(const GridMesh& mesh, const SampleField& f, uint64_t n) {
  Delaunay3 dt;
  std::string error;
  dt.init(f.size[0], f.size[1], f.size[2], &error);
  for (size_t k = 8; k < mesh.points.size(); ++k)
    dt.insert(GridPoint{int32_t(mesh.points[k][0]), int32_t(mesh.points[k][1]), int32_t(mesh.points[k][2])});
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  uint32_t cell = dt.cellOf(1);
  double sq = 0;
  for (uint64_t s = 0; s < n; ++s) {
    double p[3];
    for (int a = 0; a < 3; ++a) p[a] = u(rng) * (f.size[a] - 1);
    double lambda[4];
    for (int steps = 0;; ++steps) {
      const Delaunay3::Cell& t = dt.cell(cell);
      double q[4][3];
      for (int k = 0; k < 4; ++k)
        for (int a = 0; a < 3; ++a) q[k][a] = dt.point(t.v[k])[a];
      const double D = orientD(q[0], q[1], q[2], q[3]);
      int worst = -1;
      double worst_l = -1e-12;
      for (int k = 0; k < 4; ++k) {
        double r[4][3];
        for (int j = 0; j < 4; ++j)
          for (int a = 0; a < 3; ++a) r[j][a] = j == k ? p[a] : q[j][a];
        lambda[k] = orientD(r[0], r[1], r[2], r[3]) / D;
        if (lambda[k] < worst_l && dt.isFinite(t.n[k])) worst_l = lambda[k], worst = k;
      }
      if (worst < 0 || steps > 100000) break;
      cell = t.n[worst];
    }
    double m = 0;
    for (int k = 0; k < 4; ++k) m += lambda[k] * mesh.values[dt.cell(cell).v[k] - 1];
    const double d = m - gridValue(f, p);
    sq += d * d;
  }
  const double mse = sq / double(n);
  return mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : INFINITY;
}

struct Run {
  uint64_t tets = 0, vertices = 0;
  double secs = 0;
  GridMesh mesh;
};

// Stages from the coarsest lattice (step 16) down to every sample, or one shot.
Run insertion(const SampleField& f, const char* error, bool staged, VolumeDistance distance) {
  Run r;
  VolumeInserter ins(f.size[0], f.size[1], f.size[2]);
  ins.setDistance(distance);
  InsertionLimits limits;
  mrsv::parseErrorBound(error, &limits.max_error);
  std::string why;
  const double t0 = seconds();
  for (int shift = staged ? 4 : 0; shift >= 0; --shift)
    if (!ins.refine(f, unsigned(shift), limits, &why)) std::fprintf(stderr, "refine: %s\n", why.c_str()), std::exit(1);
  r.secs = seconds() - t0;
  r.tets = ins.cellCount();
  r.vertices = ins.vertexCount();
  ins.mesh(&r.mesh);
  return r;
}

template <typename F>
double best3(F&& f) {
  double best = 1e30;
  for (int k = 0; k < 3; ++k) {
    const double t0 = seconds();
    f();
    best = std::min(best, seconds() - t0);
  }
  return best;
}

void speed(const SampleField& f, const GridMesh& mesh, double greedy_secs) {
  std::vector<GridPoint> pts;
  for (const auto& p : mesh.points) pts.push_back({int32_t(p[0]), int32_t(p[1]), int32_t(p[2])});
  uint64_t ours_tets = 0, cgal_tets = 0;
  const double ours = best3([&] {
    Delaunay3 dt;
    std::string error;
    dt.init(f.size[0], f.size[1], f.size[2], &error);
    for (size_t k = 8; k < pts.size(); ++k) dt.insert(pts[k]);
    ours_tets = dt.finiteCellCount();
  });
  std::vector<Kernel::Point_3> cp;
  for (const GridPoint& p : pts) cp.emplace_back(p[0], p[1], p[2]);
  const double cgal = best3([&] {
    CgalDelaunay dt;
    CgalDelaunay::Cell_handle hint;
    for (const auto& p : cp) hint = dt.insert(p, hint)->cell();
    cgal_tets = dt.number_of_finite_cells();
  });
  const double cgal_sorted = best3([&] {
    CgalDelaunay dt(cp.begin(), cp.end());
    cgal_tets = dt.number_of_finite_cells();
  });
  const double n = double(pts.size());
  std::printf("  speed, %zu points in the band-by-band insertion order (%llu tets, CGAL %llu):\n", pts.size(),
              (unsigned long long)ours_tets, (unsigned long long)cgal_tets);
  std::printf("    Delaunay3 insert, walk from the last   %9.0f points/s\n", n / ours);
  std::printf("    CGAL insert, hint the last one's cell  %9.0f points/s   ours/CGAL %.2f\n", n / cgal, cgal / ours);
  std::printf("    CGAL range insert (spatial sort)       %9.0f points/s   ours/CGAL %.2f\n", n / cgal_sorted,
              cgal_sorted / ours);
  std::printf("    VolumeInserter, greedy with scans      %9.0f points/s   /CGAL %.2f, /CGAL sorted %.2f\n",
              n / greedy_secs, cgal / greedy_secs, cgal_sorted / greedy_secs);
}

void bench(const char* name, const SampleField& f, const std::vector<const char*>& errors, uint64_t samples) {
  std::printf("\n%s: %ux%ux%u (%zu samples), PSNR at %llu random positions\n", name, f.size[0], f.size[1],
              f.size[2], f.values.size(), (unsigned long long)samples);
  std::printf("  %6s | %9s %8s %7s %8s | %9s %7s %8s | %9s %7s\n", "error", "one-shot", "PSNR", "s", "", "staged",
              "PSNR", "s", "trilinear", "PSNR");
  Run finest;
  for (const char* e : errors) {
    const Run once = insertion(f, e, false, VolumeDistance::kMesh);
    const Run staged = insertion(f, e, true, VolumeDistance::kMesh);
    const Run tri = insertion(f, e, true, VolumeDistance::kTrilinear);
    std::printf("  %6s | %9llu %8.2f %7.3f %8s | %9llu %7.2f %8.3f | %9llu %7.2f\n", e,
                (unsigned long long)once.tets, psnr(once.mesh, f, samples), once.secs, "",
                (unsigned long long)staged.tets, psnr(staged.mesh, f, samples), staged.secs,
                (unsigned long long)tri.tets, psnr(tri.mesh, f, samples));
    std::fflush(stdout);
    finest = staged;
  }
  speed(f, finest.mesh, finest.secs);
}

}  // namespace

int main(int argc, char** argv) {
  // volume_insertion_bench [SAMPLES] [--speed]: PSNR at SAMPLES positions (10^6); --speed
  // measures only the insertion speed, on the 128 x 128 x 99 crop's staged mesh at E = 5.
  uint64_t samples = 1000000;
  bool speed_only = false;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--speed") == 0) speed_only = true;
    else samples = std::strtoull(argv[a], nullptr, 10);
  }
  mrsv::test::SharedGrid grid;
  if (!mrsv::test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                      "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst",
                                  &grid))
    return 1;
  const uint32_t o32[3] = {112, 112, 40}, s32[3] = {32, 32, 32};
  if (speed_only) {
    const uint32_t o128[3] = {64, 64, 0}, s128[3] = {128, 128, 99};
    const SampleField f = crop(grid, o128, s128);
    const Run staged = insertion(f, "5", true, VolumeDistance::kMesh);
    std::printf("CT head crop at (64,64,0), 128x128x99, staged insertion at E = 5: %.3f s\n", staged.secs);
    speed(f, staged.mesh, staged.secs);
    return 0;
  }
  bench("CT head crop at (112,112,40)", crop(grid, o32, s32), {"40", "20", "10", "5", "2", "1"}, samples);
  // The head has 99 slices: the "128^3" crop is 128 x 128 x 99.
  const uint32_t o128[3] = {64, 64, 0}, s128[3] = {128, 128, 99};
  bench("CT head crop at (64,64,0)", crop(grid, o128, s128), {"40", "20", "10", "5"}, samples);
  return 0;
}
