#pragma once

#include <string>
#include <vector>

#include "biovision_hri/feature_layout.hpp"

namespace biovision_hri
{
/// A trained linear window classifier: score = w . x + bias over FeatureLayout features (thesis §2.3,
/// LIBLINEAR). Stored as a biovision_common::StoredFile ("BVHRIDET", version 2 (v1 lacked grid_step): magic, version,
/// byte-order mark, size, CRC-32; written atomically), so a truncated, corrupt, foreign or other-version
/// file is refused instead of silently scoring garbage.
struct LinearDetectorModel
{
  std::string kind;            ///< "face" or "hand"
  FeatureLayout layout;        ///< the features the weights read
  std::vector<float> weights;  ///< w, layout.featureCount() values, in FeatureLayout's order
  float bias = 0.f;            ///< b (LIBLINEAR's w_{n+1} * bias term)
  std::string provenance;      ///< the training command, data split and date

  /// Throws std::invalid_argument when the kind is empty, the layout invalid, the weight count differs
  /// from layout.featureCount() or a value is not finite.
  void validate() const;
  /// w . x + b for one feature vector of layout.featureCount() values.
  float score(const float* features) const;
  void save(const std::string& path) const;
  /// Throws biovision_common::StoredFileError for a missing, foreign, corrupt, truncated, other-version
  /// or inconsistent file.
  static LinearDetectorModel load(const std::string& path);
};
}  // namespace biovision_hri
