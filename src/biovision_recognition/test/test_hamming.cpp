#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "biovision_recognition/hamming_matcher.hpp"
#include "biovision_recognition/multi_index_hash.hpp"

using namespace biovision_recognition;

namespace
{
BinaryCodeSet randomCodes(int bits, size_t n, std::mt19937_64& rng)
{
  BinaryCodeSet c(bits, n);
  for (size_t i = 0; i < n * c.words(); ++i)
    c.data()[i] = rng();
  return c;
}

/// Copies of `base` with a few bits flipped, so radius searches find something.
BinaryCodeSet nearCopies(const BinaryCodeSet& base, size_t n, int max_flips, std::mt19937_64& rng)
{
  BinaryCodeSet c(base.bits(), n);
  std::uniform_int_distribution<size_t> pick(0, base.size() - 1);
  std::uniform_int_distribution<int> flips(0, max_flips), bit(0, base.bits() - 1);
  for (size_t i = 0; i < n; ++i)
  {
    const size_t src = pick(rng);
    std::copy(base.code(src), base.code(src) + base.words(), c.code(i));
    for (int f = flips(rng); f > 0; --f)
    {
      const int b = bit(rng);
      c.setBit(i, b, !c.bit(i, b));
    }
  }
  return c;
}
}  // namespace

TEST(BinaryCodeSet, RefusesLengthsThatAreNotWholeWords)
{
  EXPECT_THROW(BinaryCodeSet(100), std::invalid_argument);
}

TEST(HammingMatcher, KnnEqualsSortedBruteForceOnEveryPathAndThreadCount)
{
  std::mt19937_64 rng(5);
  const BinaryCodeSet lib = randomCodes(128, 5000, rng);
  const BinaryCodeSet queries = nearCopies(lib, 200, 20, rng);
  for (HammingPath p : availableHammingPaths())
    for (int threads : {1, 2})
    {
      const auto result = HammingMatcher(threads, p).knnMatch(queries, lib, 3);
      ASSERT_EQ(result.size(), queries.size());
      for (size_t q = 0; q < queries.size(); q += 17)
      {
        std::vector<std::pair<int, uint32_t>> all;
        for (size_t t = 0; t < lib.size(); ++t)
          all.push_back({hammingDistanceReference(queries.code(q), lib.code(t), 2), static_cast<uint32_t>(t)});
        std::sort(all.begin(), all.end());
        ASSERT_EQ(result[q].size(), 3u);
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(result[q][k].distance, all[k].first);
          EXPECT_EQ(result[q][k].train, all[k].second);
          EXPECT_EQ(result[q][k].query, q);
        }
      }
    }
}

TEST(HammingMatcher, RadiusFindsExactlyTheCodesWithinIt)
{
  std::mt19937_64 rng(9);
  const BinaryCodeSet lib = randomCodes(128, 3000, rng);
  const BinaryCodeSet queries = nearCopies(lib, 100, 30, rng);
  const auto result = HammingMatcher(2).radiusMatch(queries, lib, 24);
  size_t found = 0;
  for (size_t q = 0; q < queries.size(); ++q)
  {
    size_t expected = 0;
    for (size_t t = 0; t < lib.size(); ++t)
      expected += hammingDistanceReference(queries.code(q), lib.code(t), 2) <= 24;
    EXPECT_EQ(result[q].size(), expected);
    EXPECT_TRUE(std::is_sorted(result[q].begin(), result[q].end(),
                               [](const HammingMatch& a, const HammingMatch& b) { return a.distance < b.distance; }));
    found += expected;
  }
  EXPECT_GT(found, 50u);  // the near copies are there
}

TEST(HammingMatcher, SmallLibraryGivesFewerThanK)
{
  std::mt19937_64 rng(1);
  const auto r = HammingMatcher().knnMatch(randomCodes(128, 2, rng), randomCodes(128, 1, rng), 2);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].size(), 1u);
  EXPECT_THROW(HammingMatcher().knnMatch(randomCodes(128, 1, rng), randomCodes(256, 1, rng), 1), std::invalid_argument);
}

TEST(MultiIndexHash, RadiusSearchEqualsBruteForce)
{
  std::mt19937_64 rng(11);
  for (int bits : {64, 128, 256})
  {
    const BinaryCodeSet lib = randomCodes(bits, 20000, rng);
    const BinaryCodeSet queries = nearCopies(lib, 60, bits / 5, rng);
    const MultiIndexHash index(lib);
    const HammingMatcher matcher(1);
    for (int radius : {0, 7, 24, bits / 4})
    {
      const auto brute = matcher.radiusMatch(queries, lib, radius);
      for (size_t q = 0; q < queries.size(); ++q)
      {
        const auto hits = index.radiusSearch(queries.code(q), radius);
        ASSERT_EQ(hits.size(), brute[q].size()) << "bits " << bits << " radius " << radius;
        for (size_t i = 0; i < hits.size(); ++i)
        {
          EXPECT_EQ(hits[i].train, brute[q][i].train);
          EXPECT_EQ(hits[i].distance, brute[q][i].distance);
        }
      }
    }
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
