// SourceSplit: no source in both parts, whatever the order or company it comes in.
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_common/eval/source_split.hpp"

using biovision_common::SourceSplit;

namespace
{
std::vector<std::string> names(int n, const std::string& prefix)
{
  std::vector<std::string> v;
  for (int i = 0; i < n; ++i)
    v.push_back(prefix + std::to_string(i));
  return v;
}
}  // namespace

TEST(SourceSplit, NoSourceInBoth)
{
  const SourceSplit split("test-salt", 0.5);
  // Views of the same scene come under differently-cased names: still one source, one part.
  std::vector<std::string> views;
  for (const auto& s : names(200, "Scene"))
    for (const auto& variant : {s, " " + s, std::string(s).append("\t")})
    {
      std::string lower = variant;
      std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
      views.push_back(variant);
      views.push_back(lower);
    }
  std::set<std::string> dev, test;
  for (const auto& v : views)
    (split.isTest(v) ? test : dev).insert(SourceSplit::key(v));
  for (const auto& k : dev)
    EXPECT_EQ(test.count(k), 0u) << k << " is in both parts";
  EXPECT_EQ(dev.size() + test.size(), 200u);
  const auto d = split.describe(views);
  for (const auto& s : d["dev"])
    for (const auto& t : d["test"])
      EXPECT_NE(SourceSplit::key(s.get<std::string>()), SourceSplit::key(t.get<std::string>()));
}

TEST(SourceSplit, PartDependsOnlyOnTheSourceAndSalt)
{
  const SourceSplit a("salt", 0.3), b("salt", 0.3), other("another-salt", 0.3);
  int differ = 0;
  for (const auto& s : names(300, "img"))
  {
    EXPECT_EQ(a.part(s), b.part(s));
    differ += a.part(s) != other.part(s);
  }
  EXPECT_GT(differ, 30);  // the salt really picks another split
  // Shuffled input order and added sources change nothing for the existing ones.
  auto list = names(50, "img");
  const auto folds = a.balancedFolds(list, 5);
  std::reverse(list.begin(), list.end());
  const auto reversed = a.balancedFolds(list, 5);
  for (size_t i = 0; i < list.size(); ++i)
    EXPECT_EQ(folds[list.size() - 1 - i], reversed[i]);
}

TEST(SourceSplit, FractionAndForcedTest)
{
  const SourceSplit split("fraction", 0.25, {"Aloe"});
  int test = 0;
  const auto list = names(4000, "s");
  for (const auto& s : list)
    test += split.isTest(s);
  EXPECT_NEAR(test / 4000.0, 0.25, 0.03);
  EXPECT_TRUE(split.isTest("aloe"));
  EXPECT_TRUE(split.isTest("ALOE"));
  EXPECT_TRUE(SourceSplit("none", 0.0, {"aloe"}).isTest("Aloe"));
  EXPECT_FALSE(SourceSplit("none", 0.0).isTest("Aloe"));
  EXPECT_TRUE(SourceSplit("all", 1.0).isTest("anything"));
  EXPECT_THROW(SourceSplit("bad", 1.5), std::invalid_argument);
}

TEST(SourceSplit, FoldsPartitionTheDevSourcesOnly)
{
  const SourceSplit split("folds", 0.5);
  auto list = names(61, "p");
  list.push_back("P3");  // a second view of p3: same fold
  const auto folds = split.balancedFolds(list, 5);
  std::vector<int> size(5, 0);
  for (size_t i = 0; i + 1 < list.size(); ++i)
  {
    if (split.isTest(list[i]))
    {
      EXPECT_EQ(folds[i], -1) << list[i];
      EXPECT_THROW(split.fold(list[i], 5), std::invalid_argument);
      continue;
    }
    ASSERT_GE(folds[i], 0);
    ASSERT_LT(folds[i], 5);
    ++size[folds[i]];
    const int f = split.fold(list[i], 5);
    EXPECT_GE(f, 0);
    EXPECT_LT(f, 5);
  }
  EXPECT_EQ(folds.back(), folds[3]);
  const auto [lo, hi] = std::minmax_element(size.begin(), size.end());
  EXPECT_LE(*hi - *lo, 1);
  EXPECT_GT(*lo, 0);
  EXPECT_THROW(split.balancedFolds(list, 1), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
