#pragma once

#include <string>

namespace biovision_common
{
/// The instruction-set extensions the SIMD paths of BioVision dispatch on, read once from CPUID at run
/// time, so one binary runs everywhere (no -march=native) and benchmarks can say which path ran.
struct CpuFeatures
{
  bool popcnt = false;
  bool avx2 = false;
  bool fma = false;
  bool avx512f = false;
  bool avx512bw = false;
  bool avx512vpopcntdq = false;

  /// This CPU's features (detected on the first call; thread-safe).
  static const CpuFeatures& host();
  /// "popcnt avx2 fma ..." — the features present, for logs and benchmark reports.
  std::string describe() const;
};
}  // namespace biovision_common
