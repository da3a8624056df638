#pragma once

#include <cstdint>

namespace biovision_common
{
/// Number of set bits of a 64-bit word by SWAR arithmetic, without POPCNT: the portable reference every
/// SIMD bit-counting path is tested against, so it must not share code with them.
inline int countBits(uint64_t x)
{
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}
}  // namespace biovision_common
