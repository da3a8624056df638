#pragma once

#include <string>
#include <vector>

namespace biovision_stereo
{
/// Instruction set of BioBin's cost-volume loops (colour-masked costs, DoG along disparity, coarse-to-fine
/// fusion, the iterative spatial filter; issue 21 item 3). kGeneric is the compiler's baseline (x86-64:
/// SSE2) and the fallback on every CPU; kAvx2 and kAvx512 are the same C++ compiled for AVX2 and for
/// AVX-512F/BW with 512-bit vectors, without FMA (the library builds with -ffp-contract=off), so every value
/// is bit for bit the generic path's (no contraction, no reassociation: test_stereo_core checks equality).
enum class CostSimd
{
  kGeneric,
  kAvx2,
  kAvx512
};

/// The fastest path this CPU runs (AVX-512 with F and BW, else AVX2, else generic).
CostSimd bestCostSimd();
/// Every path this CPU runs, generic first (the tests compare each with it).
std::vector<CostSimd> availableCostSimds();
/// "generic", "avx2" or "avx512" (benchmarks report which path ran).
std::string costSimdName(CostSimd simd);
/// Throws std::invalid_argument when `simd` needs an instruction set this CPU lacks.
void requireCostSimd(CostSimd simd);
}  // namespace biovision_stereo
