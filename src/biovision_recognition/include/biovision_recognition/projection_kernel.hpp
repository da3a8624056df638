#pragma once

#include <cstddef>

namespace biovision_recognition
{
/// y (rows x outputs, row-major) = x (rows x inputs) * p^T, p being outputs x inputs, row-major: the
/// descriptor's projection P x for many keypoints at once.
///
/// Why not Eigen: built for the baseline x86-64 it uses SSE2 only, and the projection is most of a
/// descriptor's time (perf: ~55% of recognition). This kernel is compiled for AVX-512, AVX2+FMA and the
/// baseline and the CPU's best is picked at load time (GCC target_clones); it tiles the inputs so a
/// slice of P stays in L2 while every row of x passes over it; blocks of 64 rows run in parallel.
void projectRows(const float* x, size_t rows, size_t inputs, const float* p, size_t outputs, float* y);
}  // namespace biovision_recognition
