#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace biovision_common
{
/// The instruction sets a Hamming distance can be computed with, slowest first.
enum class HammingPath
{
  Scalar,  ///< bit-twiddling count: the reference every other path is tested against
  Popcnt,  ///< one POPCNT per 64-bit word
  Avx2,    ///< nibble look-up with VPSHUFB, 256 bits at a time (Mula et al. 2018)
  Avx512,  ///< VPOPCNTQ (AVX-512 VPOPCNTDQ), 512 bits at a time
};

std::string toString(HammingPath path);
/// The paths this CPU can run, slowest first (Scalar is always there).
std::vector<HammingPath> availableHammingPaths();
/// The fastest available path, chosen once at run time from CPUID.
HammingPath bestHammingPath();

/// Distances from one code to `count` consecutive codes of `words` 64-bit words each (1, 2, 4 or 8).
/// out[i] = popcount(query XOR codes[i]). Throws std::invalid_argument when `path` is not available.
void hammingDistances(HammingPath path, const uint64_t* query, const uint64_t* codes, size_t count, int words,
                      uint16_t* out);

/// Element-wise distances of two runs of `count` codes of `words` 64-bit words each (1, 2, 4 or 8):
/// out[i] = popcount(a[i] XOR b[i]). BioBin's cost volume is this: one image row of 256-bit pixel descriptors
/// against the other row shifted by a disparity (thesis §4.4.2). The SIMD paths have a vector loop for 4-word
/// codes (8 codes per step, no scalar reduction); other lengths and the tail run the POPCNT loop.
/// Throws std::invalid_argument when `path` is not available or `words` is not one of the above.
void hammingDistancesPairwise(HammingPath path, const uint64_t* a, const uint64_t* b, size_t count, int words,
                              uint16_t* out);
/// The same counts written as floats (exact: at most 512), for a float cost volume without a conversion pass.
void hammingDistancesPairwise(HammingPath path, const uint64_t* a, const uint64_t* b, size_t count, int words,
                              float* out);

/// One distance, scalar reference.
int hammingDistanceReference(const uint64_t* a, const uint64_t* b, int words);
}  // namespace biovision_common
