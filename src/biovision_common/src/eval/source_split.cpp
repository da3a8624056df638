#include "biovision_common/eval/source_split.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <stdexcept>

namespace biovision_common
{
SourceSplit::SourceSplit(std::string salt, double test_fraction, std::vector<std::string> forced_test)
  : salt_(std::move(salt)), test_fraction_(test_fraction)
{
  if (!(test_fraction >= 0.0 && test_fraction <= 1.0))
    throw std::invalid_argument("SourceSplit: test_fraction outside [0, 1]");
  for (const auto& s : forced_test)
    forced_test_.push_back(key(s));
}

std::string SourceSplit::key(const std::string& source)
{
  const auto first = source.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    return std::string();
  const auto last = source.find_last_not_of(" \t\r\n");
  std::string k = source.substr(first, last - first + 1);
  std::transform(k.begin(), k.end(), k.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return k;
}

double SourceSplit::unit(const std::string& source, const std::string& purpose) const
{
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  for (unsigned char c : salt_ + "/" + purpose + "/" + key(source))
  {
    h ^= c;
    h *= 1099511628211ull;
  }
  h ^= h >> 33;  // finaliser: FNV's high bits alone mix short keys poorly
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return static_cast<double>(h >> 11) / 9007199254740992.0;  // 53 bits / 2^53
}

SourceSplit::Part SourceSplit::part(const std::string& source) const
{
  const std::string k = key(source);
  if (std::find(forced_test_.begin(), forced_test_.end(), k) != forced_test_.end())
    return Part::test;
  return unit(k, "part") < test_fraction_ ? Part::test : Part::dev;
}

int SourceSplit::fold(const std::string& source, int folds) const
{
  if (folds < 2)
    throw std::invalid_argument("SourceSplit: folds must be >= 2");
  if (isTest(source))
    throw std::invalid_argument("SourceSplit: test source '" + source + "' has no fold");
  return std::min(folds - 1, static_cast<int>(unit(source, "fold") * folds));
}

std::vector<int> SourceSplit::balancedFolds(const std::vector<std::string>& sources, int folds) const
{
  if (folds < 2)
    throw std::invalid_argument("SourceSplit: folds must be >= 2");
  // Distinct dev keys (a source named twice, e.g. two views, is dealt once), in hash order.
  std::vector<std::string> keys;
  for (const auto& s : sources)
    if (isDev(s) && std::find(keys.begin(), keys.end(), key(s)) == keys.end())
      keys.push_back(key(s));
  std::sort(keys.begin(), keys.end(), [&](const std::string& a, const std::string& b) {
    const double ua = unit(a, "fold"), ub = unit(b, "fold");
    return ua != ub ? ua < ub : a < b;
  });
  std::vector<int> out(sources.size(), -1);
  for (size_t i = 0; i < sources.size(); ++i)
  {
    const auto at = std::find(keys.begin(), keys.end(), key(sources[i]));
    if (at != keys.end())
      out[i] = static_cast<int>((at - keys.begin()) % folds);
  }
  return out;
}

nlohmann::ordered_json SourceSplit::describe(const std::vector<std::string>& sources) const
{
  nlohmann::ordered_json j;
  j["by"] = "source";
  j["salt"] = salt_;
  j["test_fraction"] = test_fraction_;
  j["forced_test"] = forced_test_;
  std::vector<std::string> dev, test;
  for (const auto& s : sources)
  {
    auto& list = isTest(s) ? test : dev;
    if (std::find(list.begin(), list.end(), s) == list.end())
      list.push_back(s);
  }
  j["dev"] = dev;
  j["test"] = test;
  return j;
}
}  // namespace biovision_common
