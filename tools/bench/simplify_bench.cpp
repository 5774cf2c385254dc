// Speed and quality of the edge-collapse simplifier (spec 6.9), with CGAL's
// Lindstrom-Turk edge_collapse as the peer measured in the same run.
//
//   simplify_bench [--sweep] [--no-cgal] [--no-quality] [--paper] [--free] MESH...
//
// For each mesh (OBJ, or PLY ascii / binary little or big endian) and each of
// 10 % and 1 % of its triangles it prints the time, collapses per second, the
// number of batches and two Metro-like surface distances between input and
// result, both relative to the input's bounding-box diagonal: the Hausdorff
// distance and the RMS distance, each the larger of the two directions, over
// area-proportional random samples plus all vertices. --sweep also runs the
// batch rule over a grid of batch_cost_ratio values.
//
// Meshes are read and repaired as the PM encoder's input is (mrsv_io).
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "mesh_simplifiers.h"

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Vec3 = std::array<double, 3>;
using Tri = std::array<uint32_t, 3>;

// ------------------------------------------------------------ distance --

struct Surface {
  std::vector<Triangle> triangles;
  std::vector<Point> vertices;
};

Surface surfaceOf(const std::vector<Vec3>& positions, const std::vector<Tri>& tris) {
  Surface s;
  std::vector<bool> used(positions.size(), false);
  for (const Tri& t : tris) {
    const Point a(positions[t[0]][0], positions[t[0]][1], positions[t[0]][2]);
    const Point b(positions[t[1]][0], positions[t[1]][1], positions[t[1]][2]);
    const Point c(positions[t[2]][0], positions[t[2]][1], positions[t[2]][2]);
    s.triangles.emplace_back(a, b, c);
    for (uint32_t v : t) used[v] = true;
  }
  for (size_t v = 0; v < positions.size(); ++v) {
    if (used[v]) s.vertices.emplace_back(positions[v][0], positions[v][1], positions[v][2]);
  }
  return s;
}

struct OneWay {
  double max = 0.0, rms = 0.0;
};

// Distances from samples of `from` (all vertices plus about `samples` points
// spread by area) to the surface `to`.
OneWay oneWay(const Surface& from, const Surface& to, size_t samples) {
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Tree tree(to.triangles.begin(), to.triangles.end());
  tree.accelerate_distance_queries();
  double total_area = 0.0;
  for (const Triangle& t : from.triangles) total_area += std::sqrt(t.squared_area());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  OneWay out;
  double sum = 0.0;
  size_t count = 0;
  auto measure = [&](const Point& p) {
    const double d2 = tree.squared_distance(p);
    out.max = std::max(out.max, d2);
    sum += d2;
    ++count;
  };
  for (const Point& p : from.vertices) measure(p);
  double carry = 0.0;
  for (const Triangle& t : from.triangles) {
    carry += std::sqrt(t.squared_area()) / total_area * static_cast<double>(samples);
    while (carry >= 1.0) {
      carry -= 1.0;
      double r1 = u(rng), r2 = u(rng);
      if (r1 + r2 > 1.0) {
        r1 = 1.0 - r1;
        r2 = 1.0 - r2;
      }
      const Point& a = t[0];
      measure(a + r1 * (t[1] - a) + r2 * (t[2] - a));
    }
  }
  out.max = std::sqrt(out.max);
  out.rms = std::sqrt(sum / static_cast<double>(count));
  return out;
}

struct Quality {
  double hausdorff = 0.0, rms = 0.0;
};

Quality compare(const Surface& a, const Surface& b, double diagonal) {
  const size_t samples = std::max<size_t>(200000, 4 * a.triangles.size());
  const OneWay ab = oneWay(a, b, samples), ba = oneWay(b, a, samples);
  return {std::max(ab.max, ba.max) / diagonal, std::max(ab.rms, ba.rms) / diagonal};
}

// ---------------------------------------------------------------- runs --

struct Config {
  std::string name;
  mrsv::SimplifyOptions options;
};

void runOurs(const std::string& mesh_name, const mrsv::TriangleMesh& mesh, const Surface& input,
             double diagonal, const Config& config, uint64_t target, bool measure_quality) {
  mrsv::SimplifyOptions options = config.options;
  options.target_triangles = target;
  mrsv::SimplifyResult result;
  std::string error;
  // Best of three runs for the time: the machine is shared.
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    if (!mrsv::simplifyMesh(mesh, options, &result, &error)) {
      std::printf("%s: %s\n", mesh_name.c_str(), error.c_str());
      return;
    }
    best = std::min(best, mrsv::bench::secondsSince(start));
  }
  size_t collapses = 0;
  for (const auto& b : result.batches) collapses += b.size();
  Quality q;
  if (measure_quality) {
    const mrsv::TriangleMesh simplified = mrsv::bench::meshAfterCollapses(mesh, result);
    q = compare(input, surfaceOf(simplified.positions, simplified.triangles), diagonal);
  }
  std::printf("%-22s %-26s %8llu %8llu %9.1f %9.2f %6zu %11.3e %11.3e\n", mesh_name.c_str(),
              config.name.c_str(), static_cast<unsigned long long>(target),
              static_cast<unsigned long long>(result.final_triangles), best * 1e3,
              static_cast<double>(collapses) / best / 1e6, result.batches.size(), q.hausdorff, q.rms);
  std::fflush(stdout);
}

void runCgal(const std::string& mesh_name, const mrsv::TriangleMesh& mesh, const Surface& input,
             double diagonal, uint64_t target) {
  mrsv::TriangleMesh simplified;
  const mrsv::bench::LindstromTurkRun run = mrsv::bench::simplifyLindstromTurk(mesh, target, &simplified);
  const Quality q = compare(input, surfaceOf(simplified.positions, simplified.triangles), diagonal);
  std::printf("%-22s %-26s %8llu %8zu %9.1f %9.2f %6s %11.3e %11.3e\n", mesh_name.c_str(),
              "cgal-lindstrom-turk", static_cast<unsigned long long>(target), simplified.triangles.size(),
              run.collapse_seconds * 1e3, run.collapses / run.collapse_seconds / 1e6, "-", q.hausdorff, q.rms);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool sweep = false, cgal = true, paper = false, free_placement = false, quality = true;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sweep") {
      sweep = true;
    } else if (a == "--no-cgal") {
      cgal = false;
    } else if (a == "--no-quality") {
      quality = false;
      cgal = false;
    } else if (a == "--paper") {
      paper = true;
    } else if (a == "--free") {
      free_placement = true;
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: simplify_bench [--sweep] [--no-cgal] [--no-quality] [--paper] [--free] MESH...\n");
    return 2;
  }
  std::printf("%-22s %-26s %8s %8s %9s %9s %6s %11s %11s\n", "mesh", "method", "target", "result",
              "ms", "Mcoll/s", "batch", "hausdorff", "rms");
  for (const std::string& path : files) {
    mrsv::TriangleMesh mesh;
    std::string error;
    mrsv::MeshRepairReport report;
    if (!mrsv::bench::readRepairedMesh(path, &mesh, &report, &error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    std::string name = path.substr(path.find_last_of('/') + 1);
    name = name.substr(0, name.find('_'));
    Vec3 lo = mesh.positions[mesh.triangles[0][0]], hi = lo;
    for (const Tri& t : mesh.triangles) {
      for (uint32_t v : t) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], mesh.positions[v][k]);
          hi[k] = std::max(hi[k], mesh.positions[v][k]);
        }
      }
    }
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const Surface input = surfaceOf(mesh.positions, mesh.triangles);

    std::vector<Config> configs;
    configs.push_back({"quadric-endpoint", {}});
    if (free_placement) {
      Config c{"quadric-free", {}};
      c.options.placement = mrsv::Placement::kFree;
      configs.push_back(c);
    }
    if (paper) {
      Config c{"paper-endpoint", {}};
      c.options.cost = mrsv::CollapseCost::kPaper;
      configs.push_back(c);
    }
    if (sweep) {
      for (double ratio : {1.5, 2.0, 3.0, 4.0, 8.0, 16.0, 1e9}) {
        for (double fraction : {1.0}) {
          Config c{"", {}};
          c.options.batch_cost_ratio = ratio;
          c.options.batch_max_fraction = fraction;
          char buf[64];
          std::snprintf(buf, sizeof buf, "ratio=%g", ratio);
          c.name = buf;
          configs.push_back(c);
        }
      }
    }
    for (uint64_t percent : {10, 1}) {
      const uint64_t target = mesh.triangles.size() * percent / 100;
      for (const Config& c : configs) runOurs(name, mesh, input, diagonal, c, target, quality);
      if (cgal) runCgal(name, mesh, input, diagonal, target);
    }
  }
  return 0;
}
