#include "biovision_recognition/hamming_matcher.hpp"

#include <emmintrin.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace biovision_recognition
{
namespace
{
// Library codes per block: 1024 x 128 bits = 16 KiB stays in L1 while a query batch runs over it.
constexpr size_t kBlock = 1024;
// Queries per batch sharing one library block: the library is streamed from memory once per batch, so
// a large batch keeps the matcher compute-bound (with 16 it was bound by the shared L3/DRAM bandwidth,
// measured: 2 threads no faster than 1).
constexpr size_t kQueryBatch = 256;

void checkCompatible(const BinaryCodeSet& queries, const BinaryCodeSet& library)
{
  if (queries.words() != library.words())
    throw std::invalid_argument("HammingMatcher: query and library codes differ in length");
}

bool nearer(const HammingMatch& a, const HammingMatch& b)
{
  return a.distance != b.distance ? a.distance < b.distance : a.train < b.train;
}
}  // namespace

HammingMatcher::HammingMatcher(int threads, HammingPath path) : threads_(std::max(1, threads)), path_(path)
{
}

template <typename PerQuery>
void HammingMatcher::forEachQueryBlock(size_t queries, PerQuery&& per_block) const
{
  const size_t workers = std::min<size_t>(threads_, std::max<size_t>(1, queries / 16));
  if (workers <= 1)
  {
    per_block(size_t(0), queries);
    return;
  }
  std::vector<std::thread> pool;
  const size_t chunk = (queries + workers - 1) / workers;
  for (size_t w = 0; w < workers; ++w)
  {
    const size_t begin = w * chunk, end = std::min(queries, begin + chunk);
    if (begin < end)
      pool.emplace_back([&per_block, begin, end] { per_block(begin, end); });
  }
  for (auto& t : pool)
    t.join();
}

std::vector<std::vector<HammingMatch>> HammingMatcher::knnMatch(const BinaryCodeSet& queries,
                                                                const BinaryCodeSet& library, int k) const
{
  checkCompatible(queries, library);
  if (k < 1)
    throw std::invalid_argument("HammingMatcher::knnMatch: k must be >= 1");
  std::vector<std::vector<HammingMatch>> result(queries.size());
  const int words = library.words();
  forEachQueryBlock(queries.size(), [&](size_t begin, size_t end) {
    std::vector<uint16_t> distances(kBlock);
    for (size_t q0 = begin; q0 < end; q0 += kQueryBatch)
    {
      const size_t q1 = std::min(end, q0 + kQueryBatch);
      // Per query: the current k best, sorted, and the distance a candidate must beat.
      std::vector<std::vector<HammingMatch>> best(q1 - q0);
      std::vector<int> worst(q1 - q0, 1 << 20);
      for (size_t t0 = 0; t0 < library.size(); t0 += kBlock)
      {
        const size_t n = std::min(kBlock, library.size() - t0);
        for (size_t q = q0; q < q1; ++q)
        {
          hammingDistances(path_, queries.code(q), library.code(t0), n, words, distances.data());
          auto& list = best[q - q0];
          int& bound = worst[q - q0];
          auto consider = [&](size_t i) {
            if (distances[i] >= bound)
              return;
            const HammingMatch m{static_cast<uint32_t>(q), static_cast<uint32_t>(t0 + i), distances[i]};
            list.insert(std::upper_bound(list.begin(), list.end(), m, nearer), m);
            if (static_cast<int>(list.size()) > k)
              list.pop_back();
            if (static_cast<int>(list.size()) == k)
              bound = list.back().distance;
          };
          // Eight distances per SSE2 compare (baseline x86-64): almost every group holds no candidate
          // once the k best are found, and skipping it costs one compare instead of eight branches.
          size_t i = 0;
          for (; i + 8 <= n; i += 8)
          {
            const __m128i d = _mm_loadu_si128(reinterpret_cast<const __m128i*>(distances.data() + i));
            if (_mm_movemask_epi8(_mm_cmplt_epi16(d, _mm_set1_epi16(static_cast<short>(std::min(bound, 32767))))) == 0)
              continue;
            for (size_t j = i; j < i + 8; ++j)
              consider(j);
          }
          for (; i < n; ++i)
            consider(i);
        }
      }
      for (size_t q = q0; q < q1; ++q)
        result[q] = std::move(best[q - q0]);
    }
  });
  return result;
}

std::vector<std::vector<HammingMatch>> HammingMatcher::radiusMatch(const BinaryCodeSet& queries,
                                                                   const BinaryCodeSet& library, int radius) const
{
  checkCompatible(queries, library);
  std::vector<std::vector<HammingMatch>> result(queries.size());
  const int words = library.words();
  forEachQueryBlock(queries.size(), [&](size_t begin, size_t end) {
    std::vector<uint16_t> distances(kBlock);
    for (size_t t0 = 0; t0 < library.size(); t0 += kBlock)
    {
      const size_t n = std::min(kBlock, library.size() - t0);
      for (size_t q = begin; q < end; ++q)
      {
        hammingDistances(path_, queries.code(q), library.code(t0), n, words, distances.data());
        const __m128i limit = _mm_set1_epi16(static_cast<short>(std::min(radius, 32766) + 1));
        size_t i = 0;
        for (; i + 8 <= n; i += 8)  // as in knnMatch: one compare skips eight non-candidates
        {
          const __m128i d = _mm_loadu_si128(reinterpret_cast<const __m128i*>(distances.data() + i));
          if (_mm_movemask_epi8(_mm_cmplt_epi16(d, limit)) == 0)
            continue;
          for (size_t j = i; j < i + 8; ++j)
            if (distances[j] <= radius)
              result[q].push_back({static_cast<uint32_t>(q), static_cast<uint32_t>(t0 + j), distances[j]});
        }
        for (; i < n; ++i)
          if (distances[i] <= radius)
            result[q].push_back({static_cast<uint32_t>(q), static_cast<uint32_t>(t0 + i), distances[i]});
      }
    }
    for (size_t q = begin; q < end; ++q)
      std::sort(result[q].begin(), result[q].end(), nearer);
  });
  return result;
}
}  // namespace biovision_recognition
