// Neumaier's compensated sum, for the metrics' sums of many small terms
// (10^6 squared distances or errors, 10^5 tet volumes), which a plain sum
// would round to about six digits fewer.
#pragma once

#include <cmath>

namespace mrsv {

struct CompensatedSum {
  double sum = 0.0, carry = 0.0;
  void add(double x) {
    const double t = sum + x;
    carry += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + carry; }
};

}  // namespace mrsv
