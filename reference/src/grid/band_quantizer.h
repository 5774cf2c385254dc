// The quantiser of one band at a base step (informative 5.9): the fixed-point
// step the band header carries, and the integers of an array of the band's
// coefficients. With precincts each block is quantised apart, as it is coded
// apart (fresh contexts, spec 5.7.6), so that an encoder holding one row of
// blocks makes the same integers as one holding the grid.
#pragma once

#include <cstdint>

#include "grid/coefficient_coding.h"
#include "grid/encoder_setup.h"

namespace mrsv {

struct BandQuantizer {
  uint64_t step = 1;     // fixed point (frac_bits), as the band header carries it
  double inv = 1;        // fixed-point units per x unit, over the step
  double rounding = 0.5; // 0.5 for the coarsest block; a dead zone for details
  int64_t q_limit = 0;   // the largest magnitude (kValueLimit / step)
  bool rd = false;       // rate-distortion optimised (rd_quantizer.h)
  bool drop_lone = false;// a lone +-1 below 0.9 steps set to 0
};

// For band `index` of `setup` at base step `delta` (x units, sample-domain:
// divided by the band's gain). `step_scale` divides delta first (a region of
// interest's finer step); `oracles`: the caller drops coefficients itself
// (global or local oracle), so neither rd nor drop_lone.
BandQuantizer bandQuantizer(const WaveletSetup& setup, size_t index, double delta, bool integer_samples,
                            double step_scale = 1, bool oracles = false);

// Quantises `c` (x units, contiguous over `box`, x fastest) into `q`; returns
// whether any value is non-zero.
bool quantizeArray(const BandQuantizer& quantizer, const double* c, const ArrayBox& box, int64_t* q);

// quantizeArray() over each block of a band's array apart (spec 5.7.6: the
// blocks of `box` at `resolution` for precincts of 2^precinct_log2; with 0,
// the array whole).
bool quantizeBlocked(const BandQuantizer& quantizer, const double* c, const ArrayBox& box, const int resolution[3],
                     int precinct_log2, int64_t* q);

}  // namespace mrsv
