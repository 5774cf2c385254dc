// Oracles of the encoder (paper 2.2; spec 5.9, informative): which wavelet
// coefficients to keep, where, and what the kept ones cost in L2 error.
#pragma once

#include <cstdint>
#include <vector>

#include "mrsv/encode.h"
#include "wavelet/axis_plan.h"

namespace mrsv {

// Per axis, the interval of samples [lo, hi] that each basis function of the
// Mallat layout touches, at every level (support-aware local oracle).
class AxisSupports {
 public:
  explicit AxisSupports(const wavelet::AxisPlan& axis);
  // Scaling function `index` of `level` (0 = the samples themselves).
  void scaling(int level, uint32_t index, uint32_t* lo, uint32_t* hi) const;
  // Wavelet `index` of `level` (1 = finest).
  void wavelet(int level, uint32_t index, uint32_t* lo, uint32_t* hi) const;

 private:
  std::vector<std::vector<uint32_t>> scaling_lo_, scaling_hi_, wavelet_lo_, wavelet_hi_;
};

// Weight in [0, 1] of a coefficient whose support is the box [lo, hi] (per
// axis, in samples): 1 when the support reaches into the region, else a
// Gaussian of its distance to the region with deviation `falloff` samples.
double regionWeight(const RegionOfInterest& roi, int num_dims, const uint32_t lo[3],
                    const uint32_t hi[3]);

// Exact squared L2 norm, in the function space of the finest level's B-splines
// with unit knot spacing, of the function whose coefficients (in the Mallat
// layout of `plan`) are `e`: the sum over bands of e_b^T (G_x (x) G_y (x) G_z) e_b,
// bands being mutually orthogonal in the semi-orthogonal basis. Linear time.
// For the CDF 9/7 wavelet (spec 4.11), the squared norm of the samples e
// synthesises to.
double functionSpaceNormSquared(const wavelet::GridPlan& plan,
                                const std::vector<wavelet::Band>& bands,
                                const std::vector<double>& e);

}  // namespace mrsv
