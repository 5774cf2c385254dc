// A triangle's worst sample over its rows' runs (spec 8.5's scan on a lattice
// of step 1), four samples per instruction where the CPU has AVX2: the scans
// are most of the insertion's time at the larger error bounds, where a
// triangle's rows are tens of samples long.
#pragma once

#include <cstdint>

namespace mrsv::reconstruct {

// The samples of one lattice row in [lo, hi] (empty when lo > hi).
struct SampleRun {
  int64_t lo, hi;
};

// The rows' runs and the error's numerator e(x, y) = values(x, y) den -
// q(x, y), with q(x, y) = q_row + (y - first row) dq_row + (x - x0) qx taken
// modulo 2^64. Every e is below 2^62 in size (the insertion's 64-bit scans).
struct RunScan {
  const int16_t* first_row;  // the samples of the first run's row, from x = 0
  int64_t row_stride;        // samples from one row to the next
  const SampleRun* runs;
  int64_t run_count;
  int64_t x0;
  int64_t den;  // 0 < den < 2^31
  uint64_t q_row, dq_row, qx;
};

// The largest |e| over the runs' samples and the first sample (in row, then
// x order) where it is reached; {0, nullptr} when no sample has |e| > 0.
struct RunWorst {
  int64_t size;
  const int16_t* at;
};
using RunScanFunction = RunWorst (*)(const RunScan& scan);

// The AVX2 version on CPUs that have it, else null. It reads up to three
// samples past a run's end (the caller pads its array with 4). Its result is
// the scalar scan's.
RunScanFunction runScanAvx2();

}  // namespace mrsv::reconstruct
