#pragma once

#include <cstdint>

#include "biovision_stereo/pixel_descriptor.hpp"

namespace biovision_stereo
{
/// Hamming distance of 256-bit descriptors. The POPCNT instruction is used when the CPU has it
/// (checked once at run time, so the binary stays portable without -march=native).
class Hamming
{
public:
  /// Row of costs: out[x] = distance(a[x], b[x - shift]) for x >= shift, `missing` for x < shift.
  static void row(const PixelDescriptor* a, const PixelDescriptor* b, int width, int shift, float missing, float* out);
  static int distance(const PixelDescriptor& a, const PixelDescriptor& b);
  /// Portable bit-counting reference (no POPCNT): for tests.
  static int distanceScalar(const PixelDescriptor& a, const PixelDescriptor& b);
  /// True when the POPCNT path is in use.
  static bool usesPopcnt();
};
}  // namespace biovision_stereo
