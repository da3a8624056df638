#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_recognition
{
/// Geometric verification of descriptor matches (the source's proposed fix for look-alike logos): a
/// similarity transform (rotation, uniform scale, translation) fitted by RANSAC to the matched positions;
/// only matches that agree with it count. A random or scrambled match set has no consensus and fails.
/// The transform must also be plausible for an upright descriptor on a camera that does not roll: a
/// magnification in [min_scale, max_scale] and an in-plane rotation within max_rotation_degrees (true
/// matches of upright codes cannot be turned far; a chance consensus of look-alike texture can).
class GeometricVerifier
{
public:
  struct Parameters
  {
    double inlier_distance = 4.0;  ///< reprojection error of an inlier [px of the query image]. > 0
    int min_inliers = 5;           ///< the source's rule: at least 5 matches. >= 2
    double min_scale = 0.25;       ///< plausible template -> query magnification
    double max_scale = 4.0;
    double max_rotation_degrees = 30.0;  ///< |in-plane rotation| of the transform. (0, 180]
    int max_iterations = 500;
    double confidence = 0.995;
  };

  struct Result
  {
    bool accepted = false;
    int inliers = 0;
    cv::Matx23d transform = cv::Matx23d::eye();  ///< template -> query
    std::vector<uint8_t> inlier_mask;            ///< per match
  };

  GeometricVerifier() = default;
  explicit GeometricVerifier(const Parameters& parameters) : parameters_(parameters) {}

  /// template_points[i] matched query_points[i].
  Result verify(const std::vector<cv::Point2f>& template_points, const std::vector<cv::Point2f>& query_points) const;

  const Parameters& parameters() const { return parameters_; }

private:
  Parameters parameters_;
};
}  // namespace biovision_recognition
