#include "biovision_stereo/cost_simd.hpp"

#include <algorithm>
#include <stdexcept>

#include "biovision_common/cpu_features.hpp"

namespace biovision_stereo
{
CostSimd bestCostSimd()
{
  return availableCostSimds().back();
}

std::vector<CostSimd> availableCostSimds()
{
  const auto& cpu = biovision_common::CpuFeatures::host();
  std::vector<CostSimd> simds{CostSimd::kGeneric};
  if (cpu.avx2)
    simds.push_back(CostSimd::kAvx2);
  if (cpu.avx2 && cpu.avx512f && cpu.avx512bw)
    simds.push_back(CostSimd::kAvx512);
  return simds;
}

std::string costSimdName(CostSimd simd)
{
  switch (simd)
  {
    case CostSimd::kAvx512:
      return "avx512";
    case CostSimd::kAvx2:
      return "avx2";
    default:
      return "generic";
  }
}

void requireCostSimd(CostSimd simd)
{
  const auto simds = availableCostSimds();
  if (std::find(simds.begin(), simds.end(), simd) == simds.end())
    throw std::invalid_argument("BioBin: the " + costSimdName(simd) + " cost path needs a CPU with " +
                                (simd == CostSimd::kAvx512 ? "AVX-512F and AVX-512BW" : "AVX2"));
}
}  // namespace biovision_stereo
