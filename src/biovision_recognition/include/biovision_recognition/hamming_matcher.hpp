#pragma once

#include <cstdint>
#include <vector>

#include "biovision_recognition/binary_code_set.hpp"
#include "biovision_common/hamming_distance.hpp"

namespace biovision_recognition
{
// The Hamming kernel lives in biovision_common; its path type is part of this API.
using biovision_common::availableHammingPaths;
using biovision_common::bestHammingPath;
using biovision_common::hammingDistanceReference;
using biovision_common::hammingDistances;
using biovision_common::HammingPath;
using biovision_common::toString;

/// One query-to-library match.
struct HammingMatch
{
  uint32_t query = 0;
  uint32_t train = 0;
  uint16_t distance = 0;
};

/// Brute-force Hamming matching: k nearest neighbours or all within a radius, multi-threaded over the
/// queries, with the library streamed in cache-sized blocks through the fastest kernel the CPU has.
class HammingMatcher
{
public:
  /// threads: worker threads (>= 1); path: kernel, default the best available.
  explicit HammingMatcher(int threads = 1, HammingPath path = bestHammingPath());

  /// Per query, its k nearest library codes, nearest first (ties: lower index first). Fewer than k
  /// when the library is smaller.
  std::vector<std::vector<HammingMatch>> knnMatch(const BinaryCodeSet& queries, const BinaryCodeSet& library,
                                                  int k) const;
  /// Per query, every library code with distance <= radius, nearest first.
  std::vector<std::vector<HammingMatch>> radiusMatch(const BinaryCodeSet& queries, const BinaryCodeSet& library,
                                                     int radius) const;

  int threads() const { return threads_; }
  HammingPath path() const { return path_; }

private:
  template <typename PerQuery>
  void forEachQueryBlock(size_t queries, PerQuery&& per_block) const;

  int threads_;
  HammingPath path_;
};
}  // namespace biovision_recognition
