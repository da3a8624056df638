#pragma once

#include <cstdint>
#include <vector>

#include "biovision_recognition/binary_code_set.hpp"
#include "biovision_recognition/hamming_matcher.hpp"

namespace biovision_recognition
{
/// Exact radius search in a large code library by multi-index hashing (Norouzi, Punjani & Fleet 2012).
///
/// Each code is cut into m = bits / 16 substrings and each substring indexes a direct 65,536-bucket
/// table. By the pigeonhole principle a code within distance r of the query has at least one
/// substring within floor(r / m) of the query's, so only the buckets in those small Hamming balls are
/// visited (697 of 65,536 per table for r = 24 with 128 bits) and the candidates verified with the full
/// distance. The result equals brute-force radiusMatch; it is faster only where few buckets are
/// visited (small radius relative to the code length, large library: candidateFraction()).
/// radiusSearch() is not thread-safe (it reuses visit stamps): one index per thread.
class MultiIndexHash
{
public:
  MultiIndexHash() = default;
  explicit MultiIndexHash(const BinaryCodeSet& library) { build(library); }

  void build(const BinaryCodeSet& library);
  /// Every library code within `radius` of the query, nearest first (HammingMatch::query = 0).
  std::vector<HammingMatch> radiusSearch(const uint64_t* query, int radius) const;
  size_t size() const { return library_.size(); }
  /// Fraction of the library a radius search verifies when codes are uniform: m * |16-bit ball of
  /// radius floor(r / m)| / 65536. Above a few percent SIMD brute force is faster (see matcher_bench):
  /// at r = 24 of 128 bits it is 8.5%, at r = 8 it is 0.2%.
  double candidateFraction(int radius) const;

private:
  static constexpr int kSubstringBits = 16;
  uint16_t substring(const uint64_t* code, int s) const { return static_cast<uint16_t>(code[s / 4] >> (16 * (s % 4))); }
  const std::vector<uint16_t>& flipMasks(int radius) const;

  BinaryCodeSet library_;
  int substrings_ = 0;
  std::vector<std::vector<uint32_t>> offsets_;  // per table: bucket b holds ids [offsets[b], offsets[b + 1])
  std::vector<std::vector<uint32_t>> ids_;
  mutable std::vector<std::vector<uint16_t>> flip_masks_;  // by radius: every 16-bit mask with <= r ones
  mutable std::vector<uint32_t> seen_;                     // visit stamps, one per library code
  mutable uint32_t stamp_ = 0;
};
}  // namespace biovision_recognition
