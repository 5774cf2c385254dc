// The columns of the synthesis matrices P and Q at one level, built from the
// tables of spec 4.2 by the rules of spec 4.3. Internal to the wavelet module;
// shared by the fixed-point decoder and the floating-point encoder.
#pragma once

#include <cstdint>

#include "wavelet/filter_tables.h"

namespace mrsv::wavelet {

// The nonzero taps of one column: fine rows first_row .. first_row + count - 1.
struct Column {
  uint32_t first_row;
  int count;
  const double* taps;
  const int32_t* fixed;
};

// spec: 4.3. A level with n coarse intervals: fine() = 2n + d fine coefficients,
// coarse() = n + d scaling and wavelets() = n wavelet coefficients. The caller
// guarantees n >= n_min(k), so the boundary blocks of the two ends never meet.
class LevelFilters {
 public:
  LevelFilters(int order, uint32_t coarse_intervals)
      : f_(&orderFilters(order)), n_(coarse_intervals), d_(static_cast<uint32_t>(order - 1)) {}

  uint32_t fine() const { return 2 * n_ + d_; }
  uint32_t coarse() const { return n_ + d_; }
  uint32_t wavelets() const { return n_; }

  // Column j of P, 0 <= j < coarse().
  Column p(uint32_t j) const {
    const uint32_t nb = static_cast<uint32_t>(f_->p_boundary);
    if (j < nb) return left(f_->p_left[j]);
    if (j < coarse() - nb)
      return {interiorRow(j, f_->p_interior_first), f_->p_interior_count, f_->p_interior,
              f_->p_interior_fixed};
    return right(f_->p_left[coarse() - 1 - j]);
  }

  // Column j of Q, 0 <= j < wavelets().
  Column q(uint32_t j) const {
    const uint32_t nb = static_cast<uint32_t>(f_->q_boundary);
    if (j < nb) return left(f_->q_left[j]);
    if (j < n_ - nb)
      return {interiorRow(j, f_->q_interior_first), f_->q_interior_count, f_->q_interior,
              f_->q_interior_fixed};
    return right(f_->q_left[n_ - 1 - j]);
  }

  const OrderFilters& filters() const { return *f_; }

 private:
  // 2j + first (first <= 0); an interior column j has 2j + first >= 0.
  static uint32_t interiorRow(uint32_t j, int first) {
    return static_cast<uint32_t>(int64_t{2} * j + first);
  }
  static Column left(const BoundaryColumn& c) {
    return {static_cast<uint32_t>(c.first_row), c.count, c.taps, c.fixed};
  }
  // The mirror image of a left column: row i becomes fine() - 1 - i.
  Column right(const BoundaryColumn& c) const {
    return {fine() - static_cast<uint32_t>(c.first_row + c.count), c.count, c.taps_reversed,
            c.fixed_reversed};
  }

  const OrderFilters* f_;
  uint32_t n_;
  uint32_t d_;
};

}  // namespace mrsv::wavelet
