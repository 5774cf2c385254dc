// Distances between two triangulated surfaces, measured the way Metro does
// (Cignoni, Rocchini, Scopigno 1998; used in section 7.1 of the Staadt & Gross
// paper): sample one surface densely, find for every sample the closest point
// on the other surface, and take the maximum (one-sided Hausdorff distance),
// the mean and the root mean square. Used by the tools and the tests, never
// by the decoder.
//
// The surface of a mesh is the union of its triangles with nonzero area (see
// isDegenerateTriangle); zero-area triangles and the vertices only they use are
// ignored on both the sampled side and the measured side, so that the two
// agree on what the surface is.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv {

using Point3 = std::array<double, 3>;

// About 10^6 samples on the Stanford bunny (69k triangles), as in the
// paper's Metro measurements; the same count for every mesh, so that a
// coarse level of detail is sampled as densely as the original.
constexpr uint64_t kDefaultSampleCount = 1000000;

// A triangle is degenerate when twice its area is at most 1e-12 of its
// longest edge squared (its height is below 1e-12 of that edge). Exact zero
// is not enough: the closest-point computation projects onto the triangle's
// plane, and the normal of a needle made of rounding noise points anywhere.
// Such a triangle lies within 1e-12 of its longest edge, which neighbouring
// triangles share, so leaving it out changes no distance that can be measured.
bool isDegenerateTriangle(const Point3& a, const Point3& b, const Point3& c);

// Checks what the measurement needs: corner indices in range, finite
// coordinates on every vertex a triangle uses, and at least one triangle that
// is not degenerate. On failure returns false with one line in `error`.
bool checkSurfaceMesh(const TriangleMesh& mesh, std::string* error);

struct SurfaceSamplingOptions {
  // Requested number of samples. Every vertex of the surface is a sample; the
  // rest, N - V, goes to points along the edges (a fixed spacing h) and to
  // area-proportional points inside the triangles (density 1/h^2), with h
  // chosen so that the total is exactly N. When the vertices would take more
  // than half of N, edges and faces still get N/2 and the total is V + N/2.
  uint64_t sample_count = kDefaultSampleCount;
  // Seed of the jitter inside each stratum; the same seed, mesh and count
  // give the same samples in the same order.
  uint64_t seed = 1;
};

struct SurfaceSamples {
  // Ordered triangle by triangle (its new vertices, the edges it is the first
  // to use, its interior), so neighbouring samples are close in space.
  std::vector<Point3> points;
  // Whether each point is an area-proportional face sample.
  std::vector<bool> is_face_sample;
  uint64_t vertex_samples = 0;
  uint64_t edge_samples = 0;
  uint64_t face_samples = 0;
  double area = 0.0;  // total area of the surface
};

// Samples the surface of `mesh` (which must pass checkSurfaceMesh):
//   vertices  every vertex used by a non-degenerate triangle, once;
//   edges     every edge once, k points at t = (j + u_j) / k, j < k, u_j in [0, 1);
//   faces     Metro's similar-triangle subdivision: the triangle is cut into
//             m^2 similar sub-triangles, m = ceil(sqrt(k)), k of them spread
//             evenly over the m^2 are chosen, and each gets one uniformly
//             distributed point (stratified sampling).
// Edge and face counts k are the expected counts (length * (1/h), area *
// (1/h^2)) rounded by error diffusion, so every triangle gets its share within
// one sample and the total is exact.
void sampleSurface(const TriangleMesh& mesh, const SurfaceSamplingOptions& options,
                   SurfaceSamples* samples);

// Distances from the samples of one surface to another surface.
struct OneSidedDistance {
  double max = 0.0;   // one-sided Hausdorff distance (over all samples)
  double mean = 0.0;  // estimate of (1/area) * integral of the distance
  double rms = 0.0;   // estimate of sqrt((1/area) * integral of distance^2)
  uint64_t samples = 0;       // all samples (vertices, edges, faces): the max
  uint64_t area_samples = 0;  // the area-proportional face samples: mean and rms
  Point3 max_at{};            // a sample where the max is reached
};

struct SurfaceDistanceOptions {
  SurfaceSamplingOptions sampling;
  // Worker threads for the distance queries; 0 uses every hardware thread.
  // The results do not depend on it (partial sums are added in sample order).
  unsigned threads = 0;
  // Called now and then with the fraction done, 0..1, from one thread at a time.
  std::function<void(double)> progress;
};

// The closest-point structure of one surface (a CGAL AABB tree of its
// non-degenerate triangles). Build it once to measure many sample sets against
// the same surface, e.g. every level of detail against the original.
class SurfaceDistanceTree {
 public:
  // `mesh` must pass checkSurfaceMesh; the tree keeps a copy of its triangles.
  explicit SurfaceDistanceTree(const TriangleMesh& mesh);
  ~SurfaceDistanceTree();
  SurfaceDistanceTree(SurfaceDistanceTree&&) noexcept;
  SurfaceDistanceTree& operator=(SurfaceDistanceTree&&) noexcept;

  size_t triangleCount() const;
  // Euclidean distance from `p` to the closest point of the surface.
  double distance(const Point3& p) const;
  // The closest point of the surface to `p`, and in `triangle` the index (in
  // the mesh the tree was built from) of a triangle it lies on.
  Point3 closestPoint(const Point3& p, uint32_t* triangle) const;
  // Distances from every sample. Mean and RMS use the face samples (they are
  // area-proportional, so their average estimates the surface integral); when
  // there are none, all samples.
  OneSidedDistance measure(const SurfaceSamples& samples, const SurfaceDistanceOptions& options,
                           double progress_begin = 0.0, double progress_end = 1.0) const;
  // Distance from each point, in order.
  std::vector<double> distances(const std::vector<Point3>& points, unsigned threads = 0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct SurfaceDistanceReport {
  OneSidedDistance a_to_b;  // samples of A, distances to B
  OneSidedDistance b_to_a;  // samples of B, distances to A
  // Symmetric figures. Hausdorff is the usual max of the two one-sided
  // maxima. Mean and RMS are the larger of the two directions (Metro's
  // convention for its symmetric figures): the worse side is what a
  // simplification is judged by, and a plain average would let a large error
  // on one side hide behind a small one on the other.
  double hausdorff = 0.0;
  double mean = 0.0;
  double rms = 0.0;
  // Diagonal of A's bounding box (vertices used by its surface); every figure
  // divided by it gives the relative figures the literature reports.
  double bbox_diagonal = 0.0;
  double relative(double figure) const { return bbox_diagonal > 0.0 ? figure / bbox_diagonal : 0.0; }
};

// Bounding-box diagonal of the vertices used by non-degenerate triangles.
double surfaceBoxDiagonal(const TriangleMesh& mesh);

// Measures both directions. Both meshes must pass checkSurfaceMesh; returns
// false with one line in `error` (naming "A" or "B") when one does not.
bool measureSurfaceDistance(const TriangleMesh& a, const TriangleMesh& b,
                            const SurfaceDistanceOptions& options, SurfaceDistanceReport* report,
                            std::string* error);

}  // namespace mrsv
