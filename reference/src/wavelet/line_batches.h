// Walks the lines of a box of the padded array along one axis, a batch of
// neighbouring lines at a time. Internal to the wavelet module.
//
// A batch of `width` lines is copied into scratch interleaved, line element i of
// line w at in[i * width + w], so that the 1-D kernels run over the batch with
// unit stride (and vectorise) whichever axis is transformed, and so that lines
// along y and z are read as runs of neighbouring x values instead of one value
// per cache line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrsv::wavelet {

constexpr int kLineBatch = 16;

// kernel(T* in, T* out, int width): both arrays hold box[axis] * width values;
// the kernel reads `in` (scratch it may overwrite) and writes `out`.
template <typename T, typename Kernel>
void forEachLineBatch(const uint32_t padded[3], const uint32_t box[3], int axis, T* data,
                      std::vector<T>* in, std::vector<T>* out, Kernel&& kernel) {
  const size_t stride[3] = {1, size_t{padded[0]}, size_t{padded[0]} * padded[1]};
  const int b = axis == 0 ? 1 : 0;  // batch along the fastest other axis
  const int c = 3 - axis - b;
  const size_t len = box[axis];
  const size_t sa = stride[axis], sb = stride[b];
  // Scratch for the widest batch only: a 1-D grid of 2^24 samples needs 2 lines.
  const size_t batch = box[b] < kLineBatch ? box[b] : kLineBatch;
  in->resize(len * batch);
  out->resize(len * batch);
  T* src = in->data();
  T* dst = out->data();
  for (uint32_t ic = 0; ic < box[c]; ++ic) {
    for (uint32_t ib = 0; ib < box[b]; ib += kLineBatch) {
      const int width = static_cast<int>(box[b] - ib < kLineBatch ? box[b] - ib : kLineBatch);
      T* base = data + ic * stride[c] + ib * sb;
      if (sa == 1) {
        for (int w = 0; w < width; ++w)
          for (size_t i = 0; i < len; ++i) src[i * width + w] = base[w * sb + i];
      } else {
        for (size_t i = 0; i < len; ++i)
          for (int w = 0; w < width; ++w) src[i * width + w] = base[i * sa + w * sb];
      }
      kernel(src, dst, width);
      if (sa == 1) {
        for (int w = 0; w < width; ++w)
          for (size_t i = 0; i < len; ++i) base[w * sb + i] = dst[i * width + w];
      } else {
        for (size_t i = 0; i < len; ++i)
          for (int w = 0; w < width; ++w) base[i * sa + w * sb] = dst[i * width + w];
      }
    }
  }
}

}  // namespace mrsv::wavelet
