// spec: 5.2 (value mapping, decision D6), 4.3 (levels), 5.9 (band gains).
#include "grid/encoder_setup.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "grid/precincts.h"
#include "wavelet/transform_float.h"

namespace mrsv {
namespace {

using wavelet::Band;
using wavelet::GridPlan;

Error invalid(std::string field, std::string message) {
  return Error{Status::kInvalidArgument, 0, std::move(field), std::move(message)};
}

// Sample-domain L2 gain of one interior coefficient of a 1-D axis: the
// Euclidean norm of the finest-level coefficients synthesised from a unit
// impulse. wavelet[l]: wavelets of level l (1..L); scaling[l]: scaling
// functions of level l (0..L), each synthesised from a plan of l levels (the
// same functions up to the padding).
struct AxisGains {
  std::vector<double> wavelet, scaling;
};

double impulseGain(const wavelet::AxisPlan& axis, const Band& band) {
  GridPlan line;
  line.num_dims = 1;
  line.axis[0] = axis;
  std::vector<double> buffer(axis.size(0), 0.0);
  buffer[band.offset[0] + band.size[0] / 2] = 1.0;  // an interior function
  wavelet::synthesize(line, buffer.data());
  double energy = 0;
  for (double v : buffer) energy += v * v;
  return std::sqrt(energy);
}

AxisGains axisGains(const wavelet::AxisPlan& axis) {
  AxisGains g;
  g.wavelet.assign(static_cast<size_t>(axis.levels) + 1, 1.0);
  g.scaling.assign(static_cast<size_t>(axis.levels) + 1, 1.0);
  for (int l = 1; l <= axis.levels; ++l) {
    wavelet::AxisPlan sub;
    if (!wavelet::makeAxisPlan(axis.samples, axis.order, l, &sub)) sub = axis;
    GridPlan line;
    line.num_dims = 1;
    line.axis[0] = sub;
    for (const Band& band : wavelet::bandsOf(line)) {
      if (band.mask == 0) g.scaling[static_cast<size_t>(l)] = impulseGain(sub, band);
      else if (band.level == l) g.wavelet[static_cast<size_t>(l)] = impulseGain(sub, band);
    }
  }
  return g;
}

}  // namespace

Error makeWaveletSetup(const GridHeader& grid, double c_min, double c_max, const WaveletEncodeOptions& options,
                       WaveletSetup* out) {
  static_assert(kWaveletOrderCdf97 == wavelet::kOrderCdf97, "one value for the 9/7 wavelet");
  if (!wavelet::isValidOrder(options.order))
    return invalid("order", "order must be 1 to 4, or 5 for the CDF 9/7 wavelet");
  if (options.precinct_log2 != 0 &&
      (options.precinct_log2 < kMinPrecinctLog2 || options.precinct_log2 > kMaxPrecinctLog2))
    return invalid("precinct", "the precinct must be a power of two from 2^" +
                                   std::to_string(kMinPrecinctLog2) + " to 2^" +
                                   std::to_string(kMaxPrecinctLog2));
  WaveletSetup s;
  WaveletHeader& wh = s.header;
  wh.order = static_cast<uint8_t>(options.order);
  wh.entropy_mode = options.entropy_mode;
  wh.precinct_log2 = static_cast<uint8_t>(options.precinct_log2);
  // spec: 5.2 and decision D6: x = (sample - c_min) / scale, so x spans [0, R / scale].
  const double r = c_max - c_min;
  const bool is_float = grid.sample_type == SampleType::kFloat32 || grid.sample_type == SampleType::kFloat64;
  if (!is_float) {
    s.scale = 1;
    wh.value_offset = static_cast<uint64_t>(static_cast<int64_t>(c_min));
    wh.value_scale = 0;
    // Coefficients must stay below kValueLimit = 2^35 in fixed point. A
    // coefficient can reach the product over the transformed axes of the
    // worst-case gain from samples to coefficients (spec 4.10: 1, 2.52, 3.87,
    // 7.05 for orders 1-4, rounded up here; 4.11.4: 2.1 for CDF 9/7) times the
    // range, plus one step.
    static const double kWorstAxisGain[6] = {0, 1.0, 2.6, 4.0, 7.2, 2.2};
    double gain = 1;
    for (int a = 0; a < grid.num_dims; ++a)
      if (wavelet::chooseLevels(a == 0 ? grid.size_x : a == 1 ? grid.size_y : grid.size_z, options.order,
                                options.max_levels) > 0)
        gain *= kWorstAxisGain[options.order];
    const int frac = 34 - static_cast<int>(std::ceil(std::log2(gain * (r + 1))));
    wh.frac_bits = static_cast<uint8_t>(std::clamp(frac, 0, 24));
  } else {
    s.scale = r > 0 ? std::ldexp(r, -24) : 1.0;
    std::memcpy(&wh.value_offset, &c_min, 8);
    std::memcpy(&wh.value_scale, &s.scale, 8);
    wh.frac_bits = 6;
  }
  const uint32_t size[3] = {grid.size_x, grid.size_y, grid.size_z};
  int levels[3] = {0, 0, 0};
  for (int a = 0; a < grid.num_dims; ++a) {
    levels[a] = wavelet::chooseLevels(size[a], options.order, options.max_levels);
    wh.levels[a] = static_cast<uint8_t>(levels[a]);
  }
  if (!wavelet::makeGridPlan(grid.num_dims, size, options.order, levels, &s.plan))
    return invalid("grid", "no wavelet plan for this grid");
  s.bands = wavelet::bandsOf(s.plan);
  if (s.bands.size() > 65535) return invalid("grid", "more than 65535 bands");
  AxisGains gains[3];
  for (int a = 0; a < 3; ++a) gains[a] = axisGains(s.plan.axis[a]);
  for (const Band& b : s.bands) {
    double g = 1;
    for (int a = 0; a < 3; ++a) {
      const wavelet::AxisPlan& ax = s.plan.axis[a];
      if (ax.levels == 0) continue;
      if (b.mask & (1 << a)) g *= gains[a].wavelet[static_cast<size_t>(b.level)];
      else g *= gains[a].scaling[static_cast<size_t>(b.mask == 0 ? ax.levels : std::min(b.level, ax.levels))];
    }
    s.band_gain.push_back(g);
  }
  *out = std::move(s);
  return {};
}

}  // namespace mrsv
