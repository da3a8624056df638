#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace biovision_common
{
/// Train/validation ("dev") and untouched ("test") parts of a data set, split by image *source*: a
/// whole scene, sequence, object or independent photograph is in one part, never in both, so no
/// image of a test source (nor a second view of it) reaches tuning or training.
///
/// A source's part depends only on its key and the split's salt (FNV-1a hash of "salt/key" below
/// test_fraction), not on which other sources exist: adding a data set never moves a test source
/// into dev. Keys are compared lower-case ("Venus" of Middlebury stereo and "venus" of Middlebury
/// flow are one scene). Sources named in `forced_test` are test whatever their hash (e.g. scenes that
/// another evaluation ships, such as OpenCV's sample copy of Middlebury Aloe).
/// Within dev, fold() deals sources into k cross-validation folds, again by source.
class SourceSplit
{
public:
  enum class Part
  {
    dev,
    test
  };

  /// salt: names the split (one per tool); test_fraction in [0, 1]. Throws std::invalid_argument.
  SourceSplit(std::string salt, double test_fraction, std::vector<std::string> forced_test = {});

  /// The canonical key of a source name: lower case, surrounding blanks removed.
  static std::string key(const std::string& source);

  Part part(const std::string& source) const;
  bool isTest(const std::string& source) const { return part(source) == Part::test; }
  bool isDev(const std::string& source) const { return part(source) == Part::dev; }
  /// Cross-validation fold in [0, folds) of a dev source (deterministic, by source). Throws
  /// std::invalid_argument when folds < 2 or the source is a test source.
  int fold(const std::string& source, int folds) const;
  /// Dev sources dealt round-robin into `folds` folds in hash order: fold sizes differ by at most one.
  /// Returns, per source in `sources` order, its fold; -1 for test sources.
  std::vector<int> balancedFolds(const std::vector<std::string>& sources, int folds) const;

  /// {"salt", "test_fraction", "forced_test", "dev": [...], "test": [...]} over the given sources, for
  /// the tools' JSON: the split is written next to the figures it produced.
  nlohmann::ordered_json describe(const std::vector<std::string>& sources) const;

  const std::string& salt() const { return salt_; }
  double testFraction() const { return test_fraction_; }

private:
  /// Uniform in [0, 1) from the source key and the salt (FNV-1a 64).
  double unit(const std::string& source, const std::string& purpose) const;

  std::string salt_;
  double test_fraction_;
  std::vector<std::string> forced_test_;
};
}  // namespace biovision_common
