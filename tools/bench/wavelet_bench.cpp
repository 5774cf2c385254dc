// Wavelet transform speed: analyze (encoder, floating point) and synthesizeFixed
// (decoder, normative integer synthesis) on cubes of order 4 (the B-spline) or 5
// (CDF 9/7; the second argument), with the encoder's default levels
// (chooseLevels). BM_SynthesizeCdf97Scalar runs the 9/7 synthesis with the
// portable kernels instead of the fastest this CPU has. Reports the time per
// sample of the padded array (counter per_sample, in seconds: "29.6ns" reads
// 29.6 ns per sample).
//
//   build/wavelet_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "wavelet/axis_plan.h"
#include "wavelet/cdf97_kernels.h"
#include "wavelet/synthesis_fixed.h"
#include "wavelet/transform_float.h"

namespace {

using namespace mrsv::wavelet;

GridPlan cube(uint32_t n, int order = 4) {
  const uint32_t sizes[3] = {n, n, n};
  const int levels = chooseLevels(n, order, kMaxLevels);
  const int per_axis[3] = {levels, levels, levels};
  GridPlan plan;
  makeGridPlan(3, sizes, order, per_axis, &plan);
  return plan;
}

// A smooth field with some texture, like a CT volume.
std::vector<double> field(const GridPlan& plan) {
  const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0), nz = plan.axis[2].size(0);
  std::vector<double> v(plan.paddedCount());
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x)
        v[(size_t{z} * ny + y) * nx + x] =
            1000.0 * std::sin(0.05 * x) * std::cos(0.031 * y) + 7.0 * z +
            ((x * 7 + y * 13 + z) % 17);
  return v;
}

void BM_Analyze(benchmark::State& state) {
  const GridPlan plan = cube(static_cast<uint32_t>(state.range(0)));
  const std::vector<double> input = field(plan);
  std::vector<double> data(input.size());
  for (auto _ : state) {
    state.PauseTiming();
    data = input;
    state.ResumeTiming();
    analyze(plan, data.data());
    benchmark::DoNotOptimize(data.data());
  }
  state.counters["levels"] = plan.maxLevels();
  state.counters["per_sample"] = benchmark::Counter(
      static_cast<double>(plan.paddedCount()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <bool kScalarCdf97>
void synthesizeBench(benchmark::State& state) {
  const GridPlan plan = cube(static_cast<uint32_t>(state.range(0)), static_cast<int>(state.range(1)));
  std::vector<double> coef = field(plan);
  analyze(plan, coef.data());
  std::vector<int64_t> input(coef.size());
  for (size_t i = 0; i < coef.size(); ++i)
    input[i] = static_cast<int64_t>(std::nearbyint(coef[i] * 4.0)) * 16384;  // step 1/4, 2^16 scale
  std::vector<int64_t> data(input.size());
  for (auto _ : state) {
    state.PauseTiming();
    data = input;
    state.ResumeTiming();
    if (kScalarCdf97) synthesizeFixedCdf97(plan, data.data(), 0, cdf97ScalarKernels());
    else synthesizeFixed(plan, data.data());
    benchmark::DoNotOptimize(data.data());
  }
  state.counters["levels"] = plan.maxLevels();
  state.counters["per_sample"] = benchmark::Counter(
      static_cast<double>(plan.paddedCount()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Analyze)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);
void BM_SynthesizeFixed(benchmark::State& state) { synthesizeBench<false>(state); }
void BM_SynthesizeCdf97Scalar(benchmark::State& state) { synthesizeBench<true>(state); }

BENCHMARK(BM_SynthesizeFixed)
    ->ArgsProduct({{64, 128, 256}, {4, kOrderCdf97}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeCdf97Scalar)->Args({256, kOrderCdf97})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
