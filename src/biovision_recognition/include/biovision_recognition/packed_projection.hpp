#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace biovision_recognition
{
/// The instruction sets PackedProjection runs on, slowest first.
enum class ProjectionPath
{
  Generic,  ///< Eigen's GEMM, built for the baseline x86-64 (SSE2): the reference the other paths are tested against
  Avx2,     ///< AVX2 + FMA: 6 rows x 16 outputs in 12 registers per step
  Avx512,   ///< AVX-512F: 6 rows x 64 outputs in 24 registers per step
};
std::string toString(ProjectionPath path);
/// The paths this CPU can run, slowest first (Generic is always there).
std::vector<ProjectionPath> availableProjectionPaths();
/// The fastest available path, chosen once at run time from CPUID (biovision_common::CpuFeatures).
ProjectionPath bestProjectionPath();

/// The descriptor's projection P (outputs x inputs, thesis ch. 3: the learned LDAHash matrix) stored
/// transposed, outputs padded to a multiple of 64, for y = x P^T over many keypoints at once.
///
/// Why its own kernels: the projection is most of a descriptor's time (P is 128 x 6418 for the committed
/// model: 0.8 M multiply-adds per keypoint) and Eigen, built for the baseline x86-64, uses SSE2 only (it is
/// the Generic path); the dot-product kernel before this one (4 rows x 4 outputs, reduced across lanes, GCC
/// target_clones) ran at 33 GFLOP/s on the AVX-512 EPYC here. With P transposed, each step broadcasts one input of 6 rows and
/// multiplies it into a whole vector of outputs, so the accumulators stay in registers with no reduction
/// (the register-blocked outer-product form of BLAS kernels), and the inputs are walked in chunks that
/// keep their slice of P in L2. The SIMD paths run row blocks in parallel (cv::parallel_for_); the Generic
/// path is one Eigen call (Eigen's own OpenMP threads; split into cv::parallel_for_ tasks it was slower).
class PackedProjection
{
public:
  PackedProjection() = default;
  /// p: outputs x inputs, row-major. Throws std::invalid_argument when outputs or inputs is 0.
  PackedProjection(const float* p, std::size_t outputs, std::size_t inputs);

  /// y (rows x outputs, row-major) = x (rows x inputs, row-major) P^T. Paths agree to float rounding
  /// (gtest). Throws std::invalid_argument when `path` is not available on this CPU.
  void project(const float* x, std::size_t rows, float* y, ProjectionPath path = bestProjectionPath()) const;

  std::size_t inputs() const { return inputs_; }
  std::size_t outputs() const { return outputs_; }

private:
  std::vector<float> transposed_;  ///< inputs x padded_outputs_, row-major; padding columns are 0
  std::size_t inputs_ = 0, outputs_ = 0, padded_outputs_ = 0;
};
}  // namespace biovision_recognition
