#include "biovision_recognition/packed_projection.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <Eigen/Core>
#include <opencv2/core/utility.hpp>

#include "biovision_common/cpu_features.hpp"

namespace biovision_recognition
{
namespace
{
constexpr std::size_t kOutputAlignment = 64;  // the widest path's output block; padding columns are 0
constexpr std::size_t kInputChunk = 256;      // 256 inputs x 128 outputs x 4 bytes = 128 KiB of P^T: in L2
constexpr std::size_t kRowGroup = 6;          // rows sharing each loaded vector of P^T
constexpr std::size_t kRowsPerTask = 8 * kRowGroup;

// Each kernel: y (rows x padded, row-major) = x (rows x inputs) * pt (inputs x padded); y is overwritten.

// Eigen's blocked GEMM (parallelised by Eigen itself: this library links OpenMP): it ran at 66-78 GFLOP/s
// here, ahead of the dot-product kernel before PackedProjection (33). One call: split further over two
// cv::parallel_for_ tasks (by rows or by columns) it was 0.4-0.95x of itself in projection_bench.
void projectGeneric(const float* x, std::size_t rows, std::size_t inputs, const float* pt, std::size_t padded, float* y)
{
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto r = static_cast<Eigen::Index>(rows), n = static_cast<Eigen::Index>(inputs),
             m = static_cast<Eigen::Index>(padded);
  Eigen::Map<RowMajor>(y, r, m).noalias() = Eigen::Map<const RowMajor>(x, r, n) * Eigen::Map<const RowMajor>(pt, n, m);
}

// The tiling every SIMD path shares: y (rows x padded) = x (rows x inputs) * pt (inputs x padded), y
// overwritten. For each chunk of inputs (its slice of P^T stays in L2), each group of kRowGroup rows and
// each block of `Width` outputs, micro(xr, pk, n, padded, y_block, group_rows) adds the group's products
// over the chunk's n inputs to y_block (row r at y_block + r * padded). Rows past the end repeat the last
// row (computed, never stored): the micro-kernel's loop has no row branch.
template <std::size_t Width, typename Micro>
void projectTiles(const float* x, std::size_t rows, std::size_t inputs, const float* pt, std::size_t padded, float* y,
                  Micro micro)
{
  std::memset(y, 0, rows * padded * sizeof(float));
  for (std::size_t k0 = 0; k0 < inputs; k0 += kInputChunk)
  {
    const std::size_t n = std::min(kInputChunk, inputs - k0);
    for (std::size_t i = 0; i < rows; i += kRowGroup)
    {
      const std::size_t group_rows = std::min(kRowGroup, rows - i);
      const float* xr[kRowGroup];
      for (std::size_t r = 0; r < kRowGroup; ++r)
        xr[r] = x + (i + std::min(r, group_rows - 1)) * inputs + k0;
      for (std::size_t o = 0; o < padded; o += Width)
        micro(xr, pt + k0 * padded + o, n, padded, y + i * padded + o, group_rows);
    }
  }
}

// 6 rows x 16 outputs. Named accumulators: 12 of the 16 ymm registers (an array of them was spilled in a
// prototype: 50 vs 99 GFLOP/s).
__attribute__((target("avx2,fma"))) void microAvx2(const float* const (&xr)[kRowGroup], const float* pk, std::size_t n,
                                                   std::size_t padded, float* y, std::size_t group_rows)
{
  __m256 c00 = _mm256_setzero_ps(), c01 = c00, c10 = c00, c11 = c00, c20 = c00, c21 = c00;
  __m256 c30 = c00, c31 = c00, c40 = c00, c41 = c00, c50 = c00, c51 = c00;
  for (std::size_t k = 0; k < n; ++k, pk += padded)
  {
    const __m256 b0 = _mm256_loadu_ps(pk), b1 = _mm256_loadu_ps(pk + 8);
    __m256 a = _mm256_broadcast_ss(xr[0] + k);
    c00 = _mm256_fmadd_ps(a, b0, c00);
    c01 = _mm256_fmadd_ps(a, b1, c01);
    a = _mm256_broadcast_ss(xr[1] + k);
    c10 = _mm256_fmadd_ps(a, b0, c10);
    c11 = _mm256_fmadd_ps(a, b1, c11);
    a = _mm256_broadcast_ss(xr[2] + k);
    c20 = _mm256_fmadd_ps(a, b0, c20);
    c21 = _mm256_fmadd_ps(a, b1, c21);
    a = _mm256_broadcast_ss(xr[3] + k);
    c30 = _mm256_fmadd_ps(a, b0, c30);
    c31 = _mm256_fmadd_ps(a, b1, c31);
    a = _mm256_broadcast_ss(xr[4] + k);
    c40 = _mm256_fmadd_ps(a, b0, c40);
    c41 = _mm256_fmadd_ps(a, b1, c41);
    a = _mm256_broadcast_ss(xr[5] + k);
    c50 = _mm256_fmadd_ps(a, b0, c50);
    c51 = _mm256_fmadd_ps(a, b1, c51);
  }
  const __m256 c[kRowGroup][2] = {{c00, c01}, {c10, c11}, {c20, c21}, {c30, c31}, {c40, c41}, {c50, c51}};
  for (std::size_t r = 0; r < group_rows; ++r)
  {
    float* yr = y + r * padded;
    _mm256_storeu_ps(yr, _mm256_add_ps(_mm256_loadu_ps(yr), c[r][0]));
    _mm256_storeu_ps(yr + 8, _mm256_add_ps(_mm256_loadu_ps(yr + 8), c[r][1]));
  }
}

// 6 rows x 64 outputs: 24 of the 32 zmm registers.
__attribute__((target("avx512f"))) void microAvx512(const float* const (&xr)[kRowGroup], const float* pk, std::size_t n,
                                                    std::size_t padded, float* y, std::size_t group_rows)
{
  __m512 c[kRowGroup][4];
  for (auto& row : c)
    for (auto& v : row)
      v = _mm512_setzero_ps();
  for (std::size_t k = 0; k < n; ++k, pk += padded)
  {
    const __m512 b0 = _mm512_loadu_ps(pk), b1 = _mm512_loadu_ps(pk + 16);
    const __m512 b2 = _mm512_loadu_ps(pk + 32), b3 = _mm512_loadu_ps(pk + 48);
#pragma GCC unroll 6
    for (std::size_t r = 0; r < kRowGroup; ++r)
    {
      const __m512 a = _mm512_set1_ps(xr[r][k]);
      c[r][0] = _mm512_fmadd_ps(a, b0, c[r][0]);
      c[r][1] = _mm512_fmadd_ps(a, b1, c[r][1]);
      c[r][2] = _mm512_fmadd_ps(a, b2, c[r][2]);
      c[r][3] = _mm512_fmadd_ps(a, b3, c[r][3]);
    }
  }
  for (std::size_t r = 0; r < group_rows; ++r)
  {
    float* yr = y + r * padded;
    for (int j = 0; j < 4; ++j)
      _mm512_storeu_ps(yr + 16 * j, _mm512_add_ps(_mm512_loadu_ps(yr + 16 * j), c[r][j]));
  }
}

void projectAvx2(const float* x, std::size_t rows, std::size_t inputs, const float* pt, std::size_t padded, float* y)
{
  projectTiles<16>(x, rows, inputs, pt, padded, y, microAvx2);
}

void projectAvx512(const float* x, std::size_t rows, std::size_t inputs, const float* pt, std::size_t padded, float* y)
{
  projectTiles<64>(x, rows, inputs, pt, padded, y, microAvx512);
}

bool available(ProjectionPath path)
{
  const auto& cpu = biovision_common::CpuFeatures::host();
  switch (path)
  {
    case ProjectionPath::Generic:
      return true;
    case ProjectionPath::Avx2:
      return cpu.avx2 && cpu.fma;
    case ProjectionPath::Avx512:
      return cpu.avx512f;
  }
  return false;
}
}  // namespace

std::string toString(ProjectionPath path)
{
  switch (path)
  {
    case ProjectionPath::Generic:
      return "generic";
    case ProjectionPath::Avx2:
      return "avx2";
    case ProjectionPath::Avx512:
      return "avx512";
  }
  return "unknown";
}

std::vector<ProjectionPath> availableProjectionPaths()
{
  std::vector<ProjectionPath> paths;
  for (ProjectionPath p : {ProjectionPath::Generic, ProjectionPath::Avx2, ProjectionPath::Avx512})
    if (available(p))
      paths.push_back(p);
  return paths;
}

ProjectionPath bestProjectionPath()
{
  static const ProjectionPath best = availableProjectionPaths().back();
  return best;
}

PackedProjection::PackedProjection(const float* p, std::size_t outputs, std::size_t inputs)
  : inputs_(inputs), outputs_(outputs)
{
  if (outputs == 0 || inputs == 0 || p == nullptr)
    throw std::invalid_argument("PackedProjection: empty projection (outputs and inputs must be > 0)");
  padded_outputs_ = (outputs + kOutputAlignment - 1) / kOutputAlignment * kOutputAlignment;
  transposed_.assign(inputs * padded_outputs_, 0.f);
  for (std::size_t b = 0; b < outputs; ++b)
    for (std::size_t k = 0; k < inputs; ++k)
      transposed_[k * padded_outputs_ + b] = p[b * inputs + k];
}

void PackedProjection::project(const float* x, std::size_t rows, float* y, ProjectionPath path) const
{
  if (!available(path))
    throw std::invalid_argument("PackedProjection: path " + toString(path) + " is not available on this CPU");
  if (rows == 0)
    return;
  if (transposed_.empty())
    throw std::invalid_argument("PackedProjection: no projection (default-constructed)");
  if (path == ProjectionPath::Generic)
  {
    std::vector<float> padded_y(rows * padded_outputs_);
    projectGeneric(x, rows, inputs_, transposed_.data(), padded_outputs_, padded_y.data());
    for (std::size_t r = 0; r < rows; ++r)
      std::memcpy(y + r * outputs_, padded_y.data() + r * padded_outputs_, outputs_ * sizeof(float));
    return;
  }
  const auto kernel = path == ProjectionPath::Avx512 ? projectAvx512 : projectAvx2;
  const int tasks = static_cast<int>((rows + kRowsPerTask - 1) / kRowsPerTask);
  cv::parallel_for_(cv::Range(0, tasks), [&](const cv::Range& range) {
    std::vector<float> block(kRowsPerTask * padded_outputs_);  // padded rows, then the real columns out
    for (int t = range.start; t < range.end; ++t)
    {
      const std::size_t first = t * kRowsPerTask, n = std::min(kRowsPerTask, rows - first);
      kernel(x + first * inputs_, n, inputs_, transposed_.data(), padded_outputs_, block.data());
      for (std::size_t r = 0; r < n; ++r)
        std::memcpy(y + (first + r) * outputs_, block.data() + r * padded_outputs_, outputs_ * sizeof(float));
    }
  });
}
}  // namespace biovision_recognition
