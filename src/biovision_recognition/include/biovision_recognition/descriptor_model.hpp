#pragma once

#include <string>

#include <Eigen/Core>

#include "biovision_recognition/descriptor_layout.hpp"

namespace biovision_recognition
{
/// The model the nodes, tools and tests load when none is named: a file of the package's models/ folder
/// (models/README.md gives its training command and figures). Named here only, so a switch is one line.
inline constexpr char kDefaultModelFile[] = "v1_ldahash_128.bin";

/// A trained binary descriptor: bit i = 1 where (P x)_i > t_i (thesis 3.3.3-3.3.4).
struct DescriptorModel
{
  using Projection = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  DescriptorLayout layout;
  Projection projection;       ///< P, bits x layout.featureCount()
  Eigen::VectorXf thresholds;  ///< t, one per bit
  std::string provenance;      ///< how it was trained (command line, data, date)

  int bits() const { return static_cast<int>(projection.rows()); }
  /// Identity of the trained model ("ldahash-<bits>-<crc32 of P and t>"): object memories record it.
  std::string id() const;
  /// Throws std::invalid_argument when sizes disagree or a value is not finite.
  void validate() const;

  /// Stored as a StoredFile ("BVLDAH", version 3: 2 added the phases, 3 the shape adaptation) with P in IEEE half precision: the 128-bit model is
  /// 1.6 MB instead of 3.3, and half precision moves (P x)_i by ~1e-3 of its spread (tested).
  void save(const std::string& path) const;
  /// Throws StoredFileError for a missing, foreign, corrupt, truncated or wrong-version file.
  static DescriptorModel load(const std::string& path);
};
}  // namespace biovision_recognition
