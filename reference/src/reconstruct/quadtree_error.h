// The exact error tests of spec 9.4 and 9.5: are the samples of a triangle
// (or of a run of a grid line) within E of its linear interpolant? Integers
// only: the threshold E * D is floored once per triangle, then each sample
// costs one multiply-subtract and two compares.
#pragma once

#include <cstdint>

#include "mrsv/grid_mesh.h"

namespace mrsv::quadtree {

class ErrorTest {
 public:
  ErrorTest(const SampleField& field, const ErrorBound& bound);

  // Triangle of grid points p[0..2] (counter-clockwise, inside the grid):
  // true when every sample in the closed triangle is within the bound of the
  // plane through the three vertices' samples.
  bool triangleWithin(const uint32_t p[3][2]) const;

  // Grid point (x, y), inside the closed triangle p[0..2] (counter-clockwise):
  // true when its sample alone is within the bound of that plane (the test of
  // triangleWithin for one sample).
  bool pointWithin(const uint32_t p[3][2], uint32_t x, uint32_t y) const;

  // Samples of grid points first + k * step for k = 0..n (step 1: along a row,
  // step = width: along a column): true when each is within the bound of the
  // line through the first and the last.
  bool runWithin(uint64_t first, uint64_t step, uint32_t n) const;

  const SampleField& field() const { return field_; }
  const ErrorBound& bound() const { return bound_; }

 private:
  template <class Acc>
  bool scanTriangle(const int64_t q[3][2], int64_t d, int64_t threshold) const;
  int64_t thresholdFor(int64_t d) const;  // floor(E * d)

  const SampleField& field_;
  ErrorBound bound_;
  uint64_t range_ = 0;  // max - min of the samples
};

}  // namespace mrsv::quadtree
