#pragma once

#include <cstdint>
#include <string>

#include "biovision_common/hamming_distance.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"

namespace biovision_stereo
{
/// Hamming distance of 256-bit descriptors. The rows run on biovision_common's fastest Hamming path for this
/// CPU (AVX-512 VPOPCNTDQ, AVX2 nibble look-up, POPCNT or the scalar count; chosen once at run time, so the
/// binary stays portable without -march=native).
class Hamming
{
public:
  /// Row of costs: out[x] = distance(a[x], b[x - shift]) for x >= shift, `missing` for x < shift; a and b
  /// hold `width` descriptors, shift >= 0 (a disparity), width >= 0.
  /// Runs on bestHammingPath() unless `path` is given (benchmarks compare the paths); throws
  /// std::invalid_argument when this CPU cannot run `path`.
  static void row(const PixelDescriptor* a, const PixelDescriptor* b, int width, int shift, float missing, float* out,
                  biovision_common::HammingPath path = biovision_common::bestHammingPath());
  /// The same row of costs for image row y from the images' comparison bytes alone (no descriptor is
  /// formed): out[x] = distance(a.at(x, y), b.at(x - shift, y)) for x >= shift, `missing` below; exact.
  /// A descriptor's 256 bits are windows of its neighbours' comparison bytes, so its distance is a sum of
  /// per-byte bit counts over those windows: byte arithmetic instead of 256-bit codes (BioBin's cost rows
  /// run this, on its best CostSimd clone as here). a and b: one size, from compute() or computeComparisons(); throws std::invalid_argument
  /// otherwise or when y is outside them.
  static void windowRow(const PixelDescriptorImage& a, const PixelDescriptorImage& b, int y, int shift, float missing,
                        float* out);
  static int distance(const PixelDescriptor& a, const PixelDescriptor& b);
  /// Portable bit-counting reference (no POPCNT): for tests.
  static int distanceScalar(const PixelDescriptor& a, const PixelDescriptor& b);
  /// The path row() runs on ("avx512-vpopcntdq", "avx2", "popcnt" or "scalar"), for benchmark reports.
  static std::string pathName();
};
}  // namespace biovision_stereo
