#pragma once

#include <string>

namespace biovision_stereo
{
/// Instruction set of BioBin's cost-volume loops (colour-masked costs, DoG along disparity, coarse-to-fine
/// fusion; issue 21 item 3). kGeneric is the compiler's baseline (x86-64: SSE2) and the fallback on every
/// CPU; kAvx2 is the same C++ compiled for AVX2 (twice the vector width) without FMA, so every value is
/// bit for bit the generic path's (no contraction, no reassociation: test_stereo_core checks equality).
enum class CostSimd
{
  kGeneric,
  kAvx2
};

/// The fastest path this CPU runs (AVX2 when present).
CostSimd bestCostSimd();
/// "generic" or "avx2" (benchmarks report which path ran).
std::string costSimdName(CostSimd simd);
/// Throws std::invalid_argument when `simd` needs an instruction set this CPU lacks.
void requireCostSimd(CostSimd simd);
}  // namespace biovision_stereo
