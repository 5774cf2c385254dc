// spec: 5.9 (informative) quantisation of a band.
#include "grid/band_quantizer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "grid/precincts.h"
#include "grid/rd_quantizer.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv {
namespace {

// Sets to 0 every +-1 of `q` whose neighbours in the array (the 8 or 26
// around it) are all 0 and whose scaled coefficient is below 0.9 steps. Done
// in place: a value set to 0 had only zeros around it, so no other candidate
// sees the change, and the result is that of deciding on `q` as it came.
// Returns whether any value is left.
bool dropLoneUnits(const double* c, double inv, const ArrayBox& box, int64_t* q) {
  constexpr double kLoneUnitFloor = 0.9;
  const int64_t sx = box.size[0], sy = box.size[1], sz = box.size[2];
  auto at = [&](int64_t x, int64_t y, int64_t z) { return static_cast<size_t>(x + sx * (y + sy * z)); };
  auto alone = [&](int64_t x, int64_t y, int64_t z) {
    for (int64_t nz = std::max<int64_t>(z - 1, 0); nz <= std::min(z + 1, sz - 1); ++nz)
      for (int64_t ny = std::max<int64_t>(y - 1, 0); ny <= std::min(y + 1, sy - 1); ++ny)
        for (int64_t nx = std::max<int64_t>(x - 1, 0); nx <= std::min(x + 1, sx - 1); ++nx)
          if ((nx != x || ny != y || nz != z) && q[at(nx, ny, nz)] != 0) return false;
    return true;
  };
  bool any = false;
  for (int64_t z = 0; z < sz; ++z)
    for (int64_t y = 0; y < sy; ++y)
      for (int64_t x = 0; x < sx; ++x) {
        int64_t& value = q[at(x, y, z)];
        if ((value == 1 || value == -1) && alone(x, y, z) && std::fabs(c[at(x, y, z)] * inv) < kLoneUnitFloor)
          value = 0;
        any |= value != 0;
      }
  return any;
}

}  // namespace

BandQuantizer bandQuantizer(const WaveletSetup& setup, size_t index, double delta, bool integer_samples,
                            double step_scale, bool oracles) {
  const wavelet::Band& band = setup.bands[index];
  const WaveletHeader& wh = setup.header;
  BandQuantizer q;
  const double units = std::ldexp(1.0, wh.frac_bits);
  const double step_x = delta / step_scale / setup.band_gain[index];
  // Step in fixed point; the quantiser uses exactly what the decoder will.
  q.step = static_cast<uint64_t>(
      std::clamp(std::llround(step_x * units), 1LL, static_cast<long long>(wavelet::kValueLimit)));
  q.inv = units / static_cast<double>(q.step);
  q.q_limit = wavelet::kValueLimit / static_cast<int64_t>(q.step);
  const bool coarsest = band.mask == 0;
  // A dead zone for detail coefficients: small ones cost more bits than the
  // error they remove (informative 5.9). Measured best: 0.3 for the B-spline
  // wavelets, 0.4 for 9/7 (St Helens and Everest at 1 and 2 bits/sample).
  q.rounding = coarsest ? 0.5 : wavelet::isCdf97(wh.order) ? 0.4 : 0.3;
  // Rate-distortion optimised quantisation (rd_quantizer.h) for detail bands
  // under the global rate or PSNR oracles with range coding. Lambda 0.09
  // squared steps per bit measured best (see quantizeArray). Below a step of
  // half a sample unit the decoder's rounding to integer samples hides most
  // errors, and the coefficient-domain estimate misleads (the chest CT at 2
  // bits/sample, 96.7 dB, lost 2.2 dB), so there the dead zone stays.
  q.rd = !coarsest && !oracles && wh.entropy_mode == kEntropyAdaptive &&
         (!integer_samples || delta * setup.scale >= 0.5);
  // A lone +-1 among zeros costs many bits (its zero flag is coded in the
  // quietest context, 5.7.3) for little error: it is kept only when |c| is at
  // least 0.9 steps. Measured: +0.05 to +0.13 dB at 1 bit/sample.
  q.drop_lone = !coarsest && !oracles;
  return q;
}

bool quantizeArray(const BandQuantizer& quantizer, const double* c, const ArrayBox& box, int64_t* q) {
  const size_t n = box.count();
  // Lambda = 0.09 squared steps per bit measured best on the terrains at 0.5
  // to 2 bits/sample (+0.13 to +0.25 dB over the dead zone; 0.05 and 0.13 are worse).
  constexpr double kRdLambda = 0.09;
  if (quantizer.rd) {
    std::vector<double> scaled(n);
    for (size_t i = 0; i < n; ++i) scaled[i] = c[i] * quantizer.inv;
    return rdQuantizeArray(scaled.data(), box, kRdLambda, quantizer.q_limit, q);
  }
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    const double v = c[i] * quantizer.inv;
    const int64_t m = std::min(static_cast<int64_t>(std::floor(std::fabs(v) + quantizer.rounding)), quantizer.q_limit);
    q[i] = v < 0 ? -m : m;
    any |= m != 0;
  }
  if (quantizer.drop_lone && any) any = dropLoneUnits(c, quantizer.inv, box, q);
  return any;
}

bool quantizeBlocked(const BandQuantizer& quantizer, const double* c, const ArrayBox& box, const int resolution[3],
                     int precinct_log2, int64_t* q) {
  if (precinct_log2 == 0) return quantizeArray(quantizer, c, box, q);
  bool any = false;
  std::vector<double> block_c;
  std::vector<int64_t> block_q;
  const size_t row = box.size[0], slice = row * box.size[1];
  for (const ArrayBlock& b : arrayBlocks(box, resolution, precinct_log2)) {
    block_c.resize(b.box.count());
    block_q.resize(b.box.count());
    copyBlockOut(c, row, slice, b, block_c.data());
    any |= quantizeArray(quantizer, block_c.data(), b.box, block_q.data());
    copyBlockIn(block_q.data(), b, q, row, slice);
  }
  return any;
}

}  // namespace mrsv
