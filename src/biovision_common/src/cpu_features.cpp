#include "biovision_common/cpu_features.hpp"

namespace biovision_common
{
const CpuFeatures& CpuFeatures::host()
{
  static const CpuFeatures features = [] {
    CpuFeatures f;
    __builtin_cpu_init();
    f.popcnt = __builtin_cpu_supports("popcnt");
    f.avx2 = __builtin_cpu_supports("avx2");
    f.fma = __builtin_cpu_supports("fma");
    f.avx512f = __builtin_cpu_supports("avx512f");
    f.avx512bw = __builtin_cpu_supports("avx512bw");
    f.avx512vpopcntdq = __builtin_cpu_supports("avx512vpopcntdq");
    return f;
  }();
  return features;
}

std::string CpuFeatures::describe() const
{
  std::string s;
  const std::pair<bool, const char*> names[] = {{popcnt, "popcnt"},     {avx2, "avx2"},
                                                {fma, "fma"},           {avx512f, "avx512f"},
                                                {avx512bw, "avx512bw"}, {avx512vpopcntdq, "avx512vpopcntdq"}};
  for (const auto& [present, name] : names)
    if (present)
      s += (s.empty() ? "" : " ") + std::string(name);
  return s.empty() ? "baseline x86-64" : s;
}
}  // namespace biovision_common
