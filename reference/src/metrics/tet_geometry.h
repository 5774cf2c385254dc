// Small geometric helpers the tet metrics share.
#pragma once

#include <array>

namespace mrsv {

// The signed volume of tet (a, b, c, d): det[b - a, c - a, d - a] / 6.
inline double signedTetVolume(const std::array<double, 3>& a, const std::array<double, 3>& b,
                              const std::array<double, 3>& c, const std::array<double, 3>& d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

}  // namespace mrsv
