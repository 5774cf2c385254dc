// Encoder-side filling of no-data samples (informative 5.9 item 3). The mask
// (GMSK) restores every void exactly, so the values the encoder puts there are
// free: they are chosen to cost as few wavelet bits as possible.
#pragma once

#include <cstdint>
#include <vector>

#include "wavelet/axis_plan.h"

namespace mrsv {

// Fills the voids of `x` (valid[i] == 0; x fastest over `size`) by pull-push:
// averages of valid samples over dyadic blocks, pushed back down into the voids.
void fillVoidsPullPush(std::vector<double>* x, const std::vector<uint8_t>& valid, const uint32_t size[3]);

// The padded array of `x` (the last sample of every axis repeated; constants
// cost no detail coefficients), analysed into `coefficients` (Mallat layout).
void analyzeSamples(const wavelet::GridPlan& plan, const uint32_t size[3], const std::vector<double>& x,
                    std::vector<double>* coefficients);

// Refines a filled `x` by iterative hard thresholding, the inpainting of
// sparse-representation methods: detail coefficients whose sample-domain
// importance (|c| times `band_gain`) is below a threshold are dropped, the
// voids take the synthesised values, and the threshold falls from range / 8 to
// range / 200 over the iterations. The voids converge to what the valid
// samples' own sparse approximation continues into them, so the edges a
// blocky fill makes at void borders vanish. `coefficients` holds the analysis
// of `x` on entry and on return. `range` is c_max - c_min in x units.
void refineVoidFill(const wavelet::GridPlan& plan, const uint32_t size[3],
                    const std::vector<wavelet::Band>& bands, const std::vector<double>& band_gain,
                    const std::vector<uint8_t>& valid, double range, std::vector<double>* x,
                    std::vector<double>* coefficients);

}  // namespace mrsv
