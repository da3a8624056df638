#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "biovision_common/bit_count.hpp"
#include "biovision_common/cpu_features.hpp"
#include "biovision_common/hamming_distance.hpp"

using namespace biovision_common;

namespace
{
std::vector<uint64_t> randomWords(size_t n, std::mt19937_64& rng)
{
  std::vector<uint64_t> w(n);
  for (auto& x : w)
    x = rng();
  return w;
}
}  // namespace

TEST(BitCount, EqualsTheCompilersPopcountOnRandomWords)
{
  std::mt19937_64 rng(11);
  EXPECT_EQ(countBits(0), 0);
  EXPECT_EQ(countBits(~0ULL), 64);
  for (int i = 0; i < 10000; ++i)
  {
    const uint64_t x = rng() & rng();  // also sparse words
    ASSERT_EQ(countBits(x), __builtin_popcountll(x)) << x;
  }
}

TEST(CpuFeatures, PathsFollowTheFeaturesAndTheDescriptionNamesThem)
{
  const CpuFeatures& f = CpuFeatures::host();
  const auto paths = availableHammingPaths();
  const bool has_avx512 = std::find(paths.begin(), paths.end(), HammingPath::Avx512) != paths.end();
  EXPECT_EQ(has_avx512, f.avx512f && f.avx512vpopcntdq && f.popcnt);
  EXPECT_EQ(std::find(paths.begin(), paths.end(), HammingPath::Popcnt) != paths.end(), f.popcnt);
  if (f.avx2)
  {
    EXPECT_NE(f.describe().find("avx2"), std::string::npos);  // braces: the macro ends in an if/else
  }
  EXPECT_FALSE(f.describe().empty());
}

TEST(HammingDistance, ReferenceCountsBits)
{
  const uint64_t a[2] = {0, 0}, b[2] = {0xFFFFFFFFFFFFFFFFULL, 0x5ULL};
  EXPECT_EQ(hammingDistanceReference(a, b, 2), 66);
  EXPECT_EQ(hammingDistanceReference(b, b, 2), 0);
}

TEST(HammingDistance, EveryAvailablePathEqualsTheScalarReference)
{
  std::mt19937_64 rng(3);
  const auto paths = availableHammingPaths();
  ASSERT_EQ(paths.front(), HammingPath::Scalar);
  for (int bits : {64, 128, 256, 512})
    for (size_t count : {size_t(1), size_t(7), size_t(8), size_t(16), size_t(33), size_t(47), size_t(1001)})
    {
      const int words = bits / 64;
      const std::vector<uint64_t> q = randomWords(words, rng), lib = randomWords(words * count, rng);
      std::vector<uint16_t> expected(count), got(count);
      for (size_t i = 0; i < count; ++i)
        expected[i] = static_cast<uint16_t>(hammingDistanceReference(q.data(), lib.data() + i * words, words));
      for (HammingPath p : paths)
      {
        std::fill(got.begin(), got.end(), 0xFFFF);
        hammingDistances(p, q.data(), lib.data(), count, words, got.data());
        EXPECT_EQ(got, expected) << toString(p) << " bits " << bits << " count " << count;
      }
    }
}

TEST(HammingDistance, EveryAvailablePairwisePathEqualsTheScalarReference)
{
  std::mt19937_64 rng(5);
  for (int bits : {64, 128, 256, 512})
    for (size_t count : {size_t(0), size_t(1), size_t(2), size_t(3), size_t(4), size_t(5), size_t(6), size_t(7),
                         size_t(8), size_t(9), size_t(13), size_t(16), size_t(45), size_t(451)})
    {
      const int words = bits / 64;
      std::vector<uint64_t> a = randomWords(words * count, rng), b = randomWords(words * count, rng);
      if (count > 2)
      {
        std::fill(b.begin(), b.begin() + words, 0);  // the extremes: nothing and every bit differs
        std::fill(a.begin(), a.begin() + words, 0);
        for (int w = 0; w < words; ++w)
          b[words + w] = ~a[words + w];
      }
      std::vector<uint16_t> expected(count), got(count);
      for (size_t i = 0; i < count; ++i)
        expected[i] = static_cast<uint16_t>(
            hammingDistanceReference(a.data() + i * words, b.data() + i * words, words));
      for (HammingPath p : availableHammingPaths())
      {
        std::fill(got.begin(), got.end(), 0xFFFF);
        hammingDistancesPairwise(p, a.data(), b.data(), count, words, got.data());
        EXPECT_EQ(got, expected) << toString(p) << " bits " << bits << " count " << count;
        std::vector<float> as_float(count, -1.f);
        hammingDistancesPairwise(p, a.data(), b.data(), count, words, as_float.data());
        for (size_t i = 0; i < count; ++i)
          ASSERT_EQ(as_float[i], float(expected[i])) << toString(p) << " bits " << bits << " float, code " << i;
      }
    }
  const uint64_t x[3] = {1, 2, 3};
  uint16_t out[1];
  EXPECT_THROW(hammingDistancesPairwise(HammingPath::Scalar, x, x, 1, 3, out), std::invalid_argument);
}

TEST(HammingDistance, RefusesUnsupportedLengths)
{
  const uint64_t a[3] = {1, 2, 3};
  uint16_t out[1];
  EXPECT_THROW(hammingDistances(HammingPath::Scalar, a, a, 1, 3, out), std::invalid_argument);
}
