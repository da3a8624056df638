#include "biovision_recognition/projection_kernel.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/core/utility.hpp>

namespace biovision_recognition
{
namespace
{
constexpr size_t kRowsPerTask = 64;
// 1024 inputs x 128 outputs x 4 bytes = 512 KiB of P per tile: within L2.
constexpr size_t kTile = 1024;
}  // namespace

namespace
{
__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void projectBlock(
    const float* x, size_t rows, size_t inputs, const float* p, size_t outputs, float* y)
{
  std::memset(y, 0, rows * outputs * sizeof(float));
  for (size_t k0 = 0; k0 < inputs; k0 += kTile)
  {
    const size_t n = std::min(kTile, inputs - k0);
    size_t i = 0;
    for (; i + 4 <= rows; i += 4)
    {
      const float* x0 = x + i * inputs + k0;
      const float* x1 = x0 + inputs;
      const float* x2 = x1 + inputs;
      const float* x3 = x2 + inputs;
      size_t b = 0;
      // 4 rows x 4 outputs per pass: 8 loads feed 16 multiply-adds (4 x 1 would be load-bound).
      for (; b + 4 <= outputs; b += 4)
      {
        const float* p0 = p + b * inputs + k0;
        const float* p1 = p0 + inputs;
        const float* p2 = p1 + inputs;
        const float* p3 = p2 + inputs;
        float a00 = 0, a01 = 0, a02 = 0, a03 = 0, a10 = 0, a11 = 0, a12 = 0, a13 = 0;
        float a20 = 0, a21 = 0, a22 = 0, a23 = 0, a30 = 0, a31 = 0, a32 = 0, a33 = 0;
#pragma omp simd reduction(+ : a00, a01, a02, a03, a10, a11, a12, a13, a20, a21, a22, a23, a30, a31, a32, a33)
        for (size_t k = 0; k < n; ++k)
        {
          const float v0 = x0[k], v1 = x1[k], v2 = x2[k], v3 = x3[k];
          const float w0 = p0[k], w1 = p1[k], w2 = p2[k], w3 = p3[k];
          a00 += v0 * w0;
          a01 += v0 * w1;
          a02 += v0 * w2;
          a03 += v0 * w3;
          a10 += v1 * w0;
          a11 += v1 * w1;
          a12 += v1 * w2;
          a13 += v1 * w3;
          a20 += v2 * w0;
          a21 += v2 * w1;
          a22 += v2 * w2;
          a23 += v2 * w3;
          a30 += v3 * w0;
          a31 += v3 * w1;
          a32 += v3 * w2;
          a33 += v3 * w3;
        }
        float* y0 = y + i * outputs + b;
        float* y1 = y0 + outputs;
        float* y2 = y1 + outputs;
        float* y3 = y2 + outputs;
        y0[0] += a00;
        y0[1] += a01;
        y0[2] += a02;
        y0[3] += a03;
        y1[0] += a10;
        y1[1] += a11;
        y1[2] += a12;
        y1[3] += a13;
        y2[0] += a20;
        y2[1] += a21;
        y2[2] += a22;
        y2[3] += a23;
        y3[0] += a30;
        y3[1] += a31;
        y3[2] += a32;
        y3[3] += a33;
      }
      for (; b < outputs; ++b)
      {
        const float* pb = p + b * inputs + k0;
        float a0 = 0.f, a1 = 0.f, a2 = 0.f, a3 = 0.f;
#pragma omp simd reduction(+ : a0, a1, a2, a3)
        for (size_t k = 0; k < n; ++k)
        {
          a0 += pb[k] * x0[k];
          a1 += pb[k] * x1[k];
          a2 += pb[k] * x2[k];
          a3 += pb[k] * x3[k];
        }
        y[i * outputs + b] += a0;
        y[(i + 1) * outputs + b] += a1;
        y[(i + 2) * outputs + b] += a2;
        y[(i + 3) * outputs + b] += a3;
      }
    }
    for (; i < rows; ++i)
    {
      const float* xi = x + i * inputs + k0;
      for (size_t b = 0; b < outputs; ++b)
      {
        const float* pb = p + b * inputs + k0;
        float a = 0.f;
#pragma omp simd reduction(+ : a)
        for (size_t k = 0; k < n; ++k)
          a += pb[k] * xi[k];
        y[i * outputs + b] += a;
      }
    }
  }
}
}  // namespace

void projectRows(const float* x, size_t rows, size_t inputs, const float* p, size_t outputs, float* y)
{
  // Blocks of rows are independent: both cores (cv::parallel_for_ follows cv::setNumThreads).
  const int tasks = static_cast<int>((rows + kRowsPerTask - 1) / kRowsPerTask);
  cv::parallel_for_(cv::Range(0, tasks), [&](const cv::Range& r) {
    for (int t = r.start; t < r.end; ++t)
    {
      const size_t first = t * kRowsPerTask, n = std::min(kRowsPerTask, rows - first);
      projectBlock(x + first * inputs, n, inputs, p, outputs, y + first * outputs);
    }
  });
}
}  // namespace biovision_recognition
