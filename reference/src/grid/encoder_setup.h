// What an encoder of wavelet-coded grids settles before it codes anything
// (informative 5.9): how samples map to x units, the levels of every axis, the
// plan, the bands and each band's gain. The in-memory encoder and the
// out-of-core precinct encoder share it, so that their streams agree.
#pragma once

#include <vector>

#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "wavelet/axis_plan.h"

namespace mrsv {

struct WaveletSetup {
  WaveletHeader header;           // order, entropy mode, precincts, levels, value mapping
  wavelet::GridPlan plan;
  std::vector<wavelet::Band> bands;
  std::vector<double> band_gain;  // sample-domain L2 gain of one coefficient of each band
  double scale = 1;               // sample units per x unit
};

// For a grid whose valid samples span [c_min, c_max]. Checks the order and
// the precinct size of `options`.
Error makeWaveletSetup(const GridHeader& grid, double c_min, double c_max, const WaveletEncodeOptions& options,
                       WaveletSetup* out);

}  // namespace mrsv
