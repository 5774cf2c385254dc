// Closest-point distances with a CGAL AABB tree.
#include "metrics/surface_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "metrics/compensated_sum.h"

namespace mrsv {
namespace {

// Plain doubles: the inputs are doubles and the closest point of a triangle
// needs no exact predicate (a rounding error of the result is a rounding
// error of the distance, nothing worse).
using Kernel = CGAL::Simple_cartesian<double>;
using CgalPoint = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

CgalPoint toCgal(const Point3& p) { return CgalPoint(p[0], p[1], p[2]); }

// Samples per work unit: small enough to spread over the threads and to
// report progress, large enough that the hint chain (each query starts from
// the previous answer) is rarely broken.
constexpr size_t kChunk = 8192;

struct ChunkResult {
  double max = -1.0;
  Point3 max_at{};
  CompensatedSum area_sum, area_sum2, all_sum, all_sum2;
};

unsigned threadCount(unsigned requested, size_t chunks) {
  unsigned n = requested ? requested : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::min<size_t>({n, 64, std::max<size_t>(chunks, 1)}));
}

}  // namespace

struct SurfaceDistanceTree::Impl {
  std::vector<CgalTriangle> triangles;  // the tree's primitives point into this
  std::vector<uint32_t> source;         // per entry of `triangles`: its index in the mesh
  Tree tree;

  // Runs `work(chunk)` for chunks 0..count-1 on `threads` threads (the caller
  // is one of them); `done(chunk)` runs under a lock after each.
  template <typename Work, typename Done>
  void forChunks(size_t count, unsigned threads, Work work, Done done) const {
    std::atomic<size_t> next{0};
    std::mutex lock;
    auto loop = [&] {
      for (size_t c; (c = next.fetch_add(1)) < count;) {
        work(c);
        std::lock_guard<std::mutex> guard(lock);
        done(c);
      }
    };
    std::vector<std::thread> helpers;
    for (unsigned t = 1; t < threads; ++t) helpers.emplace_back(loop);
    loop();
    for (std::thread& h : helpers) h.join();
  }

  // Distances of points[begin, end), each query hinted with the previous
  // closest point (a point of the surface, as CGAL requires of a hint).
  template <typename Visit>
  void query(const std::vector<Point3>& points, size_t begin, size_t end, Visit visit) const {
    CgalPoint hint;
    for (size_t i = begin; i < end; ++i) {
      CgalPoint p = toCgal(points[i]);
      hint = i == begin ? tree.closest_point(p) : tree.closest_point(p, hint);
      visit(i, std::sqrt(CGAL::squared_distance(p, hint)));
    }
  }
};

SurfaceDistanceTree::SurfaceDistanceTree(const TriangleMesh& mesh) : impl_(new Impl) {
  for (const auto& t : mesh.triangles) {
    const Point3& a = mesh.positions[t[0]];
    const Point3& b = mesh.positions[t[1]];
    const Point3& c = mesh.positions[t[2]];
    if (!isDegenerateTriangle(a, b, c)) {
      impl_->triangles.emplace_back(toCgal(a), toCgal(b), toCgal(c));
      impl_->source.push_back(static_cast<uint32_t>(&t - mesh.triangles.data()));
    }
  }
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  // Built now, not lazily by the first query, so that concurrent queries
  // only read the tree.
  impl_->tree.accelerate_distance_queries();
}

SurfaceDistanceTree::~SurfaceDistanceTree() = default;
SurfaceDistanceTree::SurfaceDistanceTree(SurfaceDistanceTree&&) noexcept = default;
SurfaceDistanceTree& SurfaceDistanceTree::operator=(SurfaceDistanceTree&&) noexcept = default;

size_t SurfaceDistanceTree::triangleCount() const { return impl_->triangles.size(); }

double SurfaceDistanceTree::distance(const Point3& p) const {
  return std::sqrt(impl_->tree.squared_distance(toCgal(p)));
}

Point3 SurfaceDistanceTree::closestPoint(const Point3& p, uint32_t* triangle) const {
  const auto hit = impl_->tree.closest_point_and_primitive(toCgal(p));
  *triangle = impl_->source[static_cast<size_t>(hit.second - impl_->triangles.cbegin())];
  return {hit.first.x(), hit.first.y(), hit.first.z()};
}

std::vector<double> SurfaceDistanceTree::distances(const std::vector<Point3>& points,
                                                   unsigned threads) const {
  std::vector<double> out(points.size());
  const size_t chunks = (points.size() + kChunk - 1) / kChunk;
  impl_->forChunks(
      chunks, threadCount(threads, chunks),
      [&](size_t c) {
        impl_->query(points, c * kChunk, std::min(points.size(), (c + 1) * kChunk),
                     [&](size_t i, double d) { out[i] = d; });
      },
      [](size_t) {});
  return out;
}

OneSidedDistance SurfaceDistanceTree::measure(const SurfaceSamples& samples,
                                              const SurfaceDistanceOptions& options,
                                              double progress_begin, double progress_end) const {
  const std::vector<Point3>& points = samples.points;
  const size_t chunks = (points.size() + kChunk - 1) / kChunk;
  std::vector<ChunkResult> results(chunks);
  size_t finished = 0;
  impl_->forChunks(
      chunks, threadCount(options.threads, chunks),
      [&](size_t c) {
        ChunkResult& r = results[c];
        impl_->query(points, c * kChunk, std::min(points.size(), (c + 1) * kChunk),
                     [&](size_t i, double d) {
                       if (d > r.max) {
                         r.max = d;
                         r.max_at = points[i];
                       }
                       r.all_sum.add(d);
                       r.all_sum2.add(d * d);
                       if (samples.is_face_sample[i]) {
                         r.area_sum.add(d);
                         r.area_sum2.add(d * d);
                       }
                     });
      },
      [&](size_t) {
        ++finished;
        if (options.progress)
          options.progress(progress_begin + (progress_end - progress_begin) *
                                                static_cast<double>(finished) /
                                                static_cast<double>(chunks));
      });

  // Chunk results are combined in sample order, so the figures do not depend
  // on the number of threads or on which thread ran which chunk.
  OneSidedDistance out;
  CompensatedSum area_sum, area_sum2, all_sum, all_sum2;
  double max = -1.0;
  for (const ChunkResult& r : results) {
    if (r.max > max) {  // strict: the first maximum in sample order wins
      max = r.max;
      out.max_at = r.max_at;
    }
    area_sum.add(r.area_sum.value());
    area_sum2.add(r.area_sum2.value());
    all_sum.add(r.all_sum.value());
    all_sum2.add(r.all_sum2.value());
  }
  out.max = std::max(max, 0.0);
  out.samples = points.size();
  out.area_samples = samples.face_samples;
  const bool by_area = samples.face_samples > 0;
  const double count = static_cast<double>(by_area ? samples.face_samples : points.size());
  if (count > 0) {
    out.mean = (by_area ? area_sum : all_sum).value() / count;
    out.rms = std::sqrt((by_area ? area_sum2 : all_sum2).value() / count);
  }
  return out;
}

bool measureSurfaceDistance(const TriangleMesh& a, const TriangleMesh& b,
                            const SurfaceDistanceOptions& options, SurfaceDistanceReport* report,
                            std::string* error) {
  std::string why;
  if (!checkSurfaceMesh(a, &why)) {
    *error = "A: " + why;
    return false;
  }
  if (!checkSurfaceMesh(b, &why)) {
    *error = "B: " + why;
    return false;
  }
  *report = SurfaceDistanceReport{};
  report->bbox_diagonal = surfaceBoxDiagonal(a);
  // One direction at a time, so that only one tree and one sample set are
  // in memory at once.
  const TriangleMesh* from[2] = {&a, &b};
  const TriangleMesh* to[2] = {&b, &a};
  OneSidedDistance* result[2] = {&report->a_to_b, &report->b_to_a};
  for (int d = 0; d < 2; ++d) {
    SurfaceSamples samples;
    sampleSurface(*from[d], options.sampling, &samples);
    SurfaceDistanceTree tree(*to[d]);
    *result[d] = tree.measure(samples, options, 0.5 * d, 0.5 * (d + 1));
  }
  report->hausdorff = std::max(report->a_to_b.max, report->b_to_a.max);
  report->mean = std::max(report->a_to_b.mean, report->b_to_a.mean);
  report->rms = std::max(report->a_to_b.rms, report->b_to_a.rms);
  return true;
}

}  // namespace mrsv
