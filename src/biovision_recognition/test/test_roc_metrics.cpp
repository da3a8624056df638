#include <gtest/gtest.h>

#include <vector>

#include "roc_metrics.hpp"

using namespace biovision_recognition;

TEST(RocMetrics, WithoutTiesBothReadingsAgree)
{
  std::vector<float> pos;
  for (int i = 1; i <= 20; ++i)
    pos.push_back(static_cast<float>(i));  // 95% recall: 19 of 20, threshold 19
  const std::vector<float> neg{0.5f, 10.5f, 18.5f, 19.5f, 25.f, 30.f, 40.f, 50.f};
  EXPECT_DOUBLE_EQ(fpr95AtThreshold(pos, neg), 3.0 / 8.0);
  EXPECT_DOUBLE_EQ(fpr95(pos, neg), 3.0 / 8.0);
}

TEST(RocMetrics, ATieAtTheThresholdIsSharedInProportion)
{
  // Every positive at distance 5: 95% recall takes 19 of the 20 tied positives, and with them the same
  // share of the 10 negatives tied at 5; the other 10 negatives are farther.
  const std::vector<float> pos(20, 5.f);
  std::vector<float> neg(10, 5.f);
  neg.insert(neg.end(), 10, 9.f);
  EXPECT_DOUBLE_EQ(fpr95AtThreshold(pos, neg), 0.5);
  EXPECT_DOUBLE_EQ(fpr95(pos, neg), 0.95 * 10 / 20);
  // Part of the positives below the tie: 15 at 1, 5 at 5 -> 4 of the 5 tied are needed (0.8 of the tie).
  std::vector<float> mixed(15, 1.f);
  mixed.insert(mixed.end(), 5, 5.f);
  EXPECT_DOUBLE_EQ(fpr95(mixed, neg), 0.8 * 10 / 20);
}

TEST(RocMetrics, RocAreaCountsTiesHalf)
{
  EXPECT_DOUBLE_EQ(rocArea({1.f, 1.f}, {2.f, 3.f}), 1.0);
  EXPECT_DOUBLE_EQ(rocArea({2.f}, {2.f}), 0.5);
  EXPECT_DOUBLE_EQ(rocArea({3.f}, {1.f, 2.f}), 0.0);
  EXPECT_DOUBLE_EQ(fpr95({}, {1.f}), 1.0);  // nothing to measure: the worst figure
}
