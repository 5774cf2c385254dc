// The exact error tests of spec 9.4 and 9.5: are the samples of a triangle
// (or of a run of a grid line) within E of its linear interpolant? Integers
// only: the threshold E * D is floored once per triangle, then each sample
// costs one multiply-subtract and two compares.
#pragma once

#include <cstdint>
#include <vector>

#include "mrsv/grid_mesh.h"

namespace mrsv::quadtree {

class ErrorTest {
 public:
  ErrorTest(const SampleField& field, const ErrorBound& bound);

  // Triangle of grid points p[0..2] (counter-clockwise, inside the grid):
  // true when every sample in the closed triangle is within the bound of the
  // plane through the three vertices' samples.
  bool triangleWithin(const uint32_t p[3][2]) const;

  // The test of triangleWithin for one sample, from the parts a caller has:
  // s is the sample at a point inside the closed counter-clockwise triangle
  // p0 p1 p2 with d = orient(p0, p1, p2) > 0, w1 = orient(p0, point, p2) and
  // w2 = orient(p0, p1, point); s0, s1, s2 are the vertices' samples. True
  // when s is within the bound of the plane through the three.
  bool sampleWithin(int64_t d, int64_t w1, int64_t w2, int64_t s0, int64_t s1, int64_t s2, int64_t s) const {
    if (narrow(d)) {
      const int64_t diff = (s - s0) * d - ((s1 - s0) * w1 + (s2 - s0) * w2);
      const int64_t threshold = thresholdFor(d);
      return diff <= threshold && diff >= -threshold;
    }
    return sampleWithinWide(d, w1, w2, s0, s1, s2, s);
  }

  // Samples of grid points first + k * step for k = 0..n (step 1: along a row,
  // step = width: along a column): true when each is within the bound of the
  // line through the first and the last.
  bool runWithin(uint64_t first, uint64_t step, uint32_t n) const;

  const SampleField& field() const { return field_; }
  const ErrorBound& bound() const { return bound_; }

 private:
  // A small triangle (its other vertices within kShapeReach samples of the
  // first along each axis) is tested through its shape's grid points: the
  // points of the closed triangle other than its vertices, each with its
  // offset from the first vertex in the field and its edge functions w1, w2,
  // listed the first time the shape is tested. Most triangles of the tree's
  // fine leaves and of the removal pass hold a handful of samples, which a
  // scan of their box would cost several times more to find.
  static constexpr int kShapeReach = 7;
  static constexpr int kShapeSide = 2 * kShapeReach + 1;
  struct ShapePoint {
    int64_t offset;  // in the field, from the first vertex
    int32_t w1, w2;
  };
  bool smallTriangleWithin(int64_t x0, int64_t y0, int64_t dx1, int64_t dy1, int64_t dx2, int64_t dy2, int64_t d) const;
  uint32_t shapePoints(int64_t dx1, int64_t dy1, int64_t dx2, int64_t dy2, int64_t d) const;

  // Every term of a triangle's test with twice the area d fits in 64 bits
  // relative to its first vertex's sample (spec 9.4 bounds each by 12 range d).
  bool narrow(int64_t d) const {
    return static_cast<unsigned __int128>(range_) * static_cast<uint64_t>(d) < (uint64_t{1} << 58);
  }
  template <class Acc>
  bool scanTriangle(const int64_t q[3][2], int64_t d, int64_t threshold) const;
  // floor(E * d). |s - m| <= num / den with m = n / d is |s d - n| <= num d /
  // den; the left side is an integer, so the right side may be floored.
  int64_t thresholdFor(int64_t d) const {
    int64_t product;
    if (!__builtin_mul_overflow(bound_.num, d, &product))  // both >= 0
      return bound_.den == 1 ? product : product / bound_.den;
    return thresholdWide(d);
  }
  int64_t thresholdWide(int64_t d) const;
  bool sampleWithinWide(int64_t d, int64_t w1, int64_t w2, int64_t s0, int64_t s1, int64_t s2, int64_t s) const;

  const SampleField& field_;
  ErrorBound bound_;
  uint64_t range_ = 0;  // max - min of the samples
  // Per shape (dx1, dy1, dx2, dy2): where its points start in shape_points_
  // (kShapeSide^4 entries, 0 until listed; an entry is the start + 1), each
  // list ending with an entry whose w1 is -1. Filled as shapes are met: the
  // test is const, and an ErrorTest serves one thread.
  mutable std::vector<uint32_t> shape_start_;
  mutable std::vector<ShapePoint> shape_points_;
};

}  // namespace mrsv::quadtree
