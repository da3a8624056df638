#include "biovision_stereo/cost_simd.hpp"

#include <stdexcept>

#include "biovision_common/cpu_features.hpp"

namespace biovision_stereo
{
CostSimd bestCostSimd()
{
  return biovision_common::CpuFeatures::host().avx2 ? CostSimd::kAvx2 : CostSimd::kGeneric;
}

std::string costSimdName(CostSimd simd)
{
  return simd == CostSimd::kAvx2 ? "avx2" : "generic";
}

void requireCostSimd(CostSimd simd)
{
  if (simd == CostSimd::kAvx2 && !biovision_common::CpuFeatures::host().avx2)
    throw std::invalid_argument("BioBin: the AVX2 cost path needs a CPU with AVX2");
}
}  // namespace biovision_stereo
