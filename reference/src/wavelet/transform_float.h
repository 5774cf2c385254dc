// Floating-point B-spline wavelet transform, for the encoder. (Informative,
// spec 4.8 and 4.9; the decoder uses synthesis_fixed.h.)
//
// Time is linear in the number of values: analysis solves the dual (Gram) systems
// as banded symmetric positive definite systems; synthesis applies the sparse P, Q.
#pragma once

#include <cstdint>
#include <vector>

#include "wavelet/axis_plan.h"

namespace mrsv::wavelet {

// In place, full decomposition (every axis to its plan's levels) of the padded
// array (plan.paddedCount() values, x fastest) into the Mallat layout of spec 4.4.
// The caller fills the padding (samples N..size(0)-1 of each axis). Like the other
// transforms, does nothing when !isValidGridPlan(plan). spec: 4.8
void analyze(const GridPlan& plan, double* data);

// The exact inverse of analyze (up to rounding), down to level stop_level, with the
// same level and axis order as synthesizeFixed (spec 4.5) and the exact taps.
void synthesize(const GridPlan& plan, double* data, int stop_level = 0);

// L2 norm (function space, unit-length knot spacing at the finest level) of the basis
// function behind every coefficient of one axis at its place in the Mallat layout after full
// analysis: scaling functions of the coarsest level, wavelets of every level. Tensor-product
// norms multiply. Used by the oracles and the quantiser weights. size(0) values; all 1
// for an axis with levels == 0 (its samples are not transformed). spec: 4.9
std::vector<double> axisBasisNorms(const AxisPlan& axis);

// Added: entry (i, j) of the Gram matrix of the order-k B-splines with `intervals`
// unit intervals (0 outside the band); needs intervals >= minCoarseIntervals(order).
// spec: 4.8, spec/tables/wavelet-filters.md
double gramEntry(int order, uint32_t intervals, uint32_t i, uint32_t j);

// Added: entry (i, j) of the Gram matrix Q^T G Q of the wavelets of a level with
// `coarse_intervals` intervals, unit knot spacing at its fine level. spec: 4.8
double waveletGramEntry(int order, uint32_t coarse_intervals, uint32_t i, uint32_t j);

}  // namespace mrsv::wavelet
